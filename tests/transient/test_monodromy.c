/* Monodromy matrix (gd_transient_monodromy): a damped oscillator against expm(A T) in
 * closed form, a damped Mathieu equation (TVMS gear pair, pinion prescribed) against a
 * fine RK4 reference, and two nonlinear cases against central differences of whole
 * transient runs: the Chen SFD gear pair under unbalance and a backlash pair whose
 * period contains contact losses (the saltation jumps). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static gd_transient_options tight(double rtol)
{
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = rtol;
    o.atol_q = 1e-6 * rtol;
    o.atol_v = 1e-3 * rtol;
    return o;
}

/* max |A - B| / max |B| over n x n, after scaling entry (i, j) by s_j / s_i (units) */
static double scaled_diff(int n, const double *A, const double *B, const double *s)
{
    double d = 0, b = 0;
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            double f = s ? s[j] / s[i] : 1.0;
            d = fmax(d, fabs(A[i + j * n] - B[i + j * n]) * f);
            b = fmax(b, fabs(B[i + j * n]) * f);
        }
    return d / b;
}

/* ------------------------------------------------------------------ damped oscillator */

static const char *oscillator = "dofs: [rz]\n"
                                "shafts:\n"
                                "  - name: a\n"
                                "    nodes: [{name: n1}]\n"
                                "disks:\n"
                                "  - {node: n1, polar_inertia: 0.01}\n"
                                "bearings:\n"
                                "  - {node: n1, k_torsion: 1000, c_torsion: 0.2}\n";

TEST(damped_oscillator_matches_expm)
{
    fx f;
    REQUIRE(load(&f, NULL, oscillator));
    gd_transient_spec spec = {0};
    gd_transient *tr;
    gd_error err;
    REQUIRE(gd_transient_new(f.s, &spec, 0.0, &tr, &err) == GD_OK);
    REQUIRE(gd_transient_nstates(tr) == 2);
    double w = sqrt(1000 / 0.01), z = 0.2 / (2 * sqrt(1000 * 0.01)), sg = z * w;
    double wd = w * sqrt(1 - z * z), T = 0.013;
    double e = exp(-sg * T), c = cos(wd * T), s = sin(wd * T);
    /* expm([0 1; -w^2 -2 z w] T) for the underdamped case */
    double ref[4] = {e * (c + sg / wd * s), -e * w * w / wd * s, e * s / wd, e * (c - sg / wd * s)};
    double y0[2] = {1e-3, 0.5}, phi[4], yend[2];
    gd_transient_options o = tight(1e-10);
    REQUIRE(gd_transient_monodromy(tr, 0.0, T, y0, &o, phi, yend, &err) == GD_OK);
    double sc[2] = {1e-6, 1e-3};
    double d = scaled_diff(2, phi, ref, sc);
    printf("     oscillator: |Phi - expm(AT)| / |expm(AT)| = %.2e\n", d);
    /* rtol 1e-10 over ~0.65 periods: the sensitivities carry the same error as y */
    CHECK(d < 1e-7);
    /* y_end = Phi y0 (linear, unforced) */
    CHECK_REL(yend[0], ref[0] * y0[0] + ref[2] * y0[1], 1e-7);
    CHECK_REL(yend[1], ref[1] * y0[0] + ref[3] * y0[1], 1e-7);
    /* bad period */
    CHECK(gd_transient_monodromy(tr, 0.0, 0.0, y0, &o, phi, NULL, &err) == GD_EINPUT);
    gd_transient_free(tr);
    fx_free(&f);
}

/* ------------------------------------------------------------------ Mathieu */

static const char *pair =
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

enum { NTAB = 512 };
static const double K0 = 2e8, CPK = 1490.0 / 2e8, JG = 4e-3;

typedef struct pair_case {
    fx f;
    gd_table *tvms, *ste;
    gd_tr_mesh m;
    gd_tr_prescribed pr;
    gd_tr_load load;
    gd_transient_spec spec;
    double ag; /* mesh vector entry of the gear's rz */
} pair_case;

/* k = K0 (1 + eps cos 20 th), STE amp sin 20 th (spline tables, NTAB points: the spline
 * error is ~1e-10 of the amplitude); pinion prescribed at nominal speed; optional
 * backlash gap and load torque on the gear. */
static int pair_setup(pair_case *c, double eps, double ste_amp, double gap, double torque)
{
    memset(c, 0, sizeof *c);
    double x[NTAB], k[NTAB], e[NTAB], per = 2 * M_PI / 20;
    for (int i = 0; i < NTAB; i++) {
        x[i] = i * per / NTAB;
        k[i] = K0 * (1 + eps * cos(20 * x[i]));
        e[i] = ste_amp * sin(20 * x[i]);
    }
    gd_error err;
    if (gd_table_new(NTAB, x, k, per, GD_INTERP_SPLINE, &c->tvms, &err)) return 0;
    if (gd_table_new(NTAB, x, e, per, GD_INTERP_SPLINE, &c->ste, &err)) return 0;
    if (!load(&c->f, NULL, pair)) return 0;
    gd_tr_mesh_init(c->f.s, 0, &c->m);
    c->m.tvms = c->tvms;
    c->m.ste = ste_amp != 0 ? c->ste : NULL;
    c->m.damping = 0.0;
    c->m.damping_per_k = CPK; /* about 5% of critical */
    c->m.damping_free = 10.0;
    c->m.backlash = gap > 0;
    c->m.gap = gap;
    int pin = dof(&c->f, "pinion", GD_RZ), gear = dof(&c->f, "gear", GD_RZ);
    c->pr = (gd_tr_prescribed){pin, {GD_PRESCRIBED_NOMINAL, 0, 0, 0, 0, NULL}};
    c->load = (gd_tr_load){gear, {GD_LOAD_CONSTANT, torque, 0, 0, 0, NULL}};
    c->spec.meshes = &c->m;
    c->spec.nmeshes = 1;
    c->spec.prescribed = &c->pr;
    c->spec.nprescribed = 1;
    c->spec.loads = &c->load;
    c->spec.nloads = torque != 0;
    gd_mesh_vector a;
    gd_system_mesh_vector(c->f.s, 0, &a);
    for (int j = 0; j < a.n; j++)
        if (a.dof[j] == gear) c->ag = a.a[j];
    return 1;
}

static void pair_free(pair_case *c)
{
    gd_table_free(c->tvms);
    gd_table_free(c->ste);
    fx_free(&c->f);
}

/* x'' = -(a^2 / J) (c(t) x' + k(t) x), k(t) = table(20-tooth angle W t) (cos is even,
 * so the driver's sense does not matter): RK4 with n steps over T from x(0) = col. */
static void mathieu_rhs(const pair_case *c, double W, double t, const double *x, double *dx)
{
    double k = gd_table_eval(c->tvms, W * t, NULL, NULL);
    double a2 = c->ag * c->ag;
    dx[0] = x[1];
    dx[1] = -a2 / JG * (CPK * k * x[1] + k * x[0]);
}

static void mathieu_reference(const pair_case *c, double W, double T, int n, double *phi)
{
    double h = T / n;
    for (int j = 0; j < 2; j++) {
        double x[2] = {j == 0, j == 1}, k1[2], k2[2], k3[2], k4[2], xt[2];
        for (int s = 0; s < n; s++) {
            double t = s * h;
            mathieu_rhs(c, W, t, x, k1);
            for (int i = 0; i < 2; i++)
                xt[i] = x[i] + 0.5 * h * k1[i];
            mathieu_rhs(c, W, t + 0.5 * h, xt, k2);
            for (int i = 0; i < 2; i++)
                xt[i] = x[i] + 0.5 * h * k2[i];
            mathieu_rhs(c, W, t + 0.5 * h, xt, k3);
            for (int i = 0; i < 2; i++)
                xt[i] = x[i] + h * k3[i];
            mathieu_rhs(c, W, t + h, xt, k4);
            for (int i = 0; i < 2; i++)
                x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
        }
        phi[2 * j] = x[0];
        phi[2 * j + 1] = x[1];
    }
}

/* largest |eigenvalue| of a 2 x 2 */
static double max_multiplier(const double *p)
{
    double tr = p[0] + p[3], det = p[0] * p[3] - p[1] * p[2], disc = tr * tr / 4 - det;
    if (disc >= 0) return fmax(fabs(tr / 2 + sqrt(disc)), fabs(tr / 2 - sqrt(disc)));
    return sqrt(det);
}

TEST(mathieu_matches_reference)
{
    pair_case c;
    REQUIRE(pair_setup(&c, 0.3, 0.0, 0.0, 0.0));
    /* w_n = sqrt(K0 a^2 / J) = 13416 rad/s; the mesh frequency 20 W: 10740 rad/s at
     * W = 537 (stable), 2 w_n at W = 1341.6 (centre of the primary tongue: with eps 0.3
     * > 4 zeta = 0.2 it is unstable) */
    const double speeds[2] = {537.0, 1341.6};
    double mult[2];
    for (int s = 0; s < 2; s++) {
        gd_transient *tr;
        gd_error err;
        REQUIRE(gd_transient_new(c.f.s, &c.spec, speeds[s], &tr, &err) == GD_OK);
        REQUIRE(gd_transient_nstates(tr) == 2);
        double T = 2 * M_PI / (20 * speeds[s]), y0[2] = {0, 0}, phi[4], ref[4];
        gd_transient_options o = tight(1e-10);
        REQUIRE(gd_transient_monodromy(tr, 0.0, T, y0, &o, phi, NULL, &err) == GD_OK);
        mathieu_reference(&c, speeds[s], T, 4000, ref);
        double sc[2] = {1e-6, 1e-3};
        double d = scaled_diff(2, phi, ref, sc);
        mult[s] = max_multiplier(phi);
        printf("     Mathieu W = %g: |Phi - ref| / |ref| = %.2e, max |multiplier| %.6f (ref "
               "%.6f)\n",
               speeds[s], d, mult[s], max_multiplier(ref));
        CHECK(d < 1e-7);
        CHECK_REL(mult[s], max_multiplier(ref), 1e-7);
        gd_transient_free(tr);
    }
    CHECK(mult[0] < 1.0);
    CHECK(mult[1] > 1.0);
    pair_free(&c);
}

/* ------------------------------------------------------------------ nonlinear */

/* Phi by central differences of whole runs over [t0, t0 + T] from y0 +/- h_j e_j,
 * h_j = 1e-4 of the state's scale (error ~h^2 plus rtol / 1e-4). */
static int fd_monodromy(gd_transient *tr, const gd_system *sys, double t0, double T,
                        const double *y0, const gd_transient_options *base, const double *scale,
                        double *phi)
{
    const int N = gd_transient_nstates(tr), nf = N / 2, n = sys->ndof;
    /* the free DOFs in increasing order: a run's full q0 from the state */
    int *fd = malloc((size_t)nf * sizeof *fd);
    double *q0 = calloc((size_t)n, sizeof *q0), *v0 = calloc((size_t)n, sizeof *v0);
    double *yp = malloc((size_t)N * sizeof *yp), *col = malloc((size_t)N * sizeof *col);
    int ok = fd && q0 && v0 && yp && col;
    /* every DOF is free in these cases except the prescribed ones, found as those the
     * problem does not count: here the free DOFs are the last nf */
    for (int i = 0; ok && i < nf; i++)
        fd[i] = n - nf + i;
    gd_transient_options o = *base;
    o.t_start = t0;
    o.t_end = t0 + T;
    o.record_from = t0 + T;
    o.init = GD_TR_INIT_GIVEN;
    o.q0 = q0;
    o.v0 = v0;
    for (int j = 0; ok && j < N; j++) {
        double h = 1e-4 * (fabs(y0[j]) + scale[j]);
        for (int sgn = -1; ok && sgn <= 1; sgn += 2) {
            memcpy(yp, y0, (size_t)N * sizeof *yp);
            yp[j] += sgn * h;
            for (int i = 0; i < nf; i++) {
                q0[fd[i]] = yp[i];
                v0[fd[i]] = yp[nf + i];
            }
            gd_transient_result *r = NULL;
            gd_error err;
            if (gd_transient_run(tr, &o, NULL, 0, &r, &err)) {
                ok = 0;
                break;
            }
            for (int i = 0; i < nf; i++) {
                double a = r->q_end[fd[i]], b = r->v_end[fd[i]];
                col[i] = sgn < 0 ? a : (a - col[i]) / (2 * h);
                col[nf + i] = sgn < 0 ? b : (b - col[nf + i]) / (2 * h);
            }
            gd_transient_result_free(r);
        }
        memcpy(phi + (size_t)N * j, col, (size_t)N * sizeof *phi);
    }
    free(fd);
    free(q0);
    free(v0);
    free(yp);
    free(col);
    return ok;
}

/* state [q_f; v_f] at the end of a run of duration t_settle from rest */
static int settle(gd_transient *tr, double t_settle, const gd_transient_options *base, double *y)
{
    const int N = gd_transient_nstates(tr), nf = N / 2;
    gd_transient_options o = *base;
    o.t_end = t_settle;
    o.record_from = t_settle;
    gd_transient_result *r = NULL;
    gd_error err;
    if (gd_transient_run(tr, &o, NULL, 0, &r, &err)) return 0;
    for (int i = 0; i < nf; i++) {
        y[i] = r->q_end[r->ndof - nf + i];
        y[nf + i] = r->v_end[r->ndof - nf + i];
    }
    gd_transient_result_free(r);
    return 1;
}

TEST(chen_sfd_pair_matches_differences_of_runs)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    gd_transient_model *tm;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nsfds == 1);
    gd_transient *tr;
    const double W = 1500.0, T = 2 * M_PI / W; /* unbalance period */
    REQUIRE(gd_transient_new(f.s, &tm->spec, W, &tr, &err) == GD_OK);
    const int N = gd_transient_nstates(tr);
    REQUIRE(N == 12);
    double y0[12], phi[144], ref[144], sc[12];
    gd_transient_options o = tight(1e-8);
    REQUIRE(settle(tr, 20 * T, &o, y0));
    for (int i = 0; i < N; i++)
        sc[i] = i < N / 2 ? o.atol_q / o.rtol : o.atol_v / o.rtol;
    double t0 = 20 * T;
    o = tight(1e-10);
    REQUIRE(gd_transient_monodromy(tr, t0, T, y0, &o, phi, NULL, &err) == GD_OK);
    gd_transient_options of = tight(1e-12);
    REQUIRE(fd_monodromy(tr, f.s, t0, T, y0, &of, sc, ref));
    double d = scaled_diff(N, phi, ref, sc);
    printf("     Chen SFD pair, W = %g rad/s: |Phi - FD of runs| / |Phi| = %.2e\n", W, d);
    /* FD of runs: h = 1e-4 of the scale, runs at rtol 1e-12: ~1e-8 error; Phi at 1e-10 */
    CHECK(d < 1e-6);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

TEST(backlash_pair_with_impacts_matches_differences_of_runs)
{
    pair_case c;
    /* static deflection F0 / k = 5 um, STE 12 um near the resonance W = 671 (mesh
     * frequency = w_n): the teeth separate every mesh period */
    REQUIRE(pair_setup(&c, 0.2, 12e-6, 20e-6, 1000.0 * 0.06));
    const double W = 640.0, T = 2 * M_PI / (20 * W);
    gd_transient *tr;
    gd_error err;
    REQUIRE(gd_transient_new(c.f.s, &c.spec, W, &tr, &err) == GD_OK);
    double y0[2], phi[4], ref[4], sc[2] = {1e-6, 1e-3};
    gd_transient_options o = tight(1e-9);
    o.init = GD_TR_INIT_STATIC;
    REQUIRE(settle(tr, 60 * T, &o, y0));
    o.init = GD_TR_INIT_GIVEN;
    /* the period from y0 holds contact losses (else the saltation is not exercised) */
    {
        double q0[2] = {0, y0[0]}, v0[2] = {0, y0[1]};
        gd_transient_options r = tight(1e-9);
        r.t_start = 60 * T;
        r.t_end = 61 * T;
        r.init = GD_TR_INIT_GIVEN;
        r.q0 = q0;
        r.v0 = v0;
        gd_transient_result *res = NULL;
        REQUIRE(gd_transient_run(tr, &r, NULL, 0, &res, &err) == GD_OK);
        printf("     backlash pair: %d contact losses, %d drive impacts in the period\n",
               res->contacts[0].contact_losses, res->contacts[0].drive_impacts);
        CHECK(res->contacts[0].contact_losses >= 1);
        gd_transient_result_free(res);
    }
    o = tight(1e-10);
    REQUIRE(gd_transient_monodromy(tr, 60 * T, T, y0, &o, phi, NULL, &err) == GD_OK);
    gd_transient_options of = tight(1e-12);
    REQUIRE(fd_monodromy(tr, c.f.s, 60 * T, T, y0, &of, sc, ref));
    double d = scaled_diff(2, phi, ref, sc);
    printf("     backlash pair: |Phi - FD of runs| / |Phi| = %.2e, max |multiplier| %.4f\n", d,
           max_multiplier(phi));
    CHECK(d < 1e-6);
    /* without the saltation jumps the difference is 4.9e-2 (measured): the test can fail */
    gd_transient_free(tr);
    pair_free(&c);
}

RUN_TESTS(T(damped_oscillator_matches_expm), T(mathieu_matches_reference),
          T(chen_sfd_pair_matches_differences_of_runs),
          T(backlash_pair_with_impacts_matches_differences_of_runs))
