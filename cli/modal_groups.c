/* geardyn modal --group shaft: [JMSTHelical] Table 4 (strain energy per shaft, gears and
 * bearings included, the dominant shaft) and Table 7 (one shaft's energy by motion
 * type, "no-vibration" when the shaft stores none). */
#include "modal_groups.h"

#include <stdlib.h>

#include "cli.h"

/* Below this fraction of the mode's energy (0.0 % as printed) a shaft does not vibrate in
 * it: [JMSTHelical] Table 7 writes "No-vibration" where Table 4 has 0. */
#define GD_SHAFT_IDLE 5e-4

typedef struct shaft_split {
    int ns;
    double *t;     /* ns x GD_NMOTIONS */
    double *share; /* ns */
} shaft_split;

static int split(const gd_system *s, const gd_modal_result *r, int mode, shaft_split *sp)
{
    gd_error err;
    if (gd_modal_energy_by_shaft(s, r, mode, sp->t, &err)) return gd_cli_report(&err);
    for (int j = 0; j < sp->ns; j++) {
        sp->share[j] = 0;
        for (int k = 0; k < GD_NMOTIONS; k++)
            sp->share[j] += sp->t[j * GD_NMOTIONS + k];
    }
    return 0;
}

static int split_init(shaft_split *sp, const gd_system *s)
{
    sp->ns = s->model->nshafts;
    sp->t = malloc((size_t)sp->ns * GD_NMOTIONS * sizeof *sp->t);
    sp->share = malloc((size_t)sp->ns * sizeof *sp->share);
    if (sp->t && sp->share) return 0;
    free(sp->t);
    free(sp->share);
    gd_error err;
    gd_error_set(&err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return gd_cli_report(&err);
}

static void split_free(shaft_split *sp)
{
    free(sp->t);
    free(sp->share);
}

static int dominant(const double *v, int n)
{
    int b = 0;
    for (int i = 1; i < n; i++)
        if (v[i] > v[b]) b = i;
    return b;
}

int gd_cli_print_shaft_tables(FILE *f, const gd_system *s, const gd_modal_result *r)
{
    shaft_split sp;
    int rc = split_init(&sp, s);
    if (rc) return rc;
    const gd_model *m = s->model;
    fprintf(f, "\nstrain energy by shaft, gears, bearings and meshes included (%%):\n");
    fprintf(f, "%4s %12s  %-14s", "mode", "f_n(Hz)", "dominant shaft");
    for (int j = 0; j < sp.ns; j++)
        fprintf(f, " %10.10s", m->shafts[j].name);
    fprintf(f, "\n");
    for (int i = 0; i < r->nmodes && !rc; i++) {
        if ((rc = split(s, r, i, &sp))) break;
        int rigid = r->modes[i].rigid_body;
        fprintf(f, "%4d %12.6g  %-14.14s", i + 1, r->modes[i].frequency_hz,
                rigid ? "(rigid body)" : m->shafts[dominant(sp.share, sp.ns)].name);
        for (int j = 0; j < sp.ns && !rigid; j++)
            fprintf(f, " %10.1f", 100 * sp.share[j]);
        fprintf(f, "\n");
    }
    for (int j = 0; j < sp.ns && !rc; j++) {
        fprintf(f, "\nshaft %s: its strain energy by motion type (%%):\n", m->shafts[j].name);
        fprintf(f, "%4s %12s  %-14s %6s %6s %6s %6s\n", "mode", "f_n(Hz)", "dominant", "lat%",
                "tor%", "ax%", "tilt%");
        for (int i = 0; i < r->nmodes && !rc; i++) {
            if ((rc = split(s, r, i, &sp))) break;
            const double *t = sp.t + j * GD_NMOTIONS;
            int idle = !(sp.share[j] > GD_SHAFT_IDLE);
            fprintf(f, "%4d %12.6g  %-14s", i + 1, r->modes[i].frequency_hz,
                    r->modes[i].rigid_body ? "(rigid body)"
                    : idle                 ? "no-vibration"
                                           : gd_motion_names[dominant(t, GD_NMOTIONS)]);
            for (int k = 0; k < GD_NMOTIONS && !idle; k++)
                fprintf(f, " %6.1f", 100 * t[k] / sp.share[j]);
            fprintf(f, "\n");
        }
    }
    split_free(&sp);
    return rc;
}

int gd_cli_shaft_json(cJSON *modes, const gd_system *s, const gd_modal_result *r)
{
    shaft_split sp;
    int rc = split_init(&sp, s);
    for (int i = 0; i < r->nmodes && !rc; i++) {
        if ((rc = split(s, r, i, &sp))) break;
        cJSON *mo = cJSON_GetArrayItem(modes, i);
        int rigid = r->modes[i].rigid_body;
        if (rigid)
            cJSON_AddNullToObject(mo, "dominant_shaft");
        else
            cJSON_AddStringToObject(mo, "dominant_shaft",
                                    s->model->shafts[dominant(sp.share, sp.ns)].name);
        cJSON *by = cJSON_AddObjectToObject(mo, "energy_by_shaft");
        for (int j = 0; j < sp.ns; j++) {
            const double *t = sp.t + j * GD_NMOTIONS;
            int idle = !(sp.share[j] > GD_SHAFT_IDLE);
            cJSON *o = cJSON_AddObjectToObject(by, s->model->shafts[j].name);
            cJSON_AddNumberToObject(o, "share", sp.share[j]);
            for (int k = 0; k < GD_NMOTIONS; k++)
                cJSON_AddNumberToObject(o, gd_motion_names[k], idle ? 0 : t[k] / sp.share[j]);
            cJSON_AddStringToObject(o, "dominant_motion",
                                    rigid  ? "rigid-body"
                                    : idle ? "no-vibration"
                                           : gd_motion_names[dominant(t, GD_NMOTIONS)]);
        }
    }
    if (!rc) split_free(&sp);
    return rc;
}
