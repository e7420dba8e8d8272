/* Bearings from physics at the static state (docs/bearings.md): the nonlinear static
 * equilibrium with rolling-bearing laws (a roller's 10/9 contact inside a clearance,
 * issue 38 M2), the operating point the linear analyses linearise about (a gear train
 * free in torsion, driven at the input and held at the output, issue 34), each law's
 * tangent there against central differences of its force, and the located error of a
 * bearing that cannot carry its load. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lapacke.h>

#include "geardyn/campbell.h"
#include "geardyn/law_type.h"
#include "geardyn/modal.h"
#include "geardyn/static.h"
#include "harness.h"
#include "model_support.h"

/* One mass on a roller bearing (Z 12, K 1e9 N/m^(10/9), clearance 5 um) under 200 N
 * along -y: the M2 case. */
#define M2_MODEL(EXP)                                                                              \
    "dofs: [x, y]\n"                                                                               \
    "shafts:\n"                                                                                    \
    "  - name: s\n"                                                                                \
    "    nodes: [{name: m}]\n"                                                                     \
    "disks:\n"                                                                                     \
    "  - {name: m, node: m, mass: 10}\n"                                                           \
    "laws:\n"                                                                                      \
    "  - {type: rolling_bearing, name: b, node: m, elements: 12, contact_stiffness: 1e9,\n"        \
    "     exponent: " EXP ", clearance: 5 um, pitch_diameter: 40 mm, element_diameter: 8 mm,\n"    \
    "     phase: -90 deg}\n"                                                                       \
    "excitations:\n"                                                                               \
    "  loads:\n"                                                                                   \
    "    - {node: m, dof: y, value: -200}\n"

/* The bearing's load at downward deflection d: sum over elements of K (d cos psi - g)^n
 * cos psi, element 0 at the bottom (phase -90 deg). */
static double roller_load(double d, double n)
{
    double F = 0;
    for (int j = 0; j < 12; j++) {
        double c = cos(2 * M_PI * j / 12), e = d * c - 5e-6;
        if (e > 0) F += 1e9 * pow(e, n) * c;
    }
    return F;
}

/* and its stiffness dF/dd and the lateral one (x) */
static void roller_stiffness(double d, double n, double *ky, double *kx)
{
    *ky = *kx = 0;
    for (int j = 0; j < 12; j++) {
        double c = cos(2 * M_PI * j / 12), s = sin(2 * M_PI * j / 12), e = d * c - 5e-6;
        if (e <= 0) continue;
        *ky += n * 1e9 * pow(e, n - 1) * c * c;
        *kx += n * 1e9 * pow(e, n - 1) * s * s;
    }
}

/* The M2 roller (and the same bearing with ball contact) finds its equilibrium: the
 * deflection against bisection of the load sum (1e-9: the Newton residual is 1e-10 of the
 * load, the bisection exact to 1e-15), and modal's two frequencies against sqrt(k/m)
 * from the closed-form stiffness at that deflection (1e-7: the eigensolver's rounding on
 * well separated frequencies is far below). */
TEST(roller_in_its_clearance_finds_equilibrium)
{
    const char *exps[2] = {"1.1111111111111111", "1.5"};
    for (int e = 0; e < 2; e++) {
        char yaml[1200];
        snprintf(yaml, sizeof yaml, "%s",
                 e == 0 ? M2_MODEL("1.1111111111111111") : M2_MODEL("1.5"));
        double n = atof(exps[e]);
        fx f;
        REQUIRE(load(&f, NULL, yaml));
        gd_static_options o;
        gd_static_options_init(&o);
        gd_static_result *r = NULL;
        gd_error err;
        REQUIRE(gd_static_run(f.s, &o, &r, &err) == GD_OK);
        double lo = 5e-6, hi = 1e-3;
        for (int i = 0; i < 200; i++) {
            double mid = 0.5 * (lo + hi);
            (roller_load(mid, n) > 200 ? (hi = mid) : (lo = mid));
        }
        double d = 0.5 * (lo + hi);
        int iy = dof(&f, "m", GD_Y), ix = dof(&f, "m", GD_X);
        printf("  exponent %.4g: deflection %.6g um (bisection %.6g um), fy %.10g N\n", n,
               -r->q[iy] * 1e6, d * 1e6, r->laws[0].records[1]);
        CHECK_REL(-r->q[iy], d, 1e-9);
        CHECK_ABS(r->q[ix], 0.0, 1e-12 * d);
        CHECK_REL(r->laws[0].records[1], 200.0, 1e-9);
        /* the linear analyses linearise about the same state */
        double q[2];
        REQUIRE(gd_system_law_state(f.s, 0.0, q) == 1);
        CHECK_REL(q[iy], r->q[iy], 1e-9);
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.kind = GD_MODAL_UNDAMPED;
        gd_modal_result *mr = NULL;
        REQUIRE(gd_modal_solve(f.s, &mo, &mr, &err) == GD_OK);
        REQUIRE(mr->nmodes == 2);
        double ky, kx;
        roller_stiffness(d, n, &ky, &kx);
        double w1 = sqrt(fmin(kx, ky) / 10), w2 = sqrt(fmax(kx, ky) / 10);
        printf("    modal %.6g, %.6g Hz; closed form %.6g, %.6g Hz\n", mr->modes[0].frequency_hz,
               mr->modes[1].frequency_hz, w1 / (2 * M_PI), w2 / (2 * M_PI));
        CHECK_REL(mr->modes[0].omega_n, w1, 1e-7);
        CHECK_REL(mr->modes[1].omega_n, w2, 1e-7);
        gd_modal_free(mr);
        gd_static_free(r);
        fx_free(&f);
    }
}

/* A spur pair free in torsion (no torsional support), each gear on a rolling bearing
 * (balls at the pinion, the M2 roller at the wheel, both with clearance), under gravity
 * and a constant brake torque on the wheel; the operating point adds an input torque at
 * the pinion and holds the train at the output (the static analysis's torque balance).
 * The same model with linear bearings of the laws' tangent stiffness at that state must
 * give the same modes and Campbell diagram. */
#define GEARBOX_HEAD                                                                               \
    "dofs: [x, y, rz]\n"                                                                           \
    "gravity: {direction: [0, -1, 0], g: 9.81}\n"                                                  \
    "shafts:\n"                                                                                    \
    "  - name: shaft_a\n"                                                                          \
    "    nodes: [{name: gear_a}]\n"                                                                \
    "  - name: shaft_b\n"                                                                          \
    "    nodes: [{name: gear_b}]\n"                                                                \
    "disks:\n"                                                                                     \
    "  - {name: gear_a, node: gear_a, mass: 8.975, polar_inertia: 21.45e-3}\n"                     \
    "  - {name: gear_b, node: gear_b, mass: 9.124, polar_inertia: 5.097e-3}\n"                     \
    "meshes:\n"                                                                                    \
    "  - {name: mesh, driver: gear_a, driven: gear_b, base_radius: [30 mm, 54 mm],\n"              \
    "     pressure_angle: 20 deg, line_of_centres: 0, stiffness: 34 MN/m, damping: 0,\n"           \
    "     coupling: lateral-torsional}\n"                                                          \
    "excitations:\n"                                                                               \
    "  loads:\n"                                                                                   \
    "    - {name: brake, node: gear_b, dof: rz, value: 20}\n"

static const char GEARBOX_LAWS[] =
    GEARBOX_HEAD "laws:\n"
                 "  - {type: rolling_bearing, name: ball_a, node: gear_a, elements: 9,\n"
                 "     contact_stiffness: 8e9, clearance: 2 um, pitch_diameter: 39 mm,\n"
                 "     element_diameter: 7.9 mm, phase: 10 deg}\n"
                 "  - {type: rolling_bearing, name: roller_b, node: gear_b, elements: 12,\n"
                 "     contact_stiffness: 1e9, exponent: 1.1111111111111111, clearance: 5 um,\n"
                 "     pitch_diameter: 40 mm, element_diameter: 8 mm, phase: -90 deg}\n";

static void law_tangent(const gd_system *s, int l, const double *q, double speed, double *K,
                        double *C)
{
    gd_law L = s->laws[l];
    double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0};
    for (int j = 0; j < L.ndofs; j++) {
        ql[j] = L.dof[j] >= 0 ? q[L.dof[j]] : 0.0;
        L.rate[j] *= speed;
    }
    L.spin[0] *= speed;
    L.spin[1] *= speed;
    gd_law_point x = {0.0, ql, v};
    memset(K, 0, GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS * sizeof *K);
    memset(C, 0, GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS * sizeof *C);
    L.type->linearize(&L, &x, K, C);
}

static int operating_state(fx *f, double torque, double *q)
{
    gd_static_options o;
    gd_static_options_init(&o);
    o.input_torque = torque;
    gd_error err;
    if (gd_static_operating_point(f->s, &o, 1, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        return 0;
    }
    return gd_system_law_state(f->s, 0.0, q);
}

/* The largest difference between the operating state q and static's state under the same
 * input torque, relative to static's largest deflection (torsion left out: it is relative
 * to the held DOF); -1 when static fails. */
static double static_gap(fx *f, double torque, const double *q, double *qmax_out)
{
    gd_static_options o;
    gd_static_options_init(&o);
    o.input_torque = torque;
    gd_static_result *sr = NULL;
    gd_error err;
    if (gd_static_run(f->s, &o, &sr, &err)) return -1;
    double qmax = 0, dmax = 0;
    for (int i = 0; i < f->s->ndof; i++)
        if (f->s->dof_type[i] != GD_RZ) {
            qmax = fmax(qmax, fabs(sr->q[i]));
            dmax = fmax(dmax, fabs(q[i] - sr->q[i]));
        }
    gd_static_free(sr);
    if (qmax_out) *qmax_out = qmax;
    return dmax / qmax;
}

/* The modes and Campbell diagram of the gearbox with the laws of model at its operating
 * state (input torque 50 N m) against the same gearbox on linear bearings of the laws'
 * x-y tangent at that state. */
static void equals_linear_bearings(gd_test_state *gd_ts_, const char *model)
{
    fx f;
    REQUIRE(load(&f, NULL, model));
    int n = f.s->ndof;
    double *q = calloc((size_t)n, sizeof *q);
    REQUIRE(operating_state(&f, 50.0, q));
    /* the static analysis under the same options finds the same state */
    double qmax, gap = static_gap(&f, 50.0, q, &qmax);
    printf("  static vs operating state: %.3g of the largest deflection %.4g um\n", gap,
           qmax * 1e6);
    CHECK(gap >= 0 && gap <= 1e-9);
    gd_error err;
    /* linear bearings of the laws' tangent stiffness */
    char yaml[4096];
    int len = snprintf(yaml, sizeof yaml, "%sbearings:\n", GEARBOX_HEAD);
    const char *nodes[2] = {"gear_a", "gear_b"};
    for (int l = 0; l < 2; l++) {
        double K[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS], C[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS];
        law_tangent(f.s, l, q, 0.0, K, C);
        int nd = f.s->laws[l].ndofs;
        printf("  %s: kxx %.6g kxy %.6g kyx %.6g kyy %.6g N/m\n", f.s->laws[l].name, K[0], K[nd],
               K[1], K[1 + nd]);
        CHECK(K[0] > 1e6 && K[1 + nd] > 1e6); /* loaded: the contacts are stiff */
        len += snprintf(yaml + len, sizeof yaml - (size_t)len,
                        "  - {name: b%d, node: %s, kxx: %.17g, kxy: %.17g, kyx: %.17g, kyy: "
                        "%.17g}\n",
                        l, nodes[l], K[0], K[nd], K[1], K[1 + nd]);
    }
    fx g;
    REQUIRE(load(&g, NULL, yaml));
    REQUIRE(g.s->ndof == n);
    /* modal: all modes, undamped (the torsional rigid-body mode at 0 in both) */
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.kind = GD_MODAL_UNDAMPED;
    gd_modal_result *ra = NULL, *rb = NULL;
    REQUIRE(gd_modal_solve(f.s, &mo, &ra, &err) == GD_OK);
    REQUIRE(gd_modal_solve(g.s, &mo, &rb, &err) == GD_OK);
    REQUIRE(ra->nmodes == rb->nmodes);
    double worst = 0, wmax = 0;
    int rigid = 0;
    for (int k = 0; k < ra->nmodes; k++) {
        wmax = fmax(wmax, rb->modes[k].omega_n);
        rigid += ra->modes[k].rigid_body;
    }
    for (int k = 0; k < ra->nmodes; k++)
        worst = fmax(worst, fabs(ra->modes[k].omega_n - rb->modes[k].omega_n) / wmax);
    printf("  modal: %d modes, %d rigid (torsion of the train), worst relative difference "
           "%.2g; f %.5g .. %.5g Hz\n",
           ra->nmodes, rigid, worst, ra->modes[1].frequency_hz,
           ra->modes[ra->nmodes - 1].frequency_hz);
    CHECK(rigid == 1);
    CHECK(worst <= 1e-9);
    /* at q = 0 the contacts (with clearance) carry nothing: lateral rigid-body modes,
       the silent wrong answer of issue 34 */
    gd_modal_result *rz = NULL;
    gd_error e2;
    REQUIRE(gd_system_set_operating_point(f.s, GD_OPERATING_ZERO, NULL, NULL, &e2) == GD_OK);
    REQUIRE(gd_modal_solve(f.s, &mo, &rz, &err) == GD_OK);
    int rigid0 = 0;
    for (int k = 0; k < rz->nmodes; k++)
        rigid0 += rz->modes[k].rigid_body;
    CHECK(rigid0 > 1);
    gd_modal_free(rz);
    REQUIRE(operating_state(&f, 50.0, q));
    /* campbell over a few speeds, damped: the same frequencies */
    double speeds[3] = {0, 300, 600};
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.speeds = speeds;
    co.nspeeds = 3;
    co.nthreads = 1;
    gd_campbell_result *ca = NULL, *cb = NULL;
    REQUIRE(gd_campbell(f.s, &co, &ca, &err) == GD_OK);
    REQUIRE(gd_campbell(g.s, &co, &cb, &err) == GD_OK);
    REQUIRE(ca->ntracks == cb->ntracks);
    /* the sweep's own flags of the speeds without an equilibrium (the CLI's report reads
       them): every speed has one; the model without laws has none to flag */
    REQUIRE(ca->no_equilibrium != NULL);
    CHECK(!ca->no_equilibrium[0] && !ca->no_equilibrium[1] && !ca->no_equilibrium[2]);
    CHECK(cb->no_equilibrium == NULL);
    double cworst = 0;
    for (int t = 0; t < ca->ntracks; t++)
        for (int k = 0; k < 3; k++) {
            const gd_mode *a = &ca->modes[t * 3 + k], *b = &cb->modes[t * 3 + k];
            cworst = fmax(cworst, fabs(a->omega_n - b->omega_n) / wmax);
        }
    printf("  campbell: %d tracks x 3 speeds, worst relative difference %.2g\n", ca->ntracks,
           cworst);
    CHECK(cworst <= 1e-9);
    gd_campbell_free(ca);
    gd_campbell_free(cb);
    gd_modal_free(ra);
    gd_modal_free(rb);
    free(q);
    fx_free(&g);
    fx_free(&f);
}

TEST(gearbox_free_in_torsion_equals_linear_bearings)
{
    equals_linear_bearings(gd_ts_, GEARBOX_LAWS);
}

/* The same gearbox on the 5-DOF laws from geometry (rolling_bearing_5dof): a 6205-size
 * ball bearing with 2 um clearance at the pinion, a cylindrical roller bearing (14 rollers,
 * 10 mm long) at the wheel; in the x-y plane their tangent is the linear bearings'. */
static const char GEARBOX_GEOMETRY[] =
    GEARBOX_HEAD "laws:\n"
                 "  - {type: rolling_bearing_5dof, name: ball_a, node: gear_a, elements: 9,\n"
                 "     element_diameter: 7.94 mm, pitch_diameter: 39.04 mm, clearance: 2 um,\n"
                 "     phase: 10 deg}\n"
                 "  - {type: rolling_bearing_5dof, name: roller_b, node: gear_b, elements: 14,\n"
                 "     roller: 1, element_diameter: 7.5 mm, pitch_diameter: 46 mm,\n"
                 "     roller_length: 10 mm, clearance: 5 um, phase: -90 deg}\n";

TEST(gearbox_on_geometric_bearings_equals_linear_bearings)
{
    equals_linear_bearings(gd_ts_, GEARBOX_GEOMETRY);
}

/* The gearbox in all six directions per gear (x, y, z, rx, ry, rz) on two ball bearings
 * from geometry: a 6205-size deep-groove bearing with 2 um clearance at the pinion and a
 * 25 deg angular-contact bearing preloaded by 2 um at the wheel. Nothing else holds the
 * gears axially or in tilt: the bearings' full 5 x 5 tangent at the static state does
 * (radial, axial and tilt coupled). The modes at the operating state (input torque 50 N m)
 * equal those of the same model without the laws, its stiffness plus the laws' tangents
 * at that state (the linear bearings of the full tangent, which `bearings:` cannot
 * write: it has no radial-tilt coupling), by LAPACK's dsygv: omega^2 to 1e-9 of the
 * highest. */
#define GEARBOX6_HEAD                                                                              \
    "dofs: [x, y, z, rx, ry, rz]\n"                                                                \
    "gravity: {direction: [0, -1, 0], g: 9.81}\n"                                                  \
    "shafts:\n"                                                                                    \
    "  - name: shaft_a\n"                                                                          \
    "    nodes: [{name: gear_a}]\n"                                                                \
    "  - name: shaft_b\n"                                                                          \
    "    nodes: [{name: gear_b}]\n"                                                                \
    "disks:\n"                                                                                     \
    "  - {name: gear_a, node: gear_a, mass: 8.975, polar_inertia: 21.45e-3,\n"                     \
    "     diametral_inertia: 11e-3}\n"                                                             \
    "  - {name: gear_b, node: gear_b, mass: 9.124, polar_inertia: 5.097e-3,\n"                     \
    "     diametral_inertia: 3e-3}\n"                                                              \
    "meshes:\n"                                                                                    \
    "  - {name: mesh, driver: gear_a, driven: gear_b, base_radius: [30 mm, 54 mm],\n"              \
    "     pressure_angle: 20 deg, line_of_centres: 0, stiffness: 34 MN/m, damping: 0,\n"           \
    "     coupling: lateral-torsional}\n"                                                          \
    "excitations:\n"                                                                               \
    "  loads:\n"                                                                                   \
    "    - {name: brake, node: gear_b, dof: rz, value: 20}\n"

static const char GEARBOX6_LAWS[] =
    GEARBOX6_HEAD "laws:\n"
                  "  - {type: rolling_bearing_5dof, name: ball_a, node: gear_a, elements: 9,\n"
                  "     element_diameter: 7.94 mm, pitch_diameter: 39.04 mm, clearance: 2 um,\n"
                  "     phase: 10 deg}\n"
                  "  - {type: rolling_bearing_5dof, name: angular_b, node: gear_b, elements: 13,\n"
                  "     element_diameter: 7.5 mm, pitch_diameter: 40 mm, contact_angle: 25 deg,\n"
                  "     clearance: -2 um}\n";

TEST(gearbox_in_five_directions_equals_its_tangent)
{
    fx f, g;
    REQUIRE(load(&f, NULL, GEARBOX6_LAWS));
    REQUIRE(load(&g, NULL, GEARBOX6_HEAD));
    const int n = f.s->ndof;
    REQUIRE(g.s->ndof == n);
    double *q = calloc((size_t)n, sizeof *q), *M = calloc((size_t)n * n, sizeof *M),
           *K = calloc((size_t)n * n, sizeof *K), *w = calloc((size_t)n, sizeof *w);
    REQUIRE(q && M && K && w);
    REQUIRE(operating_state(&f, 50.0, q));
    double qmax, gap = static_gap(&f, 50.0, q, &qmax);
    printf("  static vs operating state: %.3g of the largest deflection %.4g um\n", gap,
           qmax * 1e6);
    CHECK(gap >= 0 && gap <= 1e-9);
    /* the linear model plus the laws' tangents, scattered to their DOFs */
    gd_system_dense(g.s, 0.0, M, NULL, K);
    for (int l = 0; l < f.s->nlaws; l++) {
        double Kl[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS], Cl[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS];
        law_tangent(f.s, l, q, 0.0, Kl, Cl);
        const gd_law *L = &f.s->laws[l];
        const int nd = L->ndofs;
        printf("  %s: kxx %.5g kzz %.5g N/m, krxrx %.5g N m/rad, kz-rx %.5g N, kx-ry %.5g N\n",
               L->name, Kl[0], Kl[2 + nd * 2], Kl[3 + nd * 3], Kl[2 + nd * 3], Kl[0 + nd * 4]);
        CHECK(Kl[2 + nd * 2] > 1e5 && Kl[3 + nd * 3] > 10); /* axial and tilt held */
        for (int a = 0; a < nd; a++)
            for (int b = 0; b < nd; b++)
                if (L->dof[a] >= 0 && L->dof[b] >= 0)
                    K[L->dof[a] + (size_t)n * L->dof[b]] += Kl[a + nd * b];
    }
    REQUIRE(LAPACKE_dsygv(LAPACK_COL_MAJOR, 1, 'N', 'U', n, K, n, M, n, w) == 0);
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.kind = GD_MODAL_UNDAMPED;
    mo.method = GD_EIG_DENSE;
    gd_modal_result *r = NULL;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &mo, &r, &err) == GD_OK);
    REQUIRE(r->nmodes == n);
    /* eigenvalues omega^2 against dsygv's (the rigid mode's omega is the square root of
       round-off) */
    double worst = 0;
    int rigid = 0;
    for (int k = 0; k < n; k++) {
        double om = r->modes[k].omega_n;
        worst = fmax(worst, fabs(om * om - w[k]) / w[n - 1]);
        rigid += r->modes[k].rigid_body;
    }
    printf("  modal: %d modes, %d rigid, %.5g .. %.5g Hz, worst relative difference %.2g\n", n,
           rigid, r->modes[1].frequency_hz, r->modes[n - 1].frequency_hz, worst);
    CHECK(rigid == 1);
    CHECK(worst <= 1e-9);
    gd_modal_free(r);
    free(q);
    free(M);
    free(K);
    free(w);
    fx_free(&g);
    fx_free(&f);
}

/* Each law's tangent (K = -df/dq) at the operating states against central differences of
 * its force: step 1e-7 of the deflection, Richardson-extrapolated (error O(h^4): below
 * 1e-10 for the smooth Hertz contacts away from an element's first touch), tolerance 1e-6
 * of the largest entry. */
TEST(tangents_against_central_differences)
{
    fx f;
    REQUIRE(load(&f, NULL, GEARBOX_LAWS));
    int n = f.s->ndof;
    double *q = calloc((size_t)n, sizeof *q);
    const double torques[2] = {0.0, 50.0};
    for (int c = 0; c < 2; c++) {
        REQUIRE(operating_state(&f, torques[c], q));
        for (int l = 0; l < f.s->nlaws; l++) {
            gd_law L = f.s->laws[l];
            int nd = L.ndofs;
            double K[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS], C[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS];
            law_tangent(f.s, l, q, 0.0, K, C);
            double ql[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS] = {0}, big = 0, worst = 0;
            for (int j = 0; j < nd; j++)
                ql[j] = L.dof[j] >= 0 ? q[L.dof[j]] : 0.0;
            for (int j = 0; j < nd * nd; j++)
                big = fmax(big, fabs(K[j]));
            double h = 1e-7 * hypot(ql[0], ql[1]);
            for (int b = 0; b < nd; b++) {
                double d1[GD_LAW_MAX_DOFS], d2[GD_LAW_MAX_DOFS];
                for (int pass = 0; pass < 2; pass++) {
                    double hh = pass ? 2 * h : h, fp[GD_LAW_MAX_DOFS] = {0},
                           fm[GD_LAW_MAX_DOFS] = {0}, keep = ql[b];
                    gd_law_point x = {0.0, ql, v};
                    ql[b] = keep + hh;
                    L.type->force(&L, &x, fp, NULL, NULL);
                    ql[b] = keep - hh;
                    L.type->force(&L, &x, fm, NULL, NULL);
                    ql[b] = keep;
                    for (int a = 0; a < nd; a++)
                        (pass ? d2 : d1)[a] = -(fp[a] - fm[a]) / (2 * hh);
                }
                for (int a = 0; a < nd; a++)
                    worst = fmax(worst, fabs(K[a + nd * b] - (4 * d1[a] - d2[a]) / 3));
            }
            printf("  torque %g N m, %s: |K - K_fd| %.2g of the largest entry %.4g N/m\n",
                   torques[c], L.name, worst / big, big);
            CHECK(big > 0);
            CHECK(worst <= 1e-6 * big);
        }
    }
    free(q);
    fx_free(&f);
}

/* A journal bearing that cannot carry its load (the film at its eccentricity cap), and
 * a journal bearing at rest: located errors naming the law and the fix, never NaN. */
TEST(bearing_that_cannot_carry_the_load_is_named)
{
    static const char YAML[] = "dofs: [x, y]\n"
                               "gravity: {direction: [0, -1, 0], g: 9.81}\n"
                               "shafts:\n"
                               "  - name: s\n"
                               "    nodes: [{name: m}]\n"
                               "disks:\n"
                               "  - {name: m, node: m, mass: 20000}\n"
                               "laws:\n"
                               "  - {type: journal_bearing, name: jb, node: m, viscosity: 0.02,\n"
                               "     diameter: 50 mm, length: 20 mm, clearance: 50 um,\n"
                               "     max_eccentricity: 0.9}\n";
    fx f;
    REQUIRE(load(&f, NULL, YAML));
    gd_static_options o;
    gd_static_options_init(&o);
    o.speed = 100.0;
    gd_static_result *r = NULL;
    gd_error err;
    CHECK(gd_static_run(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(r == NULL);
    printf("  %s\n", err.message);
    CHECK(strstr(err.message, "journal bearing 'jb' reaches its eccentricity cap 0.9") != NULL);
    CHECK_STR(err.field, "laws[0]");
    CHECK(err.line == 9);
    CHECK(strstr(err.hint, "raise the speed") != NULL);
    /* the operating point of the linear analyses says the same */
    CHECK(gd_static_operating_point(f.s, &o, 1, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "reaches its eccentricity cap") != NULL);
    o.speed = 0;
    CHECK(gd_static_operating_point(f.s, &o, 1, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "carries nothing at 0 rad/s") != NULL);
    fx_free(&f);
}

/* The rig of examples/rig2018.yaml on four ball-bearing laws (examples/rig2018_rolling.yaml,
 * 170 DOFs, free in torsion, 2 um clearance): from rest the operating point is found at
 * both torques (before, Newton crawled by slivers of steps as the contacts stiffened and
 * the linear analyses fell back to q = 0 with eight lateral rigid-body modes), its state
 * is static's (1e-9 of the largest deflection), one rigid-body mode is left (the train's
 * torsion) and the bearing-dominated modes stiffen with the torque. */
TEST(rig_on_rolling_bearings_stiffens_with_torque)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018_rolling.yaml", NULL));
    int n = f.s->ndof;
    double *q = calloc((size_t)n, sizeof *q), first[2] = {0}, sixth[2] = {0};
    const double torque[2] = {5, 50};
    for (int c = 0; c < 2; c++) {
        REQUIRE(operating_state(&f, torque[c], q));
        double gap = static_gap(&f, torque[c], q, NULL);
        CHECK(gap >= 0 && gap <= 1e-9);
        gd_error err;
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.kind = GD_MODAL_UNDAMPED;
        mo.method = GD_EIG_DENSE;
        gd_modal_result *r = NULL;
        REQUIRE(gd_modal_solve(f.s, &mo, &r, &err) == GD_OK);
        int rigid = 0;
        for (int k = 0; k < r->nmodes; k++)
            rigid += r->modes[k].rigid_body;
        first[c] = r->modes[1].frequency_hz;
        sixth[c] = r->modes[5].frequency_hz;
        printf("  torque %g N m: %d rigid, f2 %.5g Hz, f6 %.5g Hz (state vs static %.2g)\n",
               torque[c], rigid, first[c], sixth[c], gap);
        CHECK(rigid == 1);
        gd_modal_free(r);
    }
    CHECK(first[1] > first[0] && sixth[1] > 1.05 * sixth[0]);
    free(q);
    fx_free(&f);
}

/* The rig on its four bearings from geometry alone (examples/rig2018_geometry.yaml: 6205-size
 * ball bearings as rolling_bearing_5dof laws, radial and tilt), at two input torques: the
 * operating state is static's, one rigid-body mode (the train's torsion), and the first
 * ten elastic frequencies (docs/bearings.md's table) rise as the balls take the mesh
 * load, radially and in tilt: the shaft-bending pairs (2-5) and modes 8-9 by 3 to 10 %,
 * modes 6-7 by 15 to 25 %, modes 10-11 by 25 to 40 % (loose bands about the measured
 * shifts: the sign and size, not the digits). */
TEST(rig_on_geometric_bearings_at_two_torques)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018_geometry.yaml", NULL));
    int n = f.s->ndof;
    double *q = calloc((size_t)n, sizeof *q), hz[2][11] = {{0}};
    const double torque[2] = {5, 50};
    for (int c = 0; c < 2; c++) {
        REQUIRE(operating_state(&f, torque[c], q));
        double gap = static_gap(&f, torque[c], q, NULL);
        CHECK(gap >= 0 && gap <= 1e-9);
        gd_error err;
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.kind = GD_MODAL_UNDAMPED;
        mo.method = GD_EIG_DENSE;
        gd_modal_result *r = NULL;
        REQUIRE(gd_modal_solve(f.s, &mo, &r, &err) == GD_OK);
        int rigid = 0;
        for (int k = 0; k < r->nmodes; k++)
            rigid += r->modes[k].rigid_body;
        printf("  torque %g N m (%d rigid, state vs static %.2g):", torque[c], rigid, gap);
        for (int k = 0; k < 11; k++) {
            hz[c][k] = r->modes[k].frequency_hz;
            printf(" %.1f", hz[c][k]);
        }
        printf(" Hz\n");
        CHECK(rigid == 1);
        gd_modal_free(r);
    }
    for (int k = 1; k < 11; k++) {
        double shift = hz[1][k] / hz[0][k] - 1;
        printf("    mode %d: %+.1f %%\n", k + 1, 100 * shift);
        /* measured (modes 2-11): +7.0 +5.0 +7.0 +6.6 +19.2 +19.4 +5.8 +7.5 +31.9 +32.8 % */
        static const double lo[11] = {0,    0.03, 0.03, 0.03, 0.03, 0.15,
                                      0.15, 0.03, 0.03, 0.25, 0.25},
                            hi[11] = {0,    0.10, 0.10, 0.10, 0.10, 0.25,
                                      0.25, 0.10, 0.10, 0.40, 0.40};
        CHECK(shift > lo[k] && shift < hi[k]);
    }
    free(q);
    fx_free(&f);
}

/* A cylindrical roller bearing from geometry (contact angle 0) holds no axial motion:
 * under an axial load static names the law and the 5-DOF law's hint, exit 2 in the CLI,
 * never NaN. */
TEST(axial_load_on_a_radial_roller_is_named)
{
    static const char YAML[] =
        "dofs: [x, y, z]\n"
        "shafts:\n"
        "  - name: s\n"
        "    nodes: [{name: m}]\n"
        "disks:\n"
        "  - {name: m, node: m, mass: 10}\n"
        "laws:\n"
        "  - {type: rolling_bearing_5dof, name: cyl, node: m, elements: 14, roller: 1,\n"
        "     element_diameter: 7.5 mm, pitch_diameter: 46 mm, roller_length: 10 mm}\n"
        "excitations:\n"
        "  loads:\n"
        "    - {node: m, dof: y, value: -200}\n"
        "    - {node: m, dof: z, value: 100}\n";
    fx f;
    REQUIRE(load(&f, NULL, YAML));
    gd_static_options o;
    gd_static_options_init(&o);
    gd_static_result *r = NULL;
    gd_error err;
    CHECK(gd_static_run(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(r == NULL);
    printf("  %s\n  hint: %s\n", err.message, err.hint);
    CHECK(strstr(err.message, "rolling bearing 'cyl'") != NULL);
    CHECK_STR(err.field, "laws[0]");
    CHECK(strstr(err.hint, "radial bearing (contact angle 0) little axial or tilt load") != NULL);
    gd_static_free(r);
    fx_free(&f);
}

RUN_TESTS(T(roller_in_its_clearance_finds_equilibrium),
          T(rig_on_rolling_bearings_stiffens_with_torque),
          T(rig_on_geometric_bearings_at_two_torques),
          T(gearbox_free_in_torsion_equals_linear_bearings),
          T(gearbox_on_geometric_bearings_equals_linear_bearings),
          T(gearbox_in_five_directions_equals_its_tangent), T(tangents_against_central_differences),
          T(bearing_that_cannot_carry_the_load_is_named), T(axial_load_on_a_radial_roller_is_named))
