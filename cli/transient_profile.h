/* geardyn transient with a speed profile (--speed-ramp, --speed-table): parsing the
 * profile and the order-tracked run-up waterfall of one record (docs/transient.md,
 * "Run-up through a speed profile"). */
#ifndef GD_CLI_TRANSIENT_PROFILE_H
#define GD_CLI_TRANSIENT_PROFILE_H
#include "geardyn/transient.h"
#include "geardyn/waterfall.h"

/* The speeds read for a profile (owned arrays of a table). */
typedef struct gd_cli_profile {
    gd_speed_profile p;
    double *t, *w;     /* table rows (NULL for a ramp) */
    double wmin, wmax; /* |speed| range, rad/s */
} gd_cli_profile;
void gd_cli_profile_free(gd_cli_profile *cp);

/* --speed-ramp FROM:TO (speeds with units, e.g. 0:6000rpm; FROM takes TO's unit when it
 * has none) over [0, t_end]. 0, or 2 after a usage error. */
int gd_cli_speed_ramp(const char *cmd, const char *text, double t_end, gd_cli_profile *cp);
/* --speed-table FILE: rows "time, speed" (comma or blank separated; '#' comments; an
 * optional header line naming the speed unit: rpm, rad/s (default), Hz). 0, or 2 after
 * an error naming the file and line. */
int gd_cli_speed_table(const char *cmd, const char *path, gd_cli_profile *cp);

/* Samples per revolution for the order tracking of a model whose highest order is
 * max_order: the power of two >= 2.5 max_order, at least 32. */
int gd_cli_track_samples(double max_order);

/* The order-tracked waterfall of record values (n samples at times t) under the profile.
 * 0, or the exit code after an error (reported). */
int gd_cli_runup_waterfall(const char *cmd, const gd_system *sys, const gd_cli_profile *cp,
                           const double *t, const double *x, int n, double revs_per_block,
                           int samples_per_rev, gd_waterfall **out);
#endif
