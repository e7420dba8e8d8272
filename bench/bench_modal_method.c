/* The dense/sparse choice of `geardyn modal --modes N`: times the dense (LAPACK) and
 * the sparse (shift-invert Krylov-Schur + KLU) solvers on one model, prints the cost
 * model's estimates (src/modal/method.c) beside them, what AUTO picks, and how far the
 * two solvers' eigenvalues are apart. The constants of the cost model were fitted to
 * this output. Asserts nothing.
 * usage: bench_modal_method MODEL SPEED_RAD_S NMODES [REPEATS] [--no-dense] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "geardyn/model_file.h"
#include "geardyn/modal.h"
#include "modal/modal_impl.h"

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t); /* CPU: the machine is shared */
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static double best_of(const gd_system *s, gd_modal_options *o, gd_eig_method m, int reps,
                      gd_modal_result **keep)
{
    double best = 1e30;
    gd_error err;
    o->method = m;
    for (int r = 0; r < reps; r++) {
        gd_modal_result *res;
        double t0 = now();
        if (gd_modal_solve(s, o, &res, &err)) {
            fprintf(stderr, "%s\n", err.message);
            exit(1);
        }
        double t = now() - t0;
        if (t < best) best = t;
        if (r == reps - 1 && keep)
            *keep = res;
        else
            gd_modal_free(res);
    }
    return best;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: bench_modal_method MODEL SPEED NMODES [REPEATS] [--no-dense]\n");
        return 2;
    }
    int reps = argc > 4 && argv[4][0] != '-' ? atoi(argv[4]) : 3, dense = 1;
    for (int i = 4; i < argc; i++)
        if (!strcmp(argv[i], "--no-dense")) dense = 0;
    gd_error err;
    gd_model *m;
    gd_system *s;
    if (gd_model_load(argv[1], &m, &err) || gd_system_build(m, &s, &err)) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = atof(argv[2]);
    o.nmodes = atoi(argv[3]);
    o.want_left = 0;
    gd_dynmat a;
    gd_splu_symbolic sym;
    if (gd_dynmat_build(s, &a, &err) || gd_splu_analyze(&a.pat, &sym, &err)) return 1;
    double *k = malloc((size_t)a.pat.nnz * sizeof *k), *d = malloc((size_t)a.pat.nnz * sizeof *d);
    int damped = gd_modal_damped_at(&a, &o, k, d), nev, ncv;
    gd_sparse_ks_sizes(s->ndof, o.nmodes, &nev, &ncv);
    double cs = gd_cost_sparse(&a.pat, &sym, o.nmodes), cd = gd_cost_dense(s->ndof, damped, 0);
    gd_modal_result *rs = NULL, *rd = NULL;
    double ts = best_of(s, &o, GD_EIG_SPARSE, reps, &rs);
    double td = dense ? best_of(s, &o, GD_EIG_DENSE, reps, &rd) : NAN;
    double ta = best_of(s, &o, GD_EIG_AUTO, reps, NULL);
    double dev = 0;
    if (rd)
        for (int j = 0; j < rs->nmodes && j < rd->nmodes; j++)
            dev = fmax(dev, hypot(rs->modes[j].lambda_re - rd->modes[j].lambda_re,
                                  rs->modes[j].lambda_im - rd->modes[j].lambda_im) /
                                fmax(rd->modes[j].omega_n, 1.0));
    printf("model %s: n %d nnz %d lnz+unz %.0f est_flops %.3g ncv %d damped %d modes %d\n", argv[1],
           s->ndof, a.pat.nnz, sym.sym->lnz + sym.sym->unz, sym.sym->est_flops, ncv, damped,
           o.nmodes);
    printf("sparse   %9.6f s   model %9.6f s\n", ts, cs);
    printf("dense    %9.6f s   model %9.6f s\n", td, cd);
    printf("auto     %9.6f s   picks %s\n", ta, cs < cd ? "sparse" : "dense");
    if (rd) printf("max |lambda_sparse - lambda_dense| / max(omega_n, 1) %.3g\n", dev);
    gd_modal_free(rs);
    gd_modal_free(rd);
    free(k);
    free(d);
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    gd_system_free(s);
    gd_model_free(m);
    return 0;
}
