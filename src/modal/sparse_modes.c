/* Lowest damped modes on the sparse system: shift-invert Krylov-Schur on the
 * first-order form with a real shift sigma = -s just left of the origin, so the modes
 * nearest zero (the lowest, for light damping |lambda + s| grows with the frequency)
 * converge first and rigid-body modes (lambda = 0) do not make the factorised matrix
 * singular. Each shift-invert step costs one sparse n x n solve, so the cost per
 * speed grows about linearly with the DOFs. Right eigenvectors only. */
#include <complex.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

#define PI 3.14159265358979323846
/* The Krylov-Schur tolerance (relative residual of the Ritz pairs in the scaled
 * first-order form) is opt->tol, GD_MODAL_TOL_DEFAULT = 1e-9 when 0; measured on the
 * refined MMT rig (610 DOFs, 12 modes, 0-12000 rpm): eigenvalues within 2e-10 of the
 * dense solver's, and one check less than 1e-11 would take. */

typedef struct si_ctx {
    gd_shift_invert *op;
    const gd_splu_symbolic *sym;
} si_ctx;

static void si_apply(void *ctx, const double *x, double *y)
{
    si_ctx *c = ctx;
    gd_shift_invert_apply(c->op, c->sym, x, y);
}

typedef struct cand {
    int idx;
    double re, im;
    int rigid;
} cand;

static int cmp_cand(const void *a, const void *b)
{
    const cand *x = a, *y = b;
    if (x->rigid != y->rigid) return y->rigid - x->rigid;
    double ax = hypot(x->re, x->im), ay = hypot(y->re, y->im);
    if (ax != ay) return (ax > ay) - (ax < ay);
    return x->idx - y->idx;
}

/* One explicit step of inverse iteration with the factorised P(-s) on a Ritz vector u of
 * lambda: u <- P(-s)^-1 ((lambda - s) M + D) u, the top half of Op [u; lambda u / g].
 * The Krylov vectors carry the rounding of their orthogonalisation in every direction,
 * and the stiff ones (the mesh's high modes) multiply it by up to (omega_max / omega)^2 in
 * the residual of the quadratic problem (1e-7 on rig366 from a Krylov-Schur residual of
 * 1e-10); the solve damps those directions by the same factor (purification, Nour-Omid,
 * Parlett, Ericsson and Jensen, Math. Comp. 48, 1987). x, y: 2n scratch. */
static void purify(gd_shift_invert *op, const gd_splu_symbolic *sym, double lr, double li,
                   double *re, double *im, double *x, double *y)
{
    int n = op->n;
    double ig = 1.0 / op->scale;
    memcpy(x, re, (size_t)n * sizeof *x);
    for (int i = 0; i < n; i++)
        x[n + i] = (lr * re[i] - li * im[i]) * ig;
    gd_shift_invert_apply(op, sym, x, y);
    memcpy(x, im, (size_t)n * sizeof *x);
    for (int i = 0; i < n; i++)
        x[n + i] = (lr * im[i] + li * re[i]) * ig;
    memcpy(re, y, (size_t)n * sizeof *re);
    gd_shift_invert_apply(op, sym, x, y);
    memcpy(im, y, (size_t)n * sizeof *im);
}

double gd_sparse_diag_frequency(const gd_dynmat *a, const double *k)
{
    double best = INFINITY;
    for (int j = 0; j < a->pat.n; j++) {
        int p = a->pat.diag[j];
        if (p < 0) continue;
        if (a->m[p] > 0 && k[p] > 0 && k[p] / a->m[p] < best) best = k[p] / a->m[p];
    }
    return isfinite(best) ? sqrt(best) : 1e3;
}

void gd_sparse_shift_auto(const gd_dynmat *a, const double *k, double *s, double *g, double *zero)
{
    const gd_system *sys = a->sys;
    double gd = gd_sparse_diag_frequency(a, k), gmax = 0;
    double num[6] = {0}, den[6] = {0}, kdiag[6] = {0};
    for (int j = 0; j < a->pat.n; j++) {
        int tj = (int)sys->dof_type[j];
        for (int q = a->pat.colptr[j]; q < a->pat.colptr[j + 1]; q++) {
            int i = a->pat.rowind[q];
            if ((int)sys->dof_type[i] != tj) continue;
            num[tj] += k[q];
            den[tj] += a->m[q];
            if (i == j) {
                kdiag[tj] += fabs(k[q]);
                if (a->m[q] > 0 && k[q] / a->m[q] > gmax) gmax = k[q] / a->m[q];
            }
        }
    }
    gmax = sqrt(gmax);
    /* Rayleigh quotients of the uniform motions, one per DOF type: upper bounds of the
     * lowest frequency (Rayleigh), usually within a decade of it on a rotor (the rotor
     * moving on its bearings). A motion whose quotient cancels to rounding is rigid. */
    double wrq = INFINITY;
    for (int t = 0; t < 6; t++)
        if (den[t] > 0 && num[t] > 1e-9 * kdiag[t]) wrq = fmin(wrq, sqrt(num[t] / den[t]));
    /* sqrt(min K_ii / M_ii) is an element's frequency, not the structure's: on a fine
     * mesh (issue 23's 0.6 mm elements) it is 1e5 times the lowest mode, and a shift
     * of 1e-3 of it puts every wanted mode at nearly the same distance from the shift
     * (|mu| within 1e-5 of each other: hundreds of restarts) and costs the low modes
     * the digits of (lambda / s)^2. A tenth of the Rayleigh bound sits below the
     * lowest modes; the clamp keeps the rigid-body pivot of P(-s) (s^2 M against K's
     * rounding) above rounding, and the old choice where it was already lower. */
    double sv = 1e-3 * gd;
    if (isfinite(wrq)) sv = fmax(fmin(0.1 * wrq, sv), 1e-6 * gd);
    *s = sv;
    *g = 1e3 * sv;
    /* a defective double zero converges to ~sqrt(tol) s; and the rounding of K
     * (entries up to gmax^2 M) leaves a rigid-body value at up to ~sqrt(eps) gmax
     * (measured 5e-9 gmax on the 100k-DOF shaft, 3e-8 allowed): an elastic mode that
     * low is not resolved by the mesh's arithmetic either */
    *zero = fmax(1e-3 * sv, 3e-8 * (gmax > 0 ? gmax : gd));
}

/* Krylov sizes for nmodes modes of an n-DOF system: nev Ritz values (both members of
 * each conjugate pair) in a basis of at most ncv vectors (the first pass stops as soon
 * as they have converged, usually near 2 nev). */
void gd_sparse_ks_sizes(int n, int nmodes, int *nev, int *ncv)
{
    int n2 = 2 * n;
    *nev = 2 * nmodes;
    if (*nev > n2 - 3) *nev = n2 - 3;
    *ncv = 2 * *nev + 12; /* measured: fewer restarts beat a smaller basis */
    if (*ncv > n2 - 1) *ncv = n2 - 1;
}

int gd_sparse_ws_init(gd_sparse_ws *w, const gd_dynmat *a, int nmodes)
{
    memset(w, 0, sizeof *w);
    int nev, ncv;
    gd_sparse_ks_sizes(a->pat.n, nmodes > 0 ? nmodes : a->pat.n, &nev, &ncv);
    w->k = malloc((size_t)(a->pat.nnz > 0 ? a->pat.nnz : 1) * sizeof *w->k);
    w->d = malloc((size_t)(a->pat.nnz > 0 ? a->pat.nnz : 1) * sizeof *w->d);
    if (!w->k || !w->d || gd_ks_work_init(&w->ks, 2 * a->pat.n, ncv)) {
        gd_sparse_ws_free(w);
        return 1;
    }
    return 0;
}

void gd_sparse_ws_free(gd_sparse_ws *w)
{
    free(w->k);
    free(w->d);
    free(w->warm);
    free(w->v0);
    if (w->track_free) w->track_free(w);
    gd_ks_work_free(&w->ks);
    memset(w, 0, sizeof *w);
}

int gd_sparse_ws_chain(gd_sparse_ws *ws, int n)
{
    ws->chain = 1;
    if (ws->warm) return 0;
    ws->warm_ok = 0;
    ws->warm = malloc((size_t)2 * n * sizeof *ws->warm);
    ws->v0 = malloc((size_t)2 * n * sizeof *ws->v0);
    return !ws->warm || !ws->v0;
}

void gd_sparse_ws_remember(gd_sparse_ws *ws, const gd_modal_result *r)
{
    int n = r->ndof;
    if (!ws->warm || !r->shape_re || !r->shape_im) return;
    memset(ws->warm, 0, (size_t)2 * n * sizeof *ws->warm);
    for (int j = 0; j < r->nmodes; j++) {
        const double *re = r->shape_re + (size_t)j * n, *im = r->shape_im + (size_t)j * n;
        double lr = r->modes[j].lambda_re, li = r->modes[j].lambda_im;
        for (int i = 0; i < n; i++) {
            ws->warm[i] += re[i] + im[i];
            ws->warm[n + i] += (lr * re[i] - li * im[i]) + (lr * im[i] + li * re[i]);
        }
    }
    ws->warm_ok = 1;
}

gd_status gd_sparse_modes(const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                          gd_modal_result **out, gd_error *err)
{
    *out = NULL;
    const gd_system *sys = a->sys;
    int n = a->pat.n, n2 = 2 * n, nnz = a->pat.nnz;
    if (sys->nmassless > 0)
        return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                            "use the dense solver (it condenses massless DOFs)",
                            "the sparse eigensolver needs mass on every DOF (%d massless)",
                            sys->nmassless);
    gd_status st = GD_OK;
    int want = opt->nmodes > 0 ? opt->nmodes : n, nev, ncv;
    gd_sparse_ks_sizes(n, want, &nev, &ncv);
    gd_sparse_ws local = {0};
    if (!ws || ws->ks.ncv < ncv) {
        if (gd_sparse_ws_init(&local, a, want))
            return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                                "out of memory in the sparse eigensolver");
        ws = &local;
    }
    double *k = ws->k, *d = ws->d;
    gd_shift_invert op = {0};
    gd_ks_result ks = {0};
    cand *cd = NULL;
    double *RU = NULL; /* rigid-body shapes */
    double *ure = NULL, *uim = NULL, *px = NULL, *py = NULL;
    gd_modal_result *res = NULL;
    gd_dynmat_at_state(a, opt->speed, opt->law_state, k, d);
    int any_d = 0;
    if (opt->kind == GD_MODAL_UNDAMPED)
        memset(d, 0, (size_t)nnz * sizeof *d);
    else
        for (int i = 0; i < nnz; i++)
            any_d |= d[i] != 0;
    double s, g, rtol;
    gd_sparse_shift_auto(a, k, &s, &g, &rtol);
    if (shift > 0) {
        s = shift;
        rtol = fmax(1e-3 * s, rtol);
    }
    int rc = gd_shift_invert_setup(&op, &a->pat, a->m, sym, -s, g, k, d);
    if (rc < 0) goto nomem;
    if (rc > 0) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "", "give a different shift",
                          "the shifted matrix is singular at shift -%g", s);
        goto done;
    }
    si_ctx ctx = {&op, sym};
    if (ws->chain && gd_sparse_ws_chain(ws, n)) goto nomem;
    ws->ks.v0 = NULL;
    if (ws->chain && ws->warm_ok) {
        for (int i = 0; i < n; i++) {
            ws->v0[i] = ws->warm[i];
            ws->v0[n + i] = ws->warm[n + i] / g;
        }
        ws->ks.v0 = ws->v0;
    }
    st = gd_krylov_schur(si_apply, &ctx, n2, n, nev, ncv,
                         opt->tol > 0 ? opt->tol : GD_MODAL_TOL_DEFAULT, 200, &ws->ks, &ks);
    ws->ks.v0 = NULL;
    if (ws->chain) ws->warm_ok = 0;
    if (st == GD_ENOMEM) goto nomem;
    if (st) {
        st = gd_error_set(err, GD_ENUMERIC, sys->model->file, 0, 0, "",
                          "use the dense solver (--method dense) or fewer modes",
                          "the sparse eigensolver did not converge at speed %g rad/s", opt->speed);
        goto done;
    }
    cd = malloc((size_t)(ks.nconv > 0 ? ks.nconv : 1) * sizeof *cd);
    if (!cd) goto nomem;
    int nc = 0, nrigid_real = 0;
    /* no damping and symmetric K: the eigenvalues solve lambda^2 = -omega^2 exactly
     * (imaginary, or real for a negative stiffness), as the dense symmetric solver
     * gives them; the Ritz values carry a real part of the order of the tolerance */
    int conservative = !any_d && gd_pattern_symmetric(&a->pat, k);
    for (int i = 0; i < ks.nconv; i++) {
        double complex mu = ks.mu_re[i] + I * ks.mu_im[i];
        double complex lam = -s + 1.0 / mu;
        if (conservative) {
            double l2 = creal(lam * lam);
            lam = l2 < 0 ? I * sqrt(-l2) * (cimag(lam) < 0 ? -1 : 1) : sqrt(l2);
        }
        double lr = creal(lam), li = ks.mu_im[i] == 0 ? 0.0 : cimag(lam);
        if (li < 0) continue;
        int rigid = hypot(lr, li) <= rtol;
        if (rigid && li == 0 && (nrigid_real++ % 2)) continue;
        cd[nc++] = (cand){i, lr, li, rigid};
    }
    qsort(cd, (size_t)nc, sizeof *cd, cmp_cand);
    /* rigid-body modes: the Krylov vectors of the defective zero cluster are refined
       into the null space of K (rigid_modes.c) and separated by motion type; when that
       fails (r <= 0) the Ritz vectors are kept */
    int nrig = 0, r = 0;
    while (nrig < nc && cd[nrig].rigid)
        nrig++;
    if (nrig > 0) {
        if (!(RU = malloc((size_t)n * 2 * nrig * sizeof *RU))) goto nomem;
        for (int q = 0; q < nrig; q++) {
            memcpy(RU + (size_t)2 * q * n, ks.vec_re + (size_t)cd[q].idx * n,
                   (size_t)n * sizeof *RU);
            memcpy(RU + (size_t)(2 * q + 1) * n, ks.vec_im + (size_t)cd[q].idx * n,
                   (size_t)n * sizeof *RU);
        }
        r = gd_rigid_null_sparse(a, sym, k, s * s, rtol * rtol, RU, 2 * nrig);
        if (r > 0) gd_rigid_separate(sys, RU, r);
        if (r < 0) r = 0;
    }
    const cand *cs = r > 0 ? cd + nrig : cd;
    int ncs = r > 0 ? nc - nrig : nc;
    int km = r + ncs < want ? r + ncs : want, kr = r < km ? r : km;
    res = gd_modal_result_new(sys, km, 0);
    px = malloc((size_t)17 * n * sizeof *px);
    if (!res || !px) goto nomem;
    py = px + 2 * n;
    res->damped = any_d || opt->kind == GD_MODAL_DAMPED || !conservative;
    res->sparse = 1;
    res->speed = opt->speed;
    gd_rigid_modes_fill(sys, opt->speed, res, RU, kr);
    for (int j = kr; j < km; j++) {
        gd_mode *md = &res->modes[j];
        const cand *c = &cs[j - kr];
        md->rigid_body = c->rigid;
        if (!c->rigid) gd_mode_set_lambda(md, c->re, c->im);
        double *re = res->shape_re + (size_t)j * n, *im = res->shape_im + (size_t)j * n;
        memcpy(re, ks.vec_re + (size_t)c->idx * n, (size_t)n * sizeof *re);
        memcpy(im, ks.vec_im + (size_t)c->idx * n, (size_t)n * sizeof *im);
        gd_normalise_max(re, im, n);
    }
    const double *dd = res->damped ? d : NULL;
    if (gd_modal_residuals_on(a, k, dd, res, NULL, NULL)) goto nomem;
    /* purified where the mode fails the tolerance and its rounding floor lies well below it;
     * a mode at its floor (a fine mesh: gearbox100k) is left to the refinement, whose
     * Rayleigh-Ritz takes its eigenvalue closer (gd_sparse_modes_to_tol) */
    double tol = opt->tol > 0 ? opt->tol : GD_MODAL_TOL_DEFAULT;
    for (int j = kr; j < km; j++) {
        gd_mode *md = &res->modes[j];
        double *re = res->shape_re + (size_t)j * n, *im = res->shape_im + (size_t)j * n;
        /* not along a Campbell chain: the tracker refines its modes itself (sparse_track.c),
         * by Rayleigh-Ritz on a pair's subspace; with purified vectors the isotropic pairs
         * of tests/plot/gearbox_two_stage.yaml broke into 28 tracks instead of 16 */
        if (!ws->chain && !md->rigid_body && md->residual > tol && 100 * md->residual_floor < tol) {
            purify(&op, sym, md->lambda_re, md->lambda_im, re, im, px, py);
            gd_normalise_max(re, im, n);
            gd_mode_residual(a, k, dd, md, re, im, px + 4 * (size_t)n);
        }
        gd_mode_finish(sys, opt->speed, md, re, im,
                       res->energy_by_component + (size_t)j * sys->ncomponents);
    }
    if (ws->chain) gd_sparse_ws_remember(ws, res);
    *out = res;
    res = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the sparse eigensolver");
done:
    gd_modal_free(res);
    free(RU);
    free(cd);
    free(ure);
    free(uim);
    free(px);
    gd_ks_result_free(&ks);
    gd_shift_invert_free(&op);
    gd_sparse_ws_free(&local);
    return st;
}
