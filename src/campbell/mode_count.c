/* How many modes a Campbell diagram tracks by default: every elastic mode up to 1.25 x
 * the highest excitation frequency of the sweep (its highest order, tooth-mesh orders
 * included, at its top speed), and at least 12. A fixed 12 stopped a gearbox's diagram
 * far below its tooth-mesh crossings (kHz) without a word (issue 35). The modes are
 * counted at rest without damping or gyroscopics: speed moves them a little, so the
 * margin, and 2 modes beyond the count, keep the ones near the top in the tracks. */
#include <math.h>
#include <stdlib.h>

#include "campbell/campbell_impl.h"
#include "modal/modal_impl.h"

#define MIN_MODES 12
#define MARGIN 1.25
/* the dense solve counts every mode up to this size; above it the sparse solver is asked
 * for doubling counts until its top mode passes the limit (or MAX_MODES) */
#define DENSE_COUNT_MAX 1500
#define MAX_MODES 400

static int elastic_below(const gd_modal_result *r, double limit, double *top)
{
    int n = 0;
    *top = 0;
    for (int k = 0; k < r->nmodes; k++) {
        const gd_mode *md = &r->modes[k];
        if (md->rigid_body) continue;
        if (md->omega_n > *top) *top = md->omega_n;
        if (md->omega_n <= limit) n++;
    }
    return n;
}

gd_status gd_campbell_default_modes(const gd_system *sys, const gd_campbell_options *opt,
                                    int *nmodes, double *limit, gd_error *err)
{
    *nmodes = MIN_MODES;
    *limit = 0;
    if (opt->nspeeds <= 0 || !opt->speeds) return GD_OK;
    gd_order *orders = NULL;
    int no = gd_campbell_orders(sys->model, opt, &orders);
    if (no < 0) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    double top_order = 0;
    for (int i = 0; i < no; i++)
        top_order = fmax(top_order, orders[i].order);
    free(orders);
    double top_speed = 0;
    for (int i = 0; i < opt->nspeeds; i++)
        top_speed = fmax(top_speed, fabs(opt->speeds[i]));
    *limit = MARGIN * top_order * top_speed;
    if (!(*limit > 0)) return GD_OK;
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.kind = GD_MODAL_UNDAMPED;
    int dense = sys->ndof <= DENSE_COUNT_MAX;
    if (dense) {
        /* eigenvalues only: the vectors and mode properties of a full solve cost as much
           again and are not looked at (a fifth of a 228-DOF Campbell sweep) */
        double *om = NULL;
        int m = 0;
        gd_status st = gd_modal_undamped_frequencies(sys, &mo, &om, &m, err);
        if (st) return st;
        if (om) {
            int n = 0;
            for (int k = 0; k < m; k++)
                n += om[k] >= 0 && om[k] <= *limit;
            free(om);
            int want = n + 2;
            *nmodes = want < MIN_MODES ? MIN_MODES : want > MAX_MODES ? MAX_MODES : want;
            return GD_OK;
        }
    }
    mo.method = dense ? GD_EIG_DENSE : GD_EIG_SPARSE;
    int ask = dense ? 0 : 2 * MIN_MODES;
    for (;;) {
        mo.nmodes = ask;
        gd_modal_result *r = NULL;
        gd_status st = gd_modal_solve(sys, &mo, &r, err);
        if (st) return st;
        double top;
        int n = elastic_below(r, *limit, &top);
        int found = r->nmodes;
        gd_modal_free(r);
        if (dense || top > *limit || found < ask || ask >= MAX_MODES) {
            int want = n + 2;
            *nmodes = want < MIN_MODES ? MIN_MODES : want > MAX_MODES ? MAX_MODES : want;
            return GD_OK;
        }
        ask = 2 * ask > MAX_MODES ? MAX_MODES : 2 * ask;
    }
}
