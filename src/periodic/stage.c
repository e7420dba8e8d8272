/* The problem at each value of the continuation parameter (continuation_impl.h): at a
 * speed, the caller's system and spec; at a model parameter, the caller's rebuild
 * (periodic.h); two stages kept so a step and its predecessor share factorisations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/periodic_impl.h"

void gd_per_stage_clear(stage *s)
{
    gd_transient_free(s->tr);
    free(s->loads);
    if (s->m) { /* parameter stages own their model */
        gd_transient_model_free(s->tm);
        gd_system_free(s->s);
        gd_model_free(s->m);
    }
    memset(s, 0, sizeof *s);
}

int gd_per_make_stage(ctx *c, stage *s, double key)
{
    gd_error err;
    s->valid = 1;
    s->key = key;
    const gd_system *sys = c->sys;
    const gd_transient_spec *spec = c->spec;
    double speed = key;
    if (c->param && c->param->load_frequency) {
        /* the caller's problem with its harmonic loads at this frequency */
        if (gd_per_frequency_spec(spec, key, &s->loads, &s->fspec, s->msg, sizeof s->msg)) {
            s->bad = 1;
            return 1;
        }
        spec = &s->fspec;
        speed = c->param->speed;
    } else if (c->param) {
        /* the caller rebuilds the problem at this value; the stage owns what it returns */
        const gd_periodic_param *p = c->param;
        gd_status st = p->rebuild ? p->rebuild(key, p->data, &s->m, &s->s, &s->tm, &err)
                                  : gd_error_set(&err, GD_EINPUT, "", 0, 0, "param", "",
                                                 "no rebuild function");
        if (!st && (!s->m || !s->s || !s->tm))
            st =
                gd_error_set(&err, GD_EINPUT, "", 0, 0, "param", "", "rebuild returned no problem");
        if (st) {
            s->bad = 1;
            snprintf(s->msg, sizeof s->msg, "%.60s = %.10g: %.220s", p->name ? p->name : "value",
                     key, err.message);
            return 1;
        }
        sys = s->s;
        spec = &s->tm->spec;
        speed = p->speed;
    }
    s->sys = sys;
    s->spec = spec;
    double w0;
    int order;
    if (gd_periodic_fundamental(sys, spec, speed, &w0, &order, &err)) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "%.300s", err.message);
        return 1;
    }
    if ((long)order * c->opt->subharmonic > c->H) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg,
                 "an excitation is harmonic %ld of the period (fundamental %.6g rad/s, "
                 "subharmonic %d) but H = %d: raise --harmonics",
                 (long)order * c->opt->subharmonic, w0 / c->opt->subharmonic, c->opt->subharmonic,
                 c->H);
        return 1;
    }
    s->w = w0 / c->opt->subharmonic;
    if (gd_transient_new(sys, spec, speed, &s->tr, &err)) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "%.300s", err.message);
        return 1;
    }
    if (gd_transient_terms(s->tr, NULL) < 0) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg,
                 "cam torques with include_acceleration are not supported by harmonic balance");
        return 1;
    }
    if (gd_transient_nstates(s->tr) / 2 != c->nf && c->nf) {
        s->bad = 1;
        snprintf(s->msg, sizeof s->msg, "the number of free DOFs changes with the parameter");
        return 1;
    }
    return 0;
}

/* The problem at parameter value key; NULL with c->reason set when it cannot be made. */
stage *gd_per_get_stage(ctx *c, double key)
{
    for (int i = 0; i < 2; i++)
        if (c->st[i].valid && c->st[i].key == key) {
            if (c->st[i].bad) {
                snprintf(c->reason, sizeof c->reason, "%.300s", c->st[i].msg);
                return NULL;
            }
            return &c->st[i];
        }
    stage *s = &c->st[c->next];
    c->next ^= 1;
    gd_per_stage_clear(s);
    s->id = ++c->serial;
    if (gd_per_make_stage(c, s, key)) {
        snprintf(c->reason, sizeof c->reason, "%.300s", s->msg);
        return NULL;
    }
    return s;
}

/* ---------------------------------------------------------------- Newton corrector */
