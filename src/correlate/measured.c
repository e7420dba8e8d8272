/* Measured modes for correlation: from an EMA of FRFs (shapes from the residues of one
 * reference's FRFs, at the response DOFs) or from a modes CSV (frequencies only). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/correlate.h"

void gd_measured_modes_free(gd_measured_modes *m)
{
    if (!m) return;
    free(m->hz), free(m->zeta), free(m->dof), free(m->sign), free(m->shape_re), free(m->shape_im);
    memset(m, 0, sizeof *m);
}

static gd_status alloc_modes(gd_measured_modes *m, int nmodes, int ndofs, gd_error *err)
{
    memset(m, 0, sizeof *m);
    m->nmodes = nmodes;
    m->ndofs = ndofs;
    m->hz = calloc((size_t)nmodes + 1, sizeof(double));
    m->zeta = calloc((size_t)nmodes + 1, sizeof(double));
    if (ndofs) {
        m->dof = calloc((size_t)ndofs, sizeof(int));
        m->sign = calloc((size_t)ndofs, sizeof(double));
        m->shape_re = calloc((size_t)ndofs * nmodes + 1, sizeof(double));
        m->shape_im = calloc((size_t)ndofs * nmodes + 1, sizeof(double));
    }
    if (!m->hz || !m->zeta || (ndofs && (!m->dof || !m->sign || !m->shape_re || !m->shape_im))) {
        gd_measured_modes_free(m);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    return GD_OK;
}

gd_status gd_measured_from_testdata(const gd_testdata *td, gd_measured_modes *out, gd_error *err)
{
    if (td->nmodes < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes",
                            "give a modes CSV or FRFs to extract modes from",
                            "no measured frequency");
    gd_status st = alloc_modes(out, td->nmodes, 0, err);
    if (st) return st;
    for (int i = 0; i < td->nmodes; i++) {
        out->hz[i] = td->mode_hz[i];
        out->zeta[i] = td->mode_zeta[i];
    }
    return GD_OK;
}

gd_status gd_measured_from_ema(const gd_system *sys, const gd_test_setup *setup, int nfrf,
                               const gd_td_function *const *frfs, const gd_ema_result *r,
                               gd_measured_modes *out, gd_error *err)
{
    /* the reference most FRFs share */
    int best = -1, bestn = 0;
    for (int o = 0; o < nfrf; o++) {
        int c = 0;
        for (int q = 0; q < nfrf; q++)
            c += frfs[q]->reference_node == frfs[o]->reference_node &&
                 frfs[q]->reference_dir == frfs[o]->reference_dir;
        if (c > bestn) bestn = c, best = o;
    }
    if (r->nmodes < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes",
                            "widen the band (--band) or raise the order (--order)",
                            "no mode was extracted from the FRFs");
    gd_status st = alloc_modes(out, r->nmodes, bestn, err);
    if (st) return st;
    /* the points: the responses of the main reference's FRFs */
    int d = 0, *pick = malloc((size_t)nfrf * sizeof *pick + 1);
    if (!pick) {
        gd_measured_modes_free(out);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    for (int o = 0; o < nfrf && !st; o++) {
        if (frfs[o]->reference_node != frfs[best]->reference_node ||
            frfs[o]->reference_dir != frfs[best]->reference_dir)
            continue;
        st = gd_test_point_dof(sys, setup, frfs[o]->response_node, frfs[o]->response_dir,
                               frfs[o]->file, frfs[o]->line, &out->dof[d], &out->sign[d], err);
        pick[d++] = o;
    }
    /* each mode's shape from the reference that excites it most (several references:
     * an x mode from the x hammer, a y mode from the y one), where that reference's FRFs
     * cover every point */
    for (int j = 0; j < r->nmodes && !st; j++) {
        double best_e = -1;
        int use[64 + 1];
        int nuse = bestn <= 64 ? bestn : 0;
        for (int g = 0; g < nfrf && nuse; g++) {
            /* g stands for its reference when it is the first FRF of it */
            int first = 1;
            for (int q = 0; q < g && first; q++)
                first = !(frfs[q]->reference_node == frfs[g]->reference_node &&
                          frfs[q]->reference_dir == frfs[g]->reference_dir);
            if (!first) continue;
            int cand[64], ok = 1;
            double e = 0;
            for (int k = 0; k < bestn && ok; k++) {
                const gd_td_function *pk = frfs[pick[k]];
                cand[k] = -1;
                for (int q = 0; q < nfrf; q++)
                    if (frfs[q]->reference_node == frfs[g]->reference_node &&
                        frfs[q]->reference_dir == frfs[g]->reference_dir &&
                        frfs[q]->response_node == pk->response_node &&
                        frfs[q]->response_dir == pk->response_dir)
                        cand[k] = q;
                ok = cand[k] >= 0;
                if (ok) {
                    double a = r->residue_re[cand[k] + (size_t)j * r->nfrf];
                    double b = r->residue_im[cand[k] + (size_t)j * r->nfrf];
                    e += a * a + b * b;
                }
            }
            if (ok && e > best_e) {
                best_e = e;
                memcpy(use, cand, (size_t)bestn * sizeof *use);
            }
        }
        for (int k = 0; k < bestn; k++) {
            int o = best_e >= 0 ? use[k] : pick[k];
            out->shape_re[(size_t)j * bestn + k] = r->residue_re[o + (size_t)j * r->nfrf];
            out->shape_im[(size_t)j * bestn + k] = r->residue_im[o + (size_t)j * r->nfrf];
        }
    }
    free(pick);
    for (int j = 0; j < r->nmodes; j++) {
        out->hz[j] = r->modes[j].frequency_hz;
        out->zeta[j] = r->modes[j].damping_ratio;
    }
    if (st) gd_measured_modes_free(out);
    return st;
}
