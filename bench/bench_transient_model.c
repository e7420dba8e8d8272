/* Time-integration benchmark of a model file with its own time-integration keys (e.g.
 * examples/ducati_timing_geartrain.yaml): the spec from gd_transient_model_build, the
 * model's speed, REVS revolutions of the reference shaft from rest. Prints steps per
 * second, right-hand-side evaluations per simulated second and the cost of one
 * evaluation relative to one sparse product K x.
 * usage: bench_transient_model MODEL.yaml [REVS] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "geardyn/transient_model.h"
#include "linalg/linalg_impl.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_transient_model MODEL.yaml [REVS]\n");
        return 2;
    }
    double revs = argc > 2 ? atof(argv[2]) : 2.0;
    gd_error err;
    gd_model *model = NULL;
    gd_system *sys = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_transient_result *r = NULL;
    int rc = 1;
    gd_status st = gd_model_load(argv[1], &model, &err);
    if (!st) st = gd_system_build(model, &sys, &err);
    if (!st) st = gd_transient_model_build(sys, &tm, &err);
    if (st || !(model->speed > 0)) {
        fprintf(stderr, "bench_transient_model: %s\n", st ? err.message : "model has no speed");
        goto out;
    }
    double t0 = now();
    st = gd_transient_new(sys, &tm->spec, model->speed, &tr, &err);
    double t_create = now() - t0;
    if (st) {
        fprintf(stderr, "bench_transient_model: %s\n", err.message);
        goto out;
    }
    double t_end = 2 * M_PI * revs / model->speed;
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = t_end;
    o.output_interval = t_end / 2000;
    gd_tr_record rec[1] = {{GD_REC_MESH_FORCE, 0, 0}};
    t0 = now();
    st = gd_transient_run(tr, &o, rec, model->nmeshes ? 1 : 0, &r, &err);
    double t_run = now() - t0;
    if (st) {
        fprintf(stderr, "bench_transient_model: %s\n", err.message);
        goto out;
    }
    int ns = gd_transient_nstates(tr), n = sys->ndof;
    double *y = malloc((size_t)ns * sizeof *y), *yd = malloc((size_t)ns * sizeof *yd);
    double *qv = malloc((size_t)n * sizeof *qv), *kq = malloc((size_t)n * sizeof *kq);
    for (int i = 0; i < ns; i++)
        y[i] = 1e-7 * sin(1.7 * i);
    for (int i = 0; i < n; i++)
        qv[i] = 1e-7 * cos(0.3 * i);
    int reps = n > 500 ? 2000 : 200000;
    gd_transient_set_contacts(tr, 0, y);
    t0 = now();
    for (int i = 0; i < reps; i++)
        gd_transient_rhs(tr, 1e-6 * i, y, yd);
    double t_rhs = (now() - t0) / reps;
    t0 = now();
    for (int i = 0; i < reps; i++) {
        qv[i % n] += 1e-20;
        gd_csc_mul(&sys->K, qv, kq);
    }
    double t_kx = (now() - t0) / reps;
    int losses = 0, coast = 0;
    for (int i = 0; i < r->nmeshes; i++) {
        losses += r->contacts[i].contact_losses;
        coast += r->contacts[i].coast_impacts;
    }
    printf("%s: %d DOFs (%d states), %d nonlinear meshes, %d cam valve trains, %g rpm, %g "
           "revolutions = %.4g s simulated\n",
           argv[1], n, ns, tm->spec.nmeshes, tm->spec.ncams, model->speed * 30 / M_PI, revs, t_end);
    printf("  set-up %.3g ms; run %.3g s: %ld steps (%.0f steps/s), %ld RHS evaluations "
           "(%.3g per simulated s), %ld GMRES iterations, %ld preconditioner set-ups\n",
           1e3 * t_create, t_run, r->steps, r->steps / t_run, r->rhs_evals, r->rhs_evals / t_end,
           r->lin_iters, r->prec_setups);
    printf("  contact: %d losses, %d coast impacts over all meshes, %ld located events\n", losses,
           coast, r->events);
    printf("  one RHS %.3g us, one K x %.3g us (nnz %d): ratio %.2f\n", 1e6 * t_rhs, 1e6 * t_kx,
           sys->K.colptr[n], t_rhs / t_kx);
    free(y);
    free(yd);
    free(qv);
    free(kq);
    rc = 0;
out:
    gd_transient_result_free(r);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(sys);
    gd_model_free(model);
    return rc;
}
