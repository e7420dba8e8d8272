/* `geardyn transient --poincare SHAFT|MESH`: stroboscopic (Poincare) samples once per
 * revolution of a shaft or once per tooth-mesh cycle of a mesh, their periodicity, and
 * the bifurcation-diagram sweep over speeds (transient_sweep.c; docs/transient.md). */
#ifndef GD_TRANSIENT_POINCARE_H
#define GD_TRANSIENT_POINCARE_H
#include <cjson/cJSON.h>

#include "geardyn/transient_model.h"
#include "geardyn/waterfall.h"
#include "transient_record.h"

/* The sampling period is angle / W at reference speed W. */
typedef struct gd_cli_poincare {
    char name[160]; /* "shaft:NAME" or "mesh:NAME" */
    double angle;   /* rad of the reference shaft per sample */
} gd_cli_poincare;

/* Relative tolerance of the periodicity test: two Poincare points are the same when every
 * record differs by at most this fraction of its peak-to-peak over the recorded part. */
#define GD_CLI_POINCARE_TOL 1e-3

/* Parses SHAFT|MESH: a shaft or mesh name, or shaft:NAME / mesh:NAME when a name is both.
 * 0, or 2 after a usage error naming the known shafts and meshes. */
int gd_cli_poincare_parse(const char *cmd, const gd_model *m, const char *text, gd_cli_poincare *p);
/* The sample times k P (P = angle / speed; nominal angles at t = 0 are the phase origin)
 * within [from, t_end]: count, times malloc'd (*times NULL when 0 or out of memory). */
int gd_cli_poincare_times(const gd_cli_poincare *p, double speed, double from, double t_end,
                          double **times);

/* Periodicity of n points (record r, point k: values[r * n + k]) with scale[r] the
 * record's peak-to-peak: the number of distinct points (greedy clustering: a point
 * joins the first cluster whose first point it equals) and the smallest p <= n / 2 with
 * point k + p = point k for every k and exactly p distinct points (0 when none:
 * quasi-periodic, chaotic, or a drift not settled within the settling time); verdict
 * (may be NULL): the name of gd_poincare_classify's verdict (include/geardyn/cycles.h). */
void gd_cli_poincare_classify(const double *values, int nrec, int n, const double *scale,
                              int *period, int *distinct, char *verdict, int vsize);
/* "period-P", or "many" when period is 0. */
void gd_cli_poincare_class_name(int period, char *buf, size_t size);

/* JSON of n points: {"source", "period_s", "points", "period", "distinct_points",
 * "class", "tolerance", "times_s", "records": [{"name", "values"}]}. */
cJSON *gd_cli_poincare_json(const gd_cli_poincare *p, double period_s, const gd_cli_records *recs,
                            const double *t, const double *values, int n, int period, int distinct);

/* The bifurcation-diagram sweep (transient_sweep.c): at every speed the problem is rebuilt
 * and started from the previous speed's end state, at the time where every nominal angle
 * (all proportional to W t) continues; the settling time is integrated, then `points`
 * Poincare periods are sampled. */
typedef struct gd_cli_sweep {
    const double *speeds; /* rad/s, increasing */
    int nspeeds;
    int direction;                   /* 0 up, 1 down, 2 up then down */
    double settle_time, settle_revs; /* one > 0: s, or revolutions of the reference shaft */
    int points;                      /* Poincare points per speed */
    gd_transient_options base;       /* rtol, method, init of the first speed */
    int json, quiet;
    const char *out;
    int waterfall;    /* record index whose spectra make the run-up waterfall; -1: none */
    double max_order; /* highest excitation order (samples fine enough for it) */
    const char *plot; /* --plot: the waterfall figure */
} gd_cli_sweep;

/* The record of --waterfall REC (NULL: the first record): its index in recs (REC added
 * when not recorded yet) and the model's highest excitation order (1x of each shaft,
 * teeth x speed ratio of each mesh's driver). 0, or 2 after a usage error. */
int gd_cli_waterfall_record(const char *cmd, const gd_system *sys, const gd_transient_model *tm,
                            const char *text, gd_cli_records *recs, int *index, double *max_order);

/* The waterfall's JSON object (record, orders with their cuts, spectra), its CSV files
 * (waterfall.csv, order_cuts.csv into od; 0 ok) and its text table (down: a run-down). */
cJSON *gd_cli_waterfall_json(const gd_cli_record *rec, const gd_waterfall *w);
struct gd_outdir;
int gd_cli_waterfall_csv(struct gd_outdir *od, const gd_waterfall *w, gd_error *err);
void gd_cli_waterfall_print(const gd_cli_record *rec, const gd_waterfall *w, int down);

int gd_cli_transient_sweep(const gd_system *sys, const gd_transient_model *tm,
                           const gd_cli_records *recs, const gd_cli_poincare *p,
                           const gd_cli_sweep *sw);

#endif
