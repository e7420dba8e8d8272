/* `geardyn transient --periods N`: per-period statistics over N periods of the excitations'
 * fundamental after a settling time, and the Poincare verdict on the once-per-period
 * samples (docs/transient.md, "Responses with no stable periodic orbit"). */
#ifndef GD_TRANSIENT_PERIODS_H
#define GD_TRANSIENT_PERIODS_H
#include <cjson/cJSON.h>
#include <stdio.h>

#include "geardyn/cycles.h"
#include "geardyn/transient_model.h"
#include "transient_record.h"

typedef struct gd_cli_periods {
    int count;              /* N */
    double w0, period;      /* fundamental, rad/s; T = 2 pi / w0, s */
    int max_order;          /* highest excitation order of w0 */
    double settle;          /* s: the settling time rounded up to whole periods */
    double t_end;           /* settle + N T */
    double dt;              /* output interval: T / samples_per_period (or the user's) */
    int samples_per_period; /* 0 when the user's interval does not divide T */
    /* results (gd_cli_periods_analyse) */
    gd_cycle_stats *stats; /* one per record */
    gd_poincare_verdict verdict;
} gd_cli_periods;

/* The run: T from the excitations (gd_periodic_fundamental), the settling time (seconds,
 * or revolutions of the reference shaft; both 0: 100 revolutions) rounded up to whole
 * periods, the output interval (interval > 0: the user's, else T / max(256, 50 max_order))
 * and the N + 1 section times settle + k T (malloc'd). 0, or 2 after an error message. */
int gd_cli_periods_plan(const char *cmd, const gd_system *sys, const gd_transient_spec *spec,
                        double speed, int count, double settle_time, double settle_revs,
                        double interval, gd_cli_periods *p, double **times);
/* The statistics of every record over the periods and the verdict on the section
 * samples (scale: each record's peak-to-peak over the recorded part). 0 or an exit code. */
int gd_cli_periods_analyse(gd_cli_periods *p, const gd_cli_records *recs,
                           const gd_transient_result *res);
cJSON *gd_cli_periods_json(const gd_cli_periods *p, const gd_cli_records *recs);
void gd_cli_periods_print(const gd_cli_periods *p, const gd_cli_records *recs);
/* periods.csv: record, unit, quantity, median, p05, p95, min, max */
void gd_cli_periods_csv(FILE *f, const gd_cli_periods *p, const gd_cli_records *recs);
void gd_cli_periods_free(gd_cli_periods *p);

#endif
