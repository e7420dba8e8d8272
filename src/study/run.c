/* Running cases: the case's overrides on the model parsed once (gd_model_source), the
 * system built, the analysis run and the outputs kept. A failed case is a row with its
 * status and message, never an error of the study. Many cases run over OpenMP, each on
 * its own model and system. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/static.h"
#include "geardyn/system.h"
#include "study/study_impl.h"

static gd_status run_analysis(const gd_study *s, const gd_load_options *opt, double *values,
                              gd_error *err)
{
    const gd_study_runner *a = s->analysis;
    gd_study_input in = {0};
    if (a->gear_pair) {
        gd_gear_pair_geometry g;
        gd_tvms_options t;
        gd_status st = gd_model_source_gear_pair(
            s->src, a->mesh_name ? a->mesh_name(s->opts) : NULL, opt, &g, &t, NULL, 0, err);
        if (st) return st;
        in.geom = &g;
        in.tvms = &t;
        return a->run(&in, s->opts, s->req, s->noutputs, values, err);
    }
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_status st = gd_model_source_model(s->src, opt, &m, err);
    if (!st) st = gd_system_build(m, &sys, err);
    if (!st && a->operating_speed && s->op_kind == GD_OPERATING_ZERO) {
        /* about q = 0, as the CLI's --operating-point zero (gd_cli_operating_apply) */
        if (sys->nlaws) st = gd_system_set_operating_point(sys, GD_OPERATING_ZERO, NULL, NULL, err);
    } else if (!st && a->operating_speed) {
        /* the laws linearised about the static equilibrium, as the CLI's analyses */
        double speed = a->operating_speed(s->opts);
        gd_static_options so;
        gd_static_options_init(&so);
        so.speed = speed;
        st = gd_static_operating_point(sys, &so, speed >= 0, err);
    }
    if (!st) {
        in.sys = sys;
        st = a->run(&in, s->opts, s->req, s->noutputs, values, err);
    }
    gd_system_free(sys);
    gd_model_free(m);
    return st;
}

void gd_study_run_case(const gd_study *s, size_t c, gd_study_row *row)
{
    row->index = c;
    row->status = GD_OK;
    row->message[0] = '\0';
    for (int o = 0; o < s->noutputs; o++)
        row->outputs[o] = NAN;
    gd_error err;
    gd_error_clear(&err);
    size_t width = 1024;
    char *buf = malloc((size_t)s->nparams * width);
    const char **set = malloc((size_t)s->nparams * sizeof *set);
    gd_status st = GD_ENOMEM;
    if (buf && set) {
        for (int p = 0; p < s->nparams; p++) {
            set[p] = buf + (size_t)p * width;
            gd_study_assignment(s, c, p, buf + (size_t)p * width, width);
        }
        gd_load_options opt = {s->nparams, set};
        st = run_analysis(s, &opt, row->outputs, &err);
    } else {
        gd_error_set(&err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    free(buf);
    free(set);
    if (!st) return;
    row->status = st;
    for (int o = 0; o < s->noutputs; o++)
        row->outputs[o] = NAN;
    gd_error_format(&err, row->message, sizeof row->message);
    /* one line in the table */
    size_t n = strlen(row->message);
    while (n && (row->message[n - 1] == '\n' || row->message[n - 1] == ' '))
        row->message[--n] = '\0';
    for (char *p = row->message; *p; p++)
        if (*p == '\n' || *p == '\r') *p = ' ';
}

gd_status gd_study_run(const gd_study *s, const size_t *cases, size_t n, int nthreads,
                       gd_study_sink sink, void *user, gd_error *err)
{
    int stop = 0, oom = 0;
    long count = (long)n;
#pragma omp parallel num_threads(nthreads > 0 ? nthreads : omp_get_max_threads())
    {
        gd_study_row row;
        int ok = gd_study_row_init(s, &row, NULL) == GD_OK;
        if (!ok) {
#pragma omp atomic write
            oom = 1;
        }
#pragma omp for schedule(dynamic, 1)
        for (long i = 0; i < count; i++) {
            int stopped;
#pragma omp atomic read
            stopped = stop;
            if (!ok || stopped) continue;
            gd_study_run_case(s, cases[i], &row);
#pragma omp critical
            {
                int again;
#pragma omp atomic read
                again = stop;
                if (!again && sink(user, &row)) {
#pragma omp atomic write
                    stop = 1;
                }
            }
        }
        gd_study_row_free(&row);
    }
    if (oom) return gd_error_set(err, GD_ENOMEM, s->file, 0, 0, "", "", "out of memory");
    return GD_OK;
}
