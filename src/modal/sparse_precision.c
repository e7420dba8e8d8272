/* The sparse modes to the precision asked (gd_modal_options.tol, `geardyn modal --tol`):
 * Krylov-Schur (sparse_modes.c, its vectors purified), one step of inverse iteration at
 * its own eigenvalue for each mode still above the tolerance, then the refinement of the
 * continuation (sparse_track.c) while an elastic mode's relative residual (residual.c) is
 * above the tolerance and above what rounding leaves; and gd_modal_solve_sparse, the
 * library's entry. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

/* the largest residual of the elastic modes of r: all of them (want < 0), or only those
 * above want and above 100 times their rounding floor (0: none left to improve) */
static double worst_residual(const gd_modal_result *r, double want)
{
    double w = 0;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (!md->rigid_body &&
            (want < 0 || (md->residual > want && md->residual > 100 * md->residual_floor)))
            w = fmax(w, md->residual);
    }
    return w;
}

/* Each elastic mode of r whose residual fails want while its rounding floor lies 100 times
 * below it (one at its floor is the refinement's, below): one step of inverse iteration at its own
 * eigenvalue, u <- P(lambda)^-1 P'(lambda) u with a complex factorisation of P(lambda) (KLU on a's
 * analysis). The Krylov-Schur eigenvalue is already accurate (1e-12 of itself on rig366) while its
 * vector is not (the rounding of the basis, multiplied by the stiff directions: residuals 1e-9 to
 * 1e-7 after purification), so one step takes the residual to near its floor; the shape is kept
 * only when its residual falls. An overdamped mode (a real eigenvalue) takes the step even near
 * its floor: the refinement continues complex pairs and did not converge on one (the planetary
 * reducer's input shaft on IN2: 6.3e-9 and 1.6e-7 left, 1.2e-10 and 1.4e-11 after the step).
 * k, d: the values r was solved with (d NULL: undamped). 0, or -1 when out of memory. */
static int inverse_step(const gd_dynmat *a, const gd_splu_symbolic *sym, const double *k,
                        const double *d, gd_modal_result *r, double want)
{
    const gd_pattern *p = &a->pat;
    int n = p->n, nnz = p->nnz;
    double *pv = malloc((size_t)2 * (nnz > 0 ? nnz : 1) * sizeof *pv);
    double *b = malloc((size_t)2 * n * sizeof *b), *w = malloc((size_t)15 * n * sizeof *w);
    int rc = pv && b && w ? 0 : -1;
    for (int j = 0; j < r->nmodes && !rc; j++) {
        gd_mode *md = &r->modes[j];
        if (md->rigid_body ||
            !(md->residual > want && (100 * md->residual_floor < want || md->overdamped)))
            continue;
        double lr = md->lambda_re, li = md->lambda_im, l2r = lr * lr - li * li, l2i = 2 * lr * li;
        for (int q = 0; q < nnz; q++) {
            double dq = d ? d[q] : 0;
            pv[2 * q] = l2r * a->m[q] + lr * dq + k[q];
            pv[2 * q + 1] = l2i * a->m[q] + li * dq;
        }
        gd_splu lu = {0};
        int f = gd_splu_factor(&lu, p, sym, pv, 1, 1);
        if (f < 0) rc = -1;
        if (f) {
            gd_splu_free(&lu);
            continue;
        }
        /* b = P'(lambda) u = (2 lambda M + D) u */
        double *ur = r->shape_re + (size_t)j * n, *ui = r->shape_im + (size_t)j * n;
        memset(b, 0, (size_t)2 * n * sizeof *b);
        for (int c = 0; c < n; c++)
            for (int q = p->colptr[c]; q < p->colptr[c + 1]; q++) {
                int i = p->rowind[q];
                double cr = 2 * lr * a->m[q] + (d ? d[q] : 0), ci = 2 * li * a->m[q];
                b[2 * i] += cr * ur[c] - ci * ui[c];
                b[2 * i + 1] += cr * ui[c] + ci * ur[c];
            }
        gd_splu_solve(&lu, sym, n, 1, b);
        gd_splu_free(&lu);
        double *xr = w + 13 * n, *xi = w + 14 * n;
        for (int i = 0; i < n; i++) {
            xr[i] = b[2 * i];
            xi[i] = b[2 * i + 1];
        }
        gd_normalise_max(xr, xi, n);
        gd_mode trial = *md;
        gd_mode_residual(a, k, d, &trial, xr, xi, w);
        /* the vector is now the more accurate: its Rayleigh functional, the root of
         * x^H P(lambda) x = 0 nearest lambda (gd_mode_residual left M x, D x, K x in w) */
        double complex qm = 0, qd = 0, qk = 0, lam = lr + I * li;
        for (int i = 0; i < n; i++) {
            double complex xc = xr[i] - I * xi[i];
            qm += xc * (w[n + i] + I * w[2 * n + i]);
            qd += xc * (w[4 * n + i] + I * w[5 * n + i]);
            qk += xc * (w[7 * n + i] + I * w[8 * n + i]);
        }
        if (!d) qd = 0;
        double complex sq = csqrt(qd * qd - 4 * qm * qk), r1 = (-qd + sq) / (2 * qm),
                       r2 = (-qd - sq) / (2 * qm), nl = cabs(r1 - lam) <= cabs(r2 - lam) ? r1 : r2;
        if (!r->damped) /* undamped: lambda = i omega exactly, as gd_sparse_modes */
            nl = I * sqrt(fabs(creal(nl * nl)));
        if (isfinite(creal(nl)) && isfinite(cimag(nl)) && cimag(nl) >= 0) {
            gd_mode t2 = trial;
            gd_mode_set_lambda(&t2, creal(nl), cimag(nl));
            gd_mode_residual(a, k, d, &t2, xr, xi, w);
            if (t2.residual < trial.residual) trial = t2;
        }
        if (!(trial.residual < md->residual)) continue;
        memcpy(ur, xr, (size_t)n * sizeof *ur);
        memcpy(ui, xi, (size_t)n * sizeof *ui);
        *md = trial;
        gd_mode_finish(a->sys, r->speed, md, ur, ui,
                       r->energy_by_component + (size_t)j * a->sys->ncomponents);
    }
    free(pv);
    free(b);
    free(w);
    return rc;
}

gd_status gd_sparse_modes_to_tol(const gd_dynmat *a, const gd_splu_symbolic *sym,
                                 const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                                 gd_modal_result **out, gd_error *err)
{
    gd_modal_options o = *opt;
    double want = opt->tol > 0 ? opt->tol : GD_MODAL_TOL_DEFAULT;
    /* Krylov-Schur at least to the default: the refinement below starts from its modes,
     * and from those of a looser tolerance (1e-8 on gearbox100k) it does not converge */
    o.tol = fmin(want, GD_MODAL_TOL_DEFAULT);
    gd_sparse_ws local = {0};
    gd_sparse_ws *tw = ws;
    if (!tw) {
        if (gd_sparse_ws_init(&local, a, o.nmodes > 0 ? o.nmodes : a->pat.n))
            return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                                "out of memory in the sparse eigensolver");
        tw = &local;
    }
    /* the projection of the undamped modes first (sparse_project.c), Krylov-Schur where its
     * rule declines */
    gd_status st = GD_OK;
    *out = NULL;
    if (shift <= 0 && !tw->chain) {
        st = gd_sparse_modes_projected(a, sym, &o, tw, out, err);
        if (!st && *out &&
            gd_modal_residuals_on(a, tw->k, (*out)->damped ? tw->d : NULL, *out, NULL, NULL))
            st = GD_ENOMEM;
    }
    if (!st && !*out) st = gd_sparse_modes(a, sym, &o, shift, tw, out, err);
    if (!st && worst_residual(*out, want) > 0 &&
        inverse_step(a, sym, tw->k, (*out)->damped ? tw->d : NULL, *out, want))
        st = GD_ENOMEM;
    if (!st && worst_residual(*out, want) == 0 &&
        gd_modal_energies_laws(a->sys, *out, opt->law_state))
        st = GD_ENOMEM;
    if (st || worst_residual(*out, want) == 0) {
        gd_sparse_ws_free(&local);
        if (st == GD_ENOMEM) {
            gd_modal_free(*out);
            *out = NULL;
            return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                                "out of memory in the sparse eigensolver");
        }
        return st;
    }
    /* what one step left above the tolerance (a repeated value, whose copies one step at
     * the same eigenvalue does not separate): the pairs are refined on the quadratic problem itself
     * by residual inverse iteration with Rayleigh-Ritz at factorisations of P(sigma) near them
     * (sparse_track.c, the Campbell continuation, here from this speed's own modes), a pass kept
     * only when it lowers the worst residual; at most 3 passes (repeated frequencies take two) */
    for (int pass = 0; pass < 3 && !st && worst_residual(*out, want) > 0; pass++) {
        gd_modal_result *ref = NULL;
        st = gd_sparse_refine(a, sym, &o, *out, tw, &ref, NULL);
        if (!st && ref &&
            gd_modal_residuals_on(a, tw->k, ref->damped ? tw->d : NULL, ref, NULL, NULL))
            st = GD_ENOMEM;
        int better = !st && ref && worst_residual(ref, -1) < worst_residual(*out, -1);
        if (better) {
            gd_modal_free(*out);
            *out = ref;
        } else {
            gd_modal_free(ref);
            if (!st) break;
        }
    }
    gd_sparse_ws_free(&local);
    /* the laws' strain energy, once the shapes are final */
    if (st != GD_ENOMEM && gd_modal_energies_laws(a->sys, *out, opt->law_state)) st = GD_ENOMEM;
    if (st == GD_ENOMEM) {
        gd_modal_free(*out);
        *out = NULL;
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                            "out of memory in the sparse eigensolver");
    }
    return GD_OK; /* a refinement that failed leaves the Krylov-Schur modes */
}

gd_status gd_modal_solve_sparse(const gd_system *sys, const gd_modal_options *opt, double shift,
                                gd_modal_result **out, gd_error *err)
{
    *out = NULL;
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    st = gd_splu_analyze(&a.pat, &sym, err);
    if (!st) {
        st = gd_sparse_modes_to_tol(&a, &sym, opt, shift, NULL, out, err);
        gd_splu_symbolic_free(&sym);
    }
    gd_dynmat_free(&a);
    return st;
}
