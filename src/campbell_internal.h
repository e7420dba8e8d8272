/* Internals of the Campbell diagram: tracking, orders and crossings. */
#ifndef GD_CAMPBELL_INTERNAL_H
#define GD_CAMPBELL_INTERNAL_H
#include "geardyn/campbell.h"

/* Assigns track ids to the elastic modes of every speed. elastic[s] lists, for speed s,
 * the indices into res[s]->modes of its nel[s] elastic modes (ascending frequency).
 * Fills track[s][j] (id of elastic mode j at speed s) and returns the number of
 * tracks, or -1 when out of memory. */
int gd_campbell_assign_tracks(gd_modal_result *const *res, int nspeeds, int *const *elastic,
                              const int *nel, double mac_min, int **track);

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
