/* Internals of the Campbell diagram: tracking, orders and crossings. */
#ifndef GD_CAMPBELL_INTERNAL_H
#define GD_CAMPBELL_INTERNAL_H
#include "geardyn/campbell.h"

/* How the speeds of a sparse sweep were solved: continued from the previous speed
 * (gd_sparse_track), or by Krylov-Schur after the continuation declined (fallbacks);
 * the first speed of each chain, and the speeds after a hard one in its chain, are
 * Krylov-Schur and count in neither. */
typedef struct gd_campbell_stats {
    int continued, fallbacks;
} gd_campbell_stats;

/* gd_campbell with the continuation along chains on (1, the default) or off (0: every
 * speed by Krylov-Schur, the reference), and its counts in *stats (may be NULL). */
gd_status gd_campbell_run(const gd_system *sys, const gd_campbell_options *opt, int continuation,
                          gd_campbell_stats *stats, gd_campbell_result **out, gd_error *err);

/* Assigns track ids to the elastic modes of one speed from those of the previous one
 * (prev NULL at the first speed: new tracks). elastic lists the indices into
 * cur->modes of its nel_cur elastic modes (ascending frequency); track[j] receives the
 * id of elastic mode j, a new id (*ntracks)++ when no previous mode matches with a MAC
 * of at least mac_min. Needs the mode shapes of both speeds. Returns 0, or -1 when
 * out of memory. */
int gd_campbell_track_step(const gd_modal_result *prev, const int *prev_elastic, int prev_nel,
                           const int *prev_track, const gd_modal_result *cur, const int *elastic,
                           int nel_cur, double mac_min, int *track, int *ntracks);

/* Orders: 1x of each shaft, user orders, tooth-mesh orders (deduplicated). Returns
 * the count (out allocated, caller frees) or -1 when out of memory. */
int gd_campbell_orders(const gd_model *m, const gd_campbell_options *opt, gd_order **out);

/* Critical speeds and instability onset from the filled tracks of r. Returns 0, or -1
 * when out of memory. */
int gd_campbell_crossings(gd_campbell_result *r);

/* Minimum-cost assignment of an n x n cost matrix (column-major): row i gets column
 * col_of_row[i]. Deterministic (Kuhn-Munkres with potentials). 0 ok, -1 no memory. */
int gd_hungarian(const double *cost, int n, int *col_of_row);

#endif
