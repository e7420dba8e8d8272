/* Time-integration benchmark: steps per second, right-hand-side evaluations per
 * simulated second and the cost of one evaluation relative to one sparse product K x,
 * on a torsional gear pair with backlash, TVMS and STE (impacting), and on an FE model
 * given as a file (e.g. the rig refined to ~1000 DOFs) with one backlash mesh.
 * usage: bench_transient [FE_MODEL.yaml] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#include "geardyn/transient.h"
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

static const char *pair_yaml =
    "dofs: [rz]\n"
    "shafts:\n"
    "  - name: input\n"
    "    nodes: [{name: pinion}]\n"
    "  - name: output\n"
    "    nodes: [{name: gear}]\n"
    "disks:\n"
    "  - {node: pinion, polar_inertia: 1e-3}\n"
    "  - {node: gear, polar_inertia: 4e-3}\n"
    "meshes:\n"
    "  - {name: mesh, driver: pinion, driven: gear, teeth: [20, 40],\n"
    "     base_radius: [0.03, 0.06], pressure_angle: 20 deg, stiffness: 2e8,\n"
    "     coupling: torsional}\n";

/* Runs one case and prints its figures. driver/driven: node names of the mesh. */
static int bench(const char *label, const char *yaml, const char *path, double speed, int teeth,
                 double gap, double ste, double F0, double t_end)
{
    gd_error err;
    gd_model *model = NULL;
    gd_system *sys = NULL;
    gd_status st = path ? gd_model_load(path, &model, &err)
                        : gd_model_load_string(yaml, "pair.yaml", &model, &err);
    if (!st) st = gd_system_build(model, &sys, &err);
    if (st) {
        fprintf(stderr, "bench_transient: %s: %s\n", label, err.message);
        gd_model_free(model);
        return 1;
    }
    const gd_mesh *gm = &model->meshes[0];
    int drv = gd_system_dof(sys, gm->driver, GD_RZ), dvn = gd_system_dof(sys, gm->driven, GD_RZ);
    /* TVMS +-20 % and STE sin, over one mesh period */
    enum { N = 64 };
    double x[N], k[N], e[N], per = 2 * M_PI / teeth;
    for (int i = 0; i < N; i++) {
        x[i] = i * per / N;
        k[i] = gm->stiffness * (1 + 0.2 * cos(teeth * x[i]));
        e[i] = ste * sin(teeth * x[i]);
    }
    gd_table *tk = NULL, *te = NULL;
    gd_table_new(N, x, k, per, GD_INTERP_SPLINE, &tk, &err);
    gd_table_new(N, x, e, per, GD_INTERP_SPLINE, &te, &err);
    gd_tr_mesh m;
    gd_tr_mesh_init(sys, 0, &m);
    m.tvms = tk;
    m.ste = te;
    m.damping_per_k = 0.05 * 2 / (teeth * speed * 1.25); /* ~5 % near the mesh mode */
    m.damping = 0;
    m.damping_free = 10;
    m.backlash = 1;
    m.gap = gap;
    gd_mesh_vector a;
    gd_system_mesh_vector(sys, 0, &a);
    double ag = 0;
    for (int j = 0; j < a.n; j++)
        if (a.dof[j] == dvn) ag = a.a[j];
    gd_tr_prescribed pr = {drv, {GD_PRESCRIBED_NOMINAL, 0, 0, 0, 0, NULL}};
    gd_tr_load load = {dvn, {GD_LOAD_CONSTANT, F0 * ag, 0, 0, 0, NULL}};
    gd_transient_spec spec = {0};
    spec.meshes = &m;
    spec.nmeshes = 1;
    spec.prescribed = &pr;
    spec.nprescribed = 1;
    spec.loads = &load;
    spec.nloads = 1;
    gd_transient *tr = NULL;
    double t0 = now();
    st = gd_transient_new(sys, &spec, speed, &tr, &err);
    double t_create = now() - t0;
    if (st) {
        fprintf(stderr, "bench_transient: %s: %s\n", label, err.message);
        goto out;
    }
    gd_tr_record rec[2] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_MESH_STATE, 0, 0}};
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = t_end;
    o.output_interval = t_end / 2000;
    o.init = GD_TR_INIT_STATIC;

    gd_transient_result *r = NULL, *rg = NULL;
    t0 = now();
    st = gd_transient_run(tr, &o, rec, 2, &r, &err);
    if (st) {
        fprintf(stderr, "bench_transient: %s: %s\n", label, err.message);
        goto out;
    }
    double t_run = r->cpu_seconds; /* CPU: the machine may be shared */
    /* the same with fixed-step generalized-alpha, 40 steps per mesh period */
    double period = 2 * M_PI / (teeth * speed);
    o.method = GD_TR_GEN_ALPHA;
    o.step = period / 40;
    t0 = now();
    st = gd_transient_run(tr, &o, rec, 2, &rg, &err);
    (void)t0;
    if (st) {
        fprintf(stderr, "bench_transient: %s: galpha: %s\n", label, err.message);
        gd_transient_result_free(r);
        goto out;
    }
    double fdev = 0, fpk = 0;
    for (int i = 0; i < r->nout; i++) {
        fpk = fmax(fpk, fabs(r->values[i]));
        fdev = fmax(fdev, fabs(rg->values[i] - r->values[i]));
    }
    /* one RHS vs one K x */
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
        gd_transient_rhs(tr, 1e-5 * i, y, yd);
    double t_rhs = (now() - t0) / reps;
    t0 = now();
    for (int i = 0; i < reps; i++) {
        qv[i % n] += 1e-20;
        gd_csc_mul(&sys->K, qv, kq);
    }
    double t_kx = (now() - t0) / reps;
    printf("%s: %d DOFs (%d states), %.3g s simulated, mesh period %.3g ms\n", label, n, ns, t_end,
           1e3 * 2 * M_PI / (teeth * speed));
    printf("  set-up %.3g ms; run %.3g s: %ld steps (%.0f steps/s), %ld RHS evaluations "
           "(%.3g per simulated s), %ld GMRES iterations, %ld preconditioner set-ups\n",
           1e3 * t_create, t_run, r->steps, r->steps / t_run, r->rhs_evals, r->rhs_evals / t_end,
           r->lin_iters, r->prec_setups);
    printf("  contact: %d losses, %d coast impacts, separated %.3g ms, %ld located events\n",
           r->contacts[0].contact_losses, r->contacts[0].coast_impacts,
           1e3 * r->contacts[0].separated_time, r->events);
    printf("  galpha (rho_inf 0.9, h = period/40 = %.3g us): run %.3g s CPU: %ld steps (%.0f "
           "steps/s), "
           "%ld Newton iterations, %d losses, %d coast impacts; mesh force vs CVODE: max "
           "difference %.3g of the peak\n",
           1e6 * o.step, rg->cpu_seconds, rg->steps, rg->steps / rg->cpu_seconds, rg->lin_iters,
           rg->contacts[0].contact_losses, rg->contacts[0].coast_impacts, fdev / fpk);
    /* and on the modal-reduced problem (Craig-Bampton; interior modes below the cutoff,
     * GD_BENCH_CUTOFF Hz, default 10 kHz) */
    double fc = getenv("GD_BENCH_CUTOFF") ? atof(getenv("GD_BENCH_CUTOFF")) : 1e4;
    gd_transient *trr = NULL;
    gd_transient_result *rr = NULL;
    t0 = now();
    st = gd_transient_new_reduced(sys, &spec, speed, 2 * M_PI * fc, &trr, &err);
    double t_red = now() - t0;
    if (!st) st = gd_transient_run(trr, &o, rec, 2, &rr, &err);
    if (st) {
        fprintf(stderr, "bench_transient: %s: reduced: %s\n", label, err.message);
    } else {
        int nk, nmd;
        gd_transient_reduced_size(trr, &nk, &nmd);
        double dc = 0, dg = 0;
        for (int i = 0; i < r->nout; i++) {
            dc = fmax(dc, fabs(rr->values[i] - r->values[i]));
            dg = fmax(dg, fabs(rr->values[i] - rg->values[i]));
        }
        printf("  reduced to %d kept DOFs + %d modes below %g kHz (set-up %.3g s) + galpha: run "
               "%.3g s, %.0f steps/s, %d losses; mesh force: max difference %.3g of the peak "
               "vs CVODE, %.3g vs full galpha\n",
               nk, nmd, fc / 1e3, t_red, rr->cpu_seconds, rr->steps / rr->cpu_seconds,
               rr->contacts[0].contact_losses, dc / fpk, dg / fpk);
    }
    gd_transient_result_free(rr);
    gd_transient_free(trr);
    st = GD_OK;
    gd_transient_result_free(rg);
    printf("  one RHS %.3g us, one K x %.3g us (nnz %d): ratio %.2f\n", 1e6 * t_rhs, 1e6 * t_kx,
           sys->K.colptr[n], t_rhs / t_kx);
    (void)kq;
    free(y);
    free(yd);
    free(qv);
    free(kq);
    gd_transient_result_free(r);
out:
    gd_transient_free(tr);
    gd_table_free(tk);
    gd_table_free(te);
    gd_system_free(sys);
    gd_model_free(model);
    return st ? 1 : 0;
}

int main(int argc, char **argv)
{
    int rc = bench("torsional pair, backlash + TVMS + STE (impacting)", pair_yaml, NULL, 537.0, 20,
                   3e-6, 1e-5, 1000.0, 0.05);
    if (argc > 1)
        rc |= bench("FE rig, one backlash mesh + TVMS + STE, 3000 rpm", NULL, argv[1], 314.159, 48,
                    10e-6, 5e-6, 500.0, 0.002);
    return rc;
}
