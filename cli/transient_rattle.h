/* `geardyn transient --rattle`: the rattle metrics of every backlash mesh over the
 * recorded window (geardyn/rattle.h, docs/rattle.md) from the run's contact-event log. */
#ifndef GD_TRANSIENT_RATTLE_H
#define GD_TRANSIENT_RATTLE_H
#include <cjson/cJSON.h>

#include "geardyn/model.h"
#include "geardyn/rattle.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"

typedef struct gd_cli_rattle {
    int n;        /* backlash meshes */
    int *mesh;    /* spec mesh index of each */
    double *mass; /* effective mass, kg (0: none, intensity in m^2/s^3) */
    gd_rattle_metrics *metrics;
    double target; /* the relative half-width wanted */
} gd_cli_rattle;

/* The metrics of each backlash mesh over [from, t_end] in `batches` batches at 95 %
 * confidence (target: the relative half-width wanted). 0, or an exit code after a
 * message. */
int gd_cli_rattle_analyse(gd_transient *tr, const gd_transient_model *tm,
                          const gd_transient_result *res, double from, double t_end, int batches,
                          double target, gd_cli_rattle *r);
cJSON *gd_cli_rattle_json(const gd_cli_rattle *r, const gd_model *m, const gd_transient_model *tm);
void gd_cli_rattle_print(const gd_cli_rattle *r, const gd_model *m, const gd_transient_model *tm);
void gd_cli_rattle_free(gd_cli_rattle *r);

#endif
