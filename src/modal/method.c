/* Choosing the eigensolver: dense LAPACK or sparse shift-invert, by a cost model
 * whose constants were measured once (bench/bench_modal_method.c, see below), not by a
 * DOF count. The dense cost grows as n^3 whatever the structure; the sparse cost is
 * the KLU factorisation (its flop estimate from the AMD analysis), one solve with the
 * factors and two products with the pattern per Krylov vector, and the
 * orthogonalisation of a basis of ncv vectors of length 2n. */
#include <math.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "modal/modal_impl.h"

/* Seconds per unit, fitted to bench/bench_modal_method (Release, one thread, OpenBLAS,
 * x86-64 2-core VM, 2026-11-23) on the MMT rig refined to 170 and 1010 DOFs and the
 * 366-DOF bench rotor (bench/models/rig366.yaml) at 3000 rpm, 6, 12 and 30 modes:
 * - dense state space (balance, Hessenberg-QR, inverse iteration on 2n, plus assembly
 *   and normalisation): 27 ms at n = 170, 175 ms at n = 366, 1.6 s at n = 1010, which
 *   grows as n^2.3 in this range: C_DENSE2 (2n)^2 + C_DENSE3 (2n)^3 within 30 %;
 * - dense symmetric (undamped, dsygvx on n): 0.18 ms at n = 30, 0.38 ms at 50, 2.7 ms
 *   at 170, 11 ms at 366, 115 ms at 1010: C_SYM0 + C_SYM2 n^2 + C_SYM3 n^3 within 30 %;
 * - sparse: 0.9 ms (n 170, 6 modes), 2.4 ms (366, 12), 5.9 ms (366, 30), 3.8 ms
 *   (1010, 12), 13.8 ms (1010, 30), 0.22 ms (30, 6, undamped): C_FIXED + C_DOF n + C_APPLY x
 * entries touched by the shift-invert products (factors, M and D, vectors) over 2 ncv Krylov
 * vectors + C_ORTH 2n ncv^2 (Gram-Schmidt) + C_SCHUR ncv^3 (Schur form of the projected matrix),
 * within 30 %; C_LU per flop of the KLU factorisation (AMD's estimate). */
#define C_DENSE2 2.0e-7
#define C_DENSE3 9.4e-11
#define C_SYM0 1.0e-4
#define C_SYM2 6.5e-8
#define C_SYM3 4.8e-11
#define C_FIXED 2.0e-4
#define C_DOF 1.6e-6
#define C_APPLY 3.0e-10
#define C_ORTH 2.0e-10
#define C_SCHUR 1.0e-9
#define C_LU 1.0e-9

int gd_sparse_applicable(const gd_system *sys, int nmodes)
{
    return nmodes > 0 && sys->nmassless == 0 && 2 * nmodes + 16 < sys->ndof;
}

double gd_cost_dense(int n, int damped, int nmodes)
{
    (void)nmodes; /* the reduction to condensed form dominates however many are kept */
    double m = damped ? 2.0 * n : (double)n;
    if (!damped) return C_SYM0 + C_SYM2 * m * m + C_SYM3 * m * m * m;
    return C_DENSE2 * m * m + C_DENSE3 * m * m * m;
}

double gd_cost_sparse(const gd_pattern *p, const gd_splu_symbolic *sym, int nmodes)
{
    int nev, ncv;
    gd_sparse_ks_sizes(p->n, nmodes, &nev, &ncv);
    double lu = sym->sym->lnz + sym->sym->unz, flops = sym->sym->est_flops;
    double nvec = 2.0 * ncv, n2 = 2.0 * p->n, c = ncv;
    return C_FIXED + C_DOF * p->n + C_LU * flops +
           C_APPLY * nvec * (lu + 2.0 * p->nnz + 4.0 * p->n) + C_ORTH * n2 * c * c +
           C_SCHUR * c * c * c;
}

int gd_modal_damped_at(const gd_dynmat *a, const gd_modal_options *opt, double *k, double *d)
{
    if (opt->kind == GD_MODAL_DAMPED) return 1;
    gd_dynmat_at_state(a, opt->speed, opt->law_state, k, d);
    if (!gd_pattern_symmetric(&a->pat, k)) return 1;
    if (opt->kind == GD_MODAL_UNDAMPED) return 0;
    for (int q = 0; q < a->pat.nnz; q++)
        if (d[q] != 0.0) return 1;
    return 0;
}

/* LAPACK's modes and their residuals (gd_mode.residual, the same measure as the
 * sparse solver's) */
static gd_status dense_with_residuals(const gd_system *sys, const gd_modal_options *opt,
                                      gd_modal_result **out, gd_error *err)
{
    /* the laws' operating state, solved once for the modes and their residuals */
    gd_modal_options o = *opt;
    double *q = NULL;
    if (!o.law_state && sys->nlaws) {
        q = malloc((size_t)sys->ndof * sizeof *q);
        if (!q) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        gd_system_law_state(sys, o.speed, q);
        o.law_state = q;
    }
    gd_status st = gd_modal_solve_dense(sys, &o, out, err);
    if (!st && gd_modal_energies_laws(sys, *out, o.law_state))
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (!st && (st = gd_modal_residuals(sys, *out, o.law_state, err))) {
        gd_modal_free(*out);
        *out = NULL;
    }
    free(q);
    return st;
}

gd_status gd_modal_solve(const gd_system *sys, const gd_modal_options *opt, gd_modal_result **out,
                         gd_error *err)
{
    *out = NULL;
    if (!(opt->tol >= 0 && opt->tol < 1))
        return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "tol",
                            "give a relative residual between 1e-14 and 1e-3, e.g. 1e-10, or 0 "
                            "for the default 1e-9",
                            "tolerance %g is not a relative residual below 1", opt->tol);
    int sparse_ok = gd_sparse_applicable(sys, opt->nmodes) && !opt->want_left;
    if (opt->method == GD_EIG_SPARSE) {
        if (opt->want_left)
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "method",
                                "use the dense method for left eigenvectors",
                                "the sparse eigensolver gives right eigenvectors only");
        if (opt->nmodes <= 0)
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "method",
                                "use the dense method (or ask for a number of modes)",
                                "the sparse eigensolver computes the lowest modes, not all");
        if (sys->nmassless > 0)
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "method",
                                "use the dense method (or auto)",
                                "the sparse eigensolver needs mass or inertia on every DOF; "
                                "this model has %d massless DOFs",
                                sys->nmassless);
        /* the Krylov basis (2 ncv <= 2n states) must hold the 2 N wanted values and as many
         * more for the restarts: N <= (n - 1) / 2 (gd_sparse_ks_sizes) */
        if (2 * opt->nmodes + 1 > sys->ndof) {
            char hint[96];
            snprintf(hint, sizeof hint,
                     "use the dense method (or auto), or ask for at most %d modes",
                     (sys->ndof - 1) / 2);
            return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "method", hint,
                                "the sparse eigensolver computes at most (DOFs - 1) / 2 modes: "
                                "%d modes of a %d-DOF model",
                                opt->nmodes, sys->ndof);
        }
        return gd_modal_solve_sparse(sys, opt, 0, out, err);
    }
    if (opt->method == GD_EIG_DENSE || !sparse_ok) return dense_with_residuals(sys, opt, out, err);
    /* AUTO: the pattern and its AMD analysis cost O(nnz), far below either solve */
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) {
        gd_dynmat_free(&a);
        return st;
    }
    gd_sparse_ws ws;
    if (gd_sparse_ws_init(&ws, &a, opt->nmodes)) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the eigensolver");
    } else {
        int damped = gd_modal_damped_at(&a, opt, ws.k, ws.d);
        if (err) gd_error_clear(err);
        if (gd_cost_sparse(&a.pat, &sym, opt->nmodes) <
            gd_cost_dense(sys->ndof, damped, opt->nmodes))
            st = gd_sparse_modes_to_tol(&a, &sym, opt, 0, &ws, out, err);
        else
            st = GD_ENUMERIC;  /* dense below */
        if (st == GD_ENUMERIC) /* also when Krylov-Schur did not converge */
            st = dense_with_residuals(sys, opt, out, err);
        gd_sparse_ws_free(&ws);
    }
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    return st;
}
