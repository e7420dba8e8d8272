/* Harmonic balance (periodic.h): the linear case against the unbalance response, the
 * damped Mathieu tongue of a TVMS pair against its closed form, Floquet multipliers
 * against the integrated monodromy, and backlash / SFD steady states against time
 * integration. */
#include <cblas.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "geardyn/unbalance.h"
#include "harness.h"
#include "model_support.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* Chen et al. 1998 gear pair (examples/chen1998_gear_pair.yaml) without the damper, gear a
 * enlarged to a 1:2 ratio so that both unbalances share the period of gear b. */
static const char *chen_linear =
    "dofs: [x, y, rz]\n"
    "shafts:\n"
    "  - {name: shaft_a, nodes: [{name: gear_a}]}\n"
    "  - {name: shaft_b, nodes: [{name: gear_b}]}\n"
    "disks:\n"
    "  - {name: gear_a, node: gear_a, mass: 8.975, polar_inertia: 21.45e-3}\n"
    "  - {name: gear_b, node: gear_b, mass: 9.124, polar_inertia: 5.097e-3}\n"
    "bearings:\n"
    "  - {name: support_a, node: gear_a, k: 5.683e6, c: 714.18, k_torsion: 9483, c_torsion: "
    "0.7131}\n"
    "  - {name: support_b, node: gear_b, k: 25.5735e6, c: 1527.5, k_torsion: 28680, "
    "c_torsion: 0.6045}\n"
    "meshes:\n"
    "  - {name: mesh, driver: gear_a, driven: gear_b, base_radius: [27.00 mm, 54.00 mm],\n"
    "     pressure_angle: 20 deg, line_of_centres: 0, stiffness: 34.098e6, damping: 384.35,\n"
    "     coupling: lateral-torsional}\n"
    "unbalances:\n"
    "  - {node: gear_a, mass: 8.975, eccentricity: 12.7 um, phase: 30 deg}\n"
    "  - {node: gear_b, amount: 2e-5, phase: 80 deg}\n";

static gd_periodic_result *run_speeds(const fx *f, const gd_transient_spec *spec, double w0,
                                      double w1, int count, const gd_periodic_options *o,
                                      const gd_tr_record *rec, int nrec)
{
    openblas_set_num_threads(1); /* tiny dense blocks */
    double *v = malloc((size_t)count * sizeof *v);
    for (int i = 0; i < count; i++)
        v[i] = count > 1 ? w0 + (w1 - w0) * i / (count - 1) : w0;
    gd_periodic_result *r = NULL;
    gd_error err;
    if (gd_periodic_run(f->s, spec, NULL, v, count, o, rec, nrec, &r, &err))
        fprintf(stderr, "  periodic: %s (%s) %s\n", err.message, err.field, err.hint);
    free(v);
    return r;
}

/* Loads the model text (freed here) and its transient spec; 1 on success. */
static int load_spec(fx *f, char *yaml, gd_transient_model **tm)
{
    gd_error err;
    int ok = load(f, NULL, yaml);
    free(yaml);
    *tm = NULL;
    if (ok && gd_transient_model_build(f->s, tm, &err)) {
        fprintf(stderr, "  spec: %s\n", err.message);
        ok = 0;
    }
    return ok;
}

/* Linear, constant stiffness: HB equals the unbalance response (two shafts at different
 * speeds: harmonics 1 and r_a/r_b of gear a's speed... both multiples of the common
 * fundamental). Tolerance 1e-9: both solve the same linear equations, the difference is
 * rounding. */
typedef struct seen_points {
    int n, order_ok;
    double last;
} seen_points;

static void count_point(const gd_periodic_point *p, int index, double progress, void *user)
{
    seen_points *s = user;
    if (index != s->n || progress < s->last || progress > 1) s->order_ok = 0;
    if (!p->converged) s->order_ok = 0;
    s->last = progress;
    s->n++;
}

TEST(linear_equals_unbalance)
{
    fx f;
    REQUIRE(load(&f, NULL, chen_linear));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 2;
    o.stability = 0;
    o.method = GD_PER_SEQUENTIAL;
    seen_points sp3 = {0, 1, 0.0};
    o.on_point = count_point;
    o.user = &sp3;
    const double speeds[3] = {300.0, 1100.0, 2500.0};
    gd_periodic_result *r = run_speeds(&f, &tm->spec, speeds[0], speeds[2], 3, &o, NULL, 0);
    /* middle value differs from the grid: solve it separately below */
    REQUIRE(r);
    REQUIRE(r->npoints == 3);
    /* every point announced once, in order, as it is final, progress rising to 1; a linear
     * response at H = 2 against 5: no truncation change (2e-16 measured) */
    CHECK(sp3.n == 3 && sp3.order_ok && sp3.last == 1.0);
    for (int i = 0; i < 3; i++) {
        CHECK(r->points[i].harmonic_ok == 1 && r->points[i].harmonics_ref == 5);
        CHECK(r->points[i].harmonic_error_amp < 1e-12);
    }
    gd_probe pr[6];
    int np = 0;
    const char *nodes[2] = {"gear_a", "gear_b"};
    const gd_dof ds[3] = {GD_X, GD_Y, GD_RZ};
    for (int a = 0; a < 2; a++)
        for (int d = 0; d < 3; d++)
            pr[np++] = (gd_probe){.element = NULL, .index = dof(&f, nodes[a], ds[d])};
    gd_unbalance_options uo;
    gd_unbalance_options_init(&uo);
    double sp[3] = {r->points[0].speed, r->points[1].speed, r->points[2].speed};
    uo.speeds = sp;
    uo.nspeeds = 3;
    uo.outputs = pr;
    uo.noutputs = np;
    uo.nthreads = 1;
    gd_unbalance_result *u = NULL;
    REQUIRE(gd_unbalance_response(f.s, &uo, &u, &err) == GD_OK);
    REQUIRE(u->nharmonics == 2);
    double maxerr = 0.0, maxamp = 0.0;
    for (int s = 0; s < 3; s++) {
        const gd_periodic_point *p = &r->points[s];
        REQUIRE(p->converged);
        for (int h = 0; h < 2; h++) {
            /* harmonic order 1 (gear a) is k = 2 of the period of gear b (order 0.5) */
            int k = (int)lround(u->harmonics[h].order * sp[s] / p->omega);
            for (int o2 = 0; o2 < np; o2++) {
                size_t at = ((size_t)h * np + o2) * 3 + s;
                double xr = u->re[at], xi = u->im[at];
                int i = pr[o2].index; /* no prescribed DOFs: free index = DOF index */
                double qc = p->coef[(2 * k - 1) * p->nfree + i], qs = p->coef[2 * k * p->nfree + i];
                double e = hypot(qc - xr, qs + xi);
                maxerr = e > maxerr ? e : maxerr;
                double a = hypot(xr, xi);
                maxamp = a > maxamp ? a : maxamp;
            }
        }
        CHECK(p->residual < 1e-12);
    }
    printf("  linear: max |HB - unbalance| = %.3g of max amplitude %.3g\n", maxerr, maxamp);
    CHECK(maxerr <= 1e-9 * maxamp);
    gd_unbalance_free(u);
    gd_transient_model_free(tm);
    gd_periodic_result_free(r);
    fx_free(&f);
}

/* ------------------------------------------------------------------ damped Mathieu */

/* Gear b (I = 5e-3 kg m^2, base radius 50 mm) meshing with a driver turning exactly at its
 * nominal speed (prescribed), k(theta) = k0 (1 + e cos(z theta)), z = 20: the torsion
 * obeys I q'' + c r^2 q' + k(t) r^2 q = T, a damped Mathieu equation with
 * w_n^2 = k0 r^2 / I = 5e7 (w_n = 7071 rad/s), zeta = c r^2 / (2 I w_n), parametric
 * frequency W_m = z W. The constant torque T gives a non-trivial periodic response. */
static char *mathieu_yaml(double e, double zeta)
{
    const double k0 = 1e8, r = 0.05, inertia = 5e-3, wn = sqrt(k0 * r * r / inertia);
    const double c = 2.0 * zeta * wn * inertia / (r * r);
    const int z = 20, np = 96;
    size_t cap = 16384;
    char *y = malloc(cap);
    int n = snprintf(y, cap,
                     "dofs: [rz]\n"
                     "shafts:\n"
                     "  - {name: a, nodes: [{name: gear_a}]}\n"
                     "  - {name: b, nodes: [{name: gear_b}]}\n"
                     "disks:\n"
                     "  - {node: gear_a, polar_inertia: 1e-2}\n"
                     "  - {node: gear_b, polar_inertia: %.17g}\n"
                     "meshes:\n"
                     "  - name: m\n"
                     "    driver: gear_a\n"
                     "    driven: gear_b\n"
                     "    base_radius: [25 mm, 50 mm]\n"
                     "    teeth: [%d, 40]\n"
                     "    pressure_angle: 20 deg\n"
                     "    damping: %.17g\n"
                     "    tvms:\n"
                     "      interpolation: spline\n"
                     "      angle: [",
                     inertia, z, c);
    for (int j = 0; j < np; j++)
        n += snprintf(y + n, cap - (size_t)n, "%s%.17g", j ? ", " : "", 2 * M_PI / z * j / np);
    n += snprintf(y + n, cap - (size_t)n, "]\n      stiffness: [");
    for (int j = 0; j < np; j++)
        n += snprintf(y + n, cap - (size_t)n, "%s%.17g", j ? ", " : "",
                      k0 * (1 + e * cos(2 * M_PI * j / np)));
    snprintf(y + n, cap - (size_t)n,
             "]\n"
             "prescribed:\n"
             "  - {node: gear_a, motion: nominal}\n"
             "excitations:\n"
             "  loads: [{node: gear_b, value: 20}]\n");
    return y;
}

/* Transition curves of u'' + 2 mu u' + (delta + 2 eps cos 2 tau) u = 0 near delta = 1
 * (Nayfeh & Mook, Nonlinear Oscillations, 1979, Sec. 5.4, to first order in eps):
 * (delta - 1)^2 = eps^2 - 4 mu^2. In the gear's terms, tau = W_m t / 2: delta =
 * 4 w_n^2 / W_m^2, eps = e delta / 2, mu = 2 zeta w_n / W_m. Returns g(W_m). */
static double tongue_g(double wm, double wn, double e, double zeta)
{
    double d = 4 * wn * wn / (wm * wm), eps = e * d / 2, mu = 2 * zeta * wn / wm;
    return (d - 1) * (d - 1) - (eps * eps - 4 * mu * mu);
}

static double bisect_tongue(double lo, double hi, double wn, double e, double zeta)
{
    for (int i = 0; i < 200; i++) {
        double m = 0.5 * (lo + hi);
        if ((tongue_g(m, wn, e, zeta) > 0) == (tongue_g(lo, wn, e, zeta) > 0))
            lo = m;
        else
            hi = m;
    }
    return 0.5 * (lo + hi);
}

TEST(mathieu_tongue_period_doubling)
{
    const double e = 0.05, zeta = 0.005, wn = sqrt(5e7), z = 20;
    fx f;
    gd_transient_model *tm = NULL;
    REQUIRE(load_spec(&f, mathieu_yaml(e, zeta), &tm));
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 6;
    /* speeds spanning the primary tongue W_m = 2 w_n (+-1.2 %) */
    double w0 = 2 * wn / z * 0.96, w1 = 2 * wn / z * 1.04;
    gd_periodic_result *r = run_speeds(&f, &tm->spec, w0, w1, 41, &o, NULL, 0);
    REQUIRE(r);
    double lo = bisect_tongue(2 * wn * 0.95, 2 * wn, wn, e, zeta) / z;
    double hi = bisect_tongue(2 * wn, 2 * wn * 1.05, wn, e, zeta) / z;
    int npd = 0;
    double found[2] = {0, 0};
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        printf("  %s at W = %.6f rad/s, multiplier %.9f%+.3gi\n", gd_bifurcation_name(b->type),
               b->speed, b->mu_re, b->mu_im);
        if (b->type == GD_BIF_PERIOD_DOUBLING && npd < 2) found[npd++] = b->speed;
        if (b->type == GD_BIF_PERIOD_DOUBLING) CHECK_ABS(b->mu_re, -1.0, 1e-6);
    }
    REQUIRE(npd == 2);
    printf("  tongue: HB/Floquet [%.4f, %.4f], closed form [%.4f, %.4f] rad/s (width %.4f vs "
           "%.4f)\n",
           found[0], found[1], lo, hi, found[1] - found[0], hi - lo);
    /* first-order theory: the boundaries carry O(eps^2) = 6.25e-4 relative errors */
    double eps = e / 2;
    CHECK_REL(found[0], lo, eps * eps);
    CHECK_REL(found[1], hi, eps * eps);
    CHECK_REL(found[1] - found[0], hi - lo, 0.05);
    /* the points inside are unstable, those outside stable */
    int bad = 0;
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        int inside = p->speed > found[0] && p->speed < found[1];
        if (!p->converged || p->stable != !inside) bad++;
    }
    CHECK(bad == 0);
    gd_transient_model_free(tm);
    gd_periodic_result_free(r);
    fx_free(&f);
}

/* Floquet multipliers of HB points against gd_transient_monodromy (CVODE on the
 * variational equations from the HB state at t = 0): a stable point outside the tongue and
 * an unstable one inside, to 1e-6 (both integrate to ~1e-9; the HB orbit itself is exact
 * to the residual 1e-10). */
TEST(floquet_against_monodromy)
{
    const double e = 0.05, zeta = 0.005, wn = sqrt(5e7), z = 20;
    fx f;
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(load_spec(&f, mathieu_yaml(e, zeta), &tm));
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 8;
    o.monodromy_steps = 2048;
    const double W[2] = {2 * wn / z * 0.97, 2 * wn / z};
    for (int c = 0; c < 2; c++) {
        gd_periodic_result *r = run_speeds(&f, &tm->spec, W[c], W[c], 1, &o, NULL, 0);
        REQUIRE(r && r->npoints == 1 && r->points[0].converged);
        const gd_periodic_point *p = &r->points[0];
        CHECK(p->stable == (c == 0));
        gd_transient *tr = NULL;
        REQUIRE(gd_transient_new(f.s, &tm->spec, W[c], &tr, &err) == GD_OK);
        int nf = p->nfree, ns = 2 * nf;
        double *y0 = calloc((size_t)ns, sizeof *y0), *phi = malloc((size_t)ns * ns * sizeof *phi);
        for (int k = 0; k <= p->harmonics; k++)
            for (int i = 0; i < nf; i++) {
                y0[i] += p->coef[(k ? 2 * k - 1 : 0) * nf + i];
                if (k) y0[nf + i] += p->omega * k * p->coef[2 * k * nf + i];
            }
        gd_transient_options to;
        gd_transient_options_init(&to);
        to.rtol = 1e-11;
        to.atol_q = 1e-16;
        to.atol_v = 1e-13;
        REQUIRE(gd_transient_monodromy(tr, 0.0, 2 * M_PI / p->omega, y0, &to, phi, NULL, &err) ==
                GD_OK);
        double wr[8], wi[8], dummy[1];
        REQUIRE(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', ns, phi, ns, wr, wi, dummy, 1, dummy,
                              1) == 0);
        double worst = 0.0;
        for (int a = 0; a < ns; a++) {
            double best = INFINITY;
            for (int b = 0; b < ns; b++) {
                double d = hypot(p->mu_re[a] - wr[b], p->mu_im[a] - wi[b]);
                best = d < best ? d : best;
            }
            worst = best > worst ? best : worst;
        }
        printf("  W = %.3f: |mu|max HB %.9f, max distance to the integrated multipliers %.3g\n",
               W[c], p->mu_max, worst);
        CHECK(worst <= 1e-6);
        free(y0);
        free(phi);
        gd_transient_free(tr);
        gd_periodic_result_free(r);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* ------------------------------------------------------------------ against time integration */

/* Mean and first two harmonic amplitudes of record r over the last period of a transient
 * run sampled M times per period (exactly one period from record_from, M + 1 samples). */
static void tr_harmonics(const gd_transient_result *tr, int r, int M, double out[3])
{
    double a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
    for (int j = 0; j < M; j++) {
        double v = tr->values[(size_t)r * tr->nout + j];
        for (int k = 0; k < 3; k++) {
            a[k] += (k ? 2.0 : 1.0) / M * v * cos(2 * M_PI * k * j / M);
            b[k] += (k ? 2.0 : 1.0) / M * v * sin(2 * M_PI * k * j / M);
        }
    }
    for (int k = 0; k < 3; k++)
        out[k] = k ? hypot(a[k], b[k]) : a[0];
}

static gd_transient_result *steady_transient(const gd_system *s, const gd_transient_spec *spec,
                                             double W, double period, int periods, double rtol,
                                             const gd_tr_record *rec, int nrec)
{
    gd_transient *tr = NULL;
    gd_error err;
    if (gd_transient_new(s, spec, W, &tr, &err)) return NULL;
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.t_end = periods * period;
    o.record_from = (periods - 1) * period;
    o.output_interval = period / 1024;
    o.rtol = rtol;
    o.atol_q = 1e-7 * rtol;
    o.atol_v = 1e-4 * rtol;
    o.init = spec->nloads ? GD_TR_INIT_STATIC : GD_TR_INIT_REST;
    gd_transient_result *r = NULL;
    if (gd_transient_run(tr, &o, rec, nrec, &r, &err))
        fprintf(stderr, "  transient: %s\n", err.message);
    gd_transient_free(tr);
    return r;
}

/* The backlash oscillator of test_transient (gear on a prescribed pinion, TVMS
 * k = 2e8 (1 + 0.2 cos 20 theta), STE 4 um sin 20 theta, gap 20 um, load 1000 N, damping
 * 1490 N s/m in and out of contact so the force is continuous at separation) at 537 rad/s:
 * the teeth separate once per mesh period (no impact). HB mean and harmonics 1, 2 of the
 * mesh force against 80 mesh periods of integration at rtol 1e-10 (settled to e^-31),
 * sampled 1024 times per period (sampling floor ~1e-6 of F0). The force has kinks, so
 * the error falls algebraically with H: table printed, H = 40 within 1e-4 of F0. */
TEST(backlash_against_transient)
{
    static const char *pair =
        "dofs: [rz]\n"
        "shafts:\n"
        "  - {name: input, nodes: [{name: pinion}]}\n"
        "  - {name: output, nodes: [{name: gear}]}\n"
        "disks:\n"
        "  - {node: pinion, polar_inertia: 1e-3}\n"
        "  - {node: gear, polar_inertia: 4e-3}\n"
        "meshes:\n"
        "  - {name: mesh, driver: pinion, driven: gear, teeth: [20, 40],\n"
        "     base_radius: [0.03, 0.06], pressure_angle: 20 deg, stiffness: 2e8,\n"
        "     coupling: torsional}\n";
    fx f;
    REQUIRE(load(&f, NULL, pair));
    enum { NT = 64 };
    double x[NT], k[NT], e[NT], per = 2 * M_PI / 20;
    for (int i = 0; i < NT; i++) {
        x[i] = i * per / NT;
        k[i] = 2e8 * (1 + 0.2 * cos(20 * x[i]));
        e[i] = 4e-6 * sin(20 * x[i]);
    }
    gd_table *tv = NULL, *st = NULL;
    gd_error err;
    REQUIRE(!gd_table_new(NT, x, k, per, GD_INTERP_SPLINE, &tv, &err));
    REQUIRE(!gd_table_new(NT, x, e, per, GD_INTERP_SPLINE, &st, &err));
    gd_tr_mesh m;
    gd_tr_mesh_init(f.s, 0, &m);
    m.tvms = tv;
    m.ste = st;
    m.damping = 1490;
    m.damping_free = 1490;
    m.backlash = 1;
    m.gap = 20e-6;
    int pin = dof(&f, "pinion", GD_RZ), gear = dof(&f, "gear", GD_RZ);
    gd_tr_prescribed pr = {pin, {GD_PRESCRIBED_NOMINAL, 0, 0, 0, 0, NULL}};
    gd_tr_load ld = {gear, {GD_LOAD_CONSTANT, 1000 * 0.06, 0, 0, 0, NULL}};
    gd_transient_spec spec = {0};
    spec.meshes = &m;
    spec.nmeshes = 1;
    spec.prescribed = &pr;
    spec.nprescribed = 1;
    spec.loads = &ld;
    spec.nloads = 1;
    const double W = 537.0, T = 2 * M_PI / (20 * W), F0 = 1000.0;
    gd_tr_record rec = {GD_REC_MESH_FORCE, 0, 0};
    gd_transient_result *tr = steady_transient(f.s, &spec, W, T, 80, 1e-10, &rec, 1);
    REQUIRE(tr);
    CHECK(tr->contacts[0].contact_losses == 1 && tr->contacts[0].coast_impacts == 0);
    double ref[3], mn = INFINITY, mx = -INFINITY;
    tr_harmonics(tr, 0, 1024, ref);
    for (int j = 0; j < 1024; j++) {
        mn = fmin(mn, tr->values[j]);
        mx = fmax(mx, tr->values[j]);
    }
    const double p2p_ref = mx - mn;
    const int Hs[4] = {5, 10, 20, 40};
    double errH[4], ep[4], eh[4], ap[4], ah[4];
    printf("  backlash pair at %.0f rad/s, mesh force vs transient (|error| / F0), and the\n"
           "  truncation estimate (change from H to 2 H + 1) against the error of the\n"
           "  peak-to-peak and of A1, A2 (relative to A1):\n"
           "     H     mean      A1        A2     p2p err  estimate  A err  estimate\n",
           W);
    for (int h = 0; h < 4; h++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = Hs[h];
        o.stability = 0;
        gd_periodic_result *r = run_speeds(&f, &spec, W, W, 1, &o, &rec, 1);
        REQUIRE(r && r->npoints == 1 && r->points[0].converged);
        const gd_periodic_point *pt = &r->points[0];
        const gd_per_record_stats *sr = &pt->records[0];
        double e0 = fabs(sr->mean - ref[0]) / F0, e1 = fabs(sr->amplitude[1] - ref[1]) / F0,
               e2 = fabs(sr->amplitude[2] - ref[2]) / F0;
        errH[h] = fmax(e0, fmax(e1, e2));
        ap[h] = fabs(sr->peak_to_peak - p2p_ref) / p2p_ref;
        ah[h] = fmax(fabs(sr->amplitude[1] - ref[1]), fabs(sr->amplitude[2] - ref[2])) / ref[1];
        ep[h] = pt->harmonic_error_p2p;
        eh[h] = pt->harmonic_error_amp;
        CHECK(pt->harmonics_ref == 2 * Hs[h] + 1);
        CHECK(sr->p2p_error == ep[h] && sr->amp_error == eh[h]); /* one record: the largest */
        printf("  %4d  %.2e  %.2e  %.2e  %.2e  %.2e  %.2e  %.2e\n", Hs[h], e0, e1, e2, ap[h], ep[h],
               ah[h], eh[h]);
        gd_periodic_result_free(r);
    }
    /* with a contact law the AFT takes at least 128 samples: the error of H = 5, 10, 20
     * is then that of the samples (~1e-4 of F0, measured 1.2e-4, 8.8e-5, 8.6e-5), H = 40
     * (256 samples) 1.5e-5 */
    CHECK(errH[3] < 1e-4);
    CHECK(errH[3] < 0.2 * errH[0]);
    /* the estimate is of the error's size: amplitudes' estimate / error 4.4, 0.85, 1.17,
     * 1.23 for H = 5, 10, 20, 40 (never below half, at most 5x over); the peak-to-peak's
     * 0.69 and 1.02 for H = 20, 40. For H = 5, 10 the peak-to-peak differs from the
     * transient's by ~7e-4 whatever H: the records' 256 samples against 1024 catch the
     * kink's peak differently, which the estimate (same record sampling at both H) does
     * not see */
    for (int h = 0; h < 4; h++)
        CHECK(eh[h] > ah[h] / 2 && eh[h] < 5 * ah[h]);
    for (int h = 2; h < 4; h++)
        CHECK(ep[h] > ap[h] / 2 && ep[h] < 2 * ap[h]);
    gd_transient_result_free(tr);
    gd_table_free(tv);
    gd_table_free(st);
    fx_free(&f);
}

/* The Chen et al. gear pair with its squeeze film damper (examples/chen1998_gear_pair.yaml)
 * at 1000 rad/s: harmonic 1 of gear a's x, the damper force and the mesh force against
 * 100 shaft periods of integration at rtol 1e-9 (settled to e^-20). The laws are smooth
 * here: the error falls fast with H; H = 15 within 1e-4 (measured ~1e-6). */
TEST(sfd_pair_against_transient)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    REQUIRE(tm->spec.nsfds == 1);
    gd_tr_record rec[3] = {{GD_REC_DISP, dof(&f, "gear_a", GD_X), 0},
                           {GD_REC_SFD_FX, 0, 0},
                           {GD_REC_MESH_FORCE, 0, 0}};
    const double W = 1000.0, T = 2 * M_PI / W;
    gd_transient_result *tr = steady_transient(f.s, &tm->spec, W, T, 100, 1e-9, rec, 3);
    REQUIRE(tr);
    double ref[3][3];
    for (int q = 0; q < 3; q++)
        tr_harmonics(tr, q, 1024, ref[q]);
    const int Hs[4] = {2, 4, 8, 15};
    double errH[4];
    printf("  Chen SFD pair at %.0f rad/s, harmonic 1 vs transient (relative):\n"
           "     H   gear_a.x  sfd fx    mesh F\n",
           W);
    for (int h = 0; h < 4; h++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = Hs[h];
        o.stability = 0;
        gd_periodic_result *r = run_speeds(&f, &tm->spec, W, W, 1, &o, rec, 3);
        REQUIRE(r && r->npoints == 1 && r->points[0].converged);
        double e[3];
        for (int q = 0; q < 3; q++)
            e[q] = fabs(r->points[0].records[q].amplitude[1] - ref[q][1]) / ref[q][1];
        errH[h] = fmax(e[0], fmax(e[1], e[2]));
        printf("  %4d  %.2e  %.2e  %.2e\n", Hs[h], e[0], e[1], e[2]);
        gd_periodic_result_free(r);
    }
    CHECK(errH[3] < 1e-4);
    CHECK(errH[3] < 1e-2 * errH[0]);
    gd_transient_result_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* ------------------------------------------------------------------ folds */

/* The backlash pair as a model file: TVMS 2e8 (1 + 0.2 cos 20 theta), STE 2 um sin 20
 * theta, gap 20 um, damping 600 N s/m in and out of contact, 1000 N load. */
static char *backlash_yaml(void)
{
    const int np = 48;
    size_t cap = 4 * 4096 + 4096; /* four lists and the text around them */
    char *y = malloc(cap), ang[4096] = "", k[4096] = "", e[4096] = "";
    int na = 0, nk = 0, ne = 0;
    for (int j = 0; j < np; j++) {
        double x = 2 * M_PI / 20 * j / np, c = 2 * M_PI * j / np;
        na += snprintf(ang + na, sizeof ang - (size_t)na, "%s%.17g", j ? ", " : "", x);
        nk += snprintf(k + nk, sizeof k - (size_t)nk, "%s%.17g", j ? ", " : "",
                       2e8 * (1 + 0.2 * cos(c)));
        ne += snprintf(e + ne, sizeof e - (size_t)ne, "%s%.17g", j ? ", " : "", 2e-6 * sin(c));
    }
    snprintf(y, cap,
             "dofs: [rz]\n"
             "shafts:\n"
             "  - {name: input, nodes: [{name: pinion}]}\n"
             "  - {name: output, nodes: [{name: gear}]}\n"
             "disks:\n"
             "  - {node: pinion, polar_inertia: 1e-3}\n"
             "  - {node: gear, polar_inertia: 4e-3}\n"
             "meshes:\n"
             "  - name: mesh\n"
             "    driver: pinion\n"
             "    driven: gear\n"
             "    teeth: [20, 40]\n"
             "    base_radius: [0.03, 0.06]\n"
             "    pressure_angle: 20 deg\n"
             "    coupling: torsional\n"
             "    damping: {constant: 600, separated: 600}\n"
             "    tvms: {interpolation: spline, angle: [%s], stiffness: [%s]}\n"
             "    transmission_error: {interpolation: spline, angle: [%s], error: [%s]}\n"
             "    backlash: {gap: 20 um}\n"
             "prescribed:\n"
             "  - {node: pinion, motion: nominal}\n"
             "excitations:\n"
             "  loads: [{node: gear, value: 60}]\n",
             ang, k, ang, e);
    return y;
}

/* The same backlash pair with the default harmonics (auto: from H = 1, the branch at the
 * coarse H that passed, points reported at the finer) and the AFT's minimum of 128
 * samples for contact laws: every point converges and the four folds come out within
 * 0.5 % of the H = 20 ones (555.351, 353.551, 479.79, 369.314 rad/s at 1024 and 2048
 * samples), the third within 0.6 %: the branch runs at H = 3, whose folds are 555.222,
 * 353.818, 482.360, 369.740 rad/s (the same at 26 and 81 speeds to 2e-10). The third is
 * the highest tooth of the sampled branch's zigzag at its turn (a tooth per sample
 * switching contact): at H = 3 it lies at 481.064 with 1024 samples and 481.049 with
 * 4096, so 1.26 rad/s of the 2.57 (0.54 %) are H = 3's truncation and 1.31 the 128
 * samples. (The tangent rule placed it at 479.36 on a tooth below the turn.) At 32
 * samples (H = 7) Newton cycled near grazing and the arclength stalled at the first fold
 * for its 1500 steps. */
TEST(backlash_branch_with_auto_harmonics)
{
    fx f;
    gd_transient_model *tm = NULL;
    REQUIRE(load_spec(&f, backlash_yaml(), &tm));
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.adaptive = 1;
    o.stability = 0;
    gd_tr_record rec = {GD_REC_MESH_FORCE, 0, 0};
    gd_periodic_result *r = run_speeds(&f, &tm->spec, 300, 800, 26, &o, &rec, 1);
    REQUIRE(r);
    int bad = 0, folds = 0, near = 0, unest = 0;
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        bad += !p->converged;
        if (p->converged && p->harmonic_ok == 1) CHECK(p->harmonic_error_p2p <= 0.01);
        /* next to a fold the refined branch may not reach the point (480 rad/s: the
         * solution at H = 7 from the H = 3 one fails): it stands, not estimated, and
         * says so */
        if (p->converged && p->harmonic_ok < 0) {
            unest++;
            CHECK(strstr(p->reason, "not estimated") != NULL);
        }
        CHECK(p->harmonic_ok != 0);
    }
    CHECK(unest <= 1);
    const double at[4] = {555.351, 353.551, 479.79, 369.314}, tol[4] = {5e-3, 5e-3, 6e-3, 5e-3};
    for (int i = 0; i < r->nbifurcations; i++) {
        if (r->bifurcations[i].type != GD_BIF_FOLD) continue;
        folds++;
        for (int k = 0; k < 4; k++)
            near += fabs(r->bifurcations[i].speed - at[k]) < tol[k] * at[k];
        printf("  fold at %.3f rad/s\n", r->bifurcations[i].speed);
    }
    printf("  %d points, %d steps, %d not converged\n", r->npoints, r->steps, bad);
    CHECK(bad == 0 && r->npoints >= 56);
    CHECK(folds == 4 && near == 4);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The same pair at H = 3 over 300..2500 rad/s with 45 speeds (arclength steps 4.4 times
 * longer in speed than over 300..800): the corrector once jumped from 354.04 to 428.14
 * rad/s (20 iterations) onto the part of the branch already traced, the chord turned
 * there and the loop was traced twice (five folds, 65 points). A corrector landing more
 * than 3 steps away is now refused: four folds, equal to the 26-speed run over 300..800
 * (555.2221283909, 353.8182313419, 482.3602396383, 369.7404411236) to 1e-8 (measured
 * 1e-11), 57 points (45 and the 12 inside the two loops). */
TEST(backlash_wide_range_no_retrace)
{
    fx f;
    gd_transient_model *tm = NULL;
    REQUIRE(load_spec(&f, backlash_yaml(), &tm));
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 3;
    o.estimate = 0;
    o.stability = 0;
    gd_periodic_result *r = run_speeds(&f, &tm->spec, 300, 2500, 45, &o, NULL, 0);
    REQUIRE(r);
    const double at[4] = {555.2221283909, 353.8182313419, 482.3602396383, 369.7404411236};
    int bad = 0;
    for (int i = 0; i < r->npoints; i++)
        bad += !r->points[i].converged;
    for (int i = 0; i < r->nbifurcations; i++)
        printf("  %s at %.10f rad/s\n", gd_bifurcation_name(r->bifurcations[i].type),
               r->bifurcations[i].speed);
    printf("  %d points, %d steps\n", r->npoints, r->steps);
    CHECK(bad == 0 && r->npoints == 57);
    CHECK(r->nbifurcations == 4);
    for (int i = 0; i < 4 && i < r->nbifurcations; i++)
        CHECK_REL(r->bifurcations[i].speed, at[i], 1e-8);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Softening by tooth separation bends the mesh resonance to low speeds: over 300..800
 * rad/s the branch turns four times (two hysteresis loops); the arclength traces it
 * through its unstable parts. Every requested speed in a loop has three solutions, the
 * middle one unstable with a real multiplier beyond +1, and the stability changes exactly
 * at the folds. The Floquet multipliers of an unstable point on the separating branch
 * against gd_transient_monodromy (CVODE from the HB state): see the tolerance below. */
TEST(backlash_folds_traced_through_unstable_branch)
{
    fx f;
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(load_spec(&f, backlash_yaml(), &tm));
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 20;
    o.monodromy_steps = 128; /* split at every contact change anyway */
    gd_periodic_result *r = run_speeds(&f, &tm->spec, 300, 800, 26, &o, NULL, 0);
    REQUIRE(r);
    /* the four turning points of the two loops, and nothing else (near 480 rad/s the
     * sampled branch's zigzag is one fold, below) */
    const double at[4] = {555.35, 353.52, 480.79, 369.18};
    int seen[4] = {0, 0, 0, 0}, stray = 0;
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        int hit = -1;
        for (int k = 0; k < 4; k++)
            if (fabs(b->speed - at[k]) < 2.0) hit = k;
        if (b->type != GD_BIF_FOLD || hit < 0)
            stray++;
        else
            seen[hit]++;
        printf("  %s at %.3f rad/s\n", gd_bifurcation_name(b->type), b->speed);
    }
    printf("  %d points, %d bifurcations, %d steps\n", r->npoints, r->nbifurcations, r->steps);
    CHECK(seen[0] == 1 && seen[1] == 1 && seen[2] == 1 && seen[3] == 1);
    CHECK(stray == 0);
    int at400 = 0, unstable400 = -1, flips = 0;
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        CHECK(p->converged);
        if (fabs(p->speed - 400) < 1e-9) {
            at400++;
            if (!p->stable) unstable400 = i;
        }
        if (i && p->stable != r->points[i - 1].stable) flips++;
    }
    CHECK(at400 == 5); /* two loops overlap at 400 rad/s: five solutions */
    CHECK(flips == 4);
    {
        /* the folds are located on the branch, not on the grid: 26 and 81 speeds give
         * the same folds to 1e-8 (measured 4e-11, 1e-12, 3.4e-10, 1e-12). Near 480 rad/s
         * the sampled branch (128 samples) zigzags at its turn, a tooth per sample
         * switching contact: the fold is its highest tooth, 480.7899697 (the located
         * tooth the steps came near before: 479.36 and 480.79; with 2048 samples the
         * turn is at 479.7925, within 1.2e-5 of 1024's; shooting on CVODE's period map
         * with located contact events puts the continuous contact's fold at 479.788) */
        gd_periodic_options o2 = o;
        o2.stability = 0;
        o2.estimate = 0;
        gd_periodic_result *r2 = run_speeds(&f, &tm->spec, 300, 800, 81, &o2, NULL, 0);
        REQUIRE(r2);
        CHECK(r2->nbifurcations == r->nbifurcations);
        for (int i = 0; i < r->nbifurcations && i < r2->nbifurcations; i++) {
            printf("  fold %.9f (26 speeds) %.9f (81 speeds)\n", r->bifurcations[i].speed,
                   r2->bifurcations[i].speed);
            CHECK_REL(r2->bifurcations[i].speed, r->bifurcations[i].speed, 1e-8);
        }
        gd_periodic_result_free(r2);
    }
    REQUIRE(unstable400 >= 0);
    const gd_periodic_point *p = &r->points[unstable400];
    gd_transient *tr = NULL;
    REQUIRE(gd_transient_new(f.s, &tm->spec, 400.0, &tr, &err) == GD_OK);
    int nf = p->nfree, ns = 2 * nf;
    double y0[2] = {0, 0}, phi[4], wr[2], wi[2], dummy[1];
    REQUIRE(ns == 2);
    for (int k = 0; k <= p->harmonics; k++) {
        y0[0] += p->coef[(k ? 2 * k - 1 : 0) * nf];
        if (k) y0[1] += p->omega * k * p->coef[2 * k * nf];
    }
    gd_transient_options to;
    gd_transient_options_init(&to);
    to.rtol = 1e-11;
    to.atol_q = 1e-17;
    to.atol_v = 1e-13;
    REQUIRE(gd_transient_monodromy(tr, 0.0, 2 * M_PI / p->omega, y0, &to, phi, NULL, &err) ==
            GD_OK);
    REQUIRE(LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', ns, phi, ns, wr, wi, dummy, 1, dummy, 1) ==
            0);
    double worst = 0.0;
    for (int a = 0; a < ns; a++) {
        double best = INFINITY;
        for (int b = 0; b < ns; b++)
            best = fmin(best, hypot(p->mu_re[a] - wr[b], p->mu_im[a] - wi[b]));
        worst = fmax(worst, best);
    }
    printf("  unstable point at 400 rad/s: HB multipliers %.8f, %.8f; integrated %.8f, %.8f; "
           "max distance %.2e\n",
           p->mu_re[0], p->mu_re[1], wr[0], wr[1], worst);
    /* the orbit itself carries the truncation error of H = 20 harmonics of a force with
     * kinks (measured 1.5e-3 here, 4e-4 with H = 40: ~H^-2); smooth laws reach 1e-10
     * (floquet_against_monodromy) */
    CHECK(worst <= 2e-3 * p->mu_max);
    gd_transient_free(tr);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The Chen SFD pair with the unbalance read as e_u/C = 1/2 (3 x the example's; [Chen1998]
 * Figs. 9-11): transient sweeps (docs/transient.md, poincare helper) find period-1 up
 * to 5582 rad/s, a Neimark-Sacker bifurcation at 5583 rad/s with the complex pair at
 * 44.5 deg (the 0.876x line), quasi-periodic motion to 5740 and period-1 again from 5760
 * rad/s. Harmonic balance with Floquet multipliers, independently: the same two
 * Neimark-Sacker points (to the 2 rad/s of the sweeps; 10 rad/s at the upper end where
 * they sampled 20 rad/s) and the same angle to 1 deg. */
TEST(chen_sfd_neimark_sacker_matches_transient)
{
    fx f;
    gd_load_options lo;
    const char *set[1] = {"unbalances.gear_a_unbalance.eccentricity=38.1um"};
    lo.nset = 1;
    lo.set = set;
    gd_error err;
    memset(&f, 0, sizeof f);
    REQUIRE(gd_model_load_opts(GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", &lo, &f.m,
                               &err) == GD_OK);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    gd_transient_model *tm = NULL;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 12;
    o.monodromy_steps = 128; /* smooth laws: ample for a 2 rad/s location */
    /* from rest Newton needs a start away from the resonance: 5350 rad/s (at 5560 it
     * fails; the arclength then carries the solution) */
    gd_periodic_result *r = run_speeds(&f, &tm->spec, 5350, 5800, 46, &o, NULL, 0);
    REQUIRE(r);
    int ns = 0;
    double at[2] = {0, 0}, ang = 0;
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        printf("  %s at %.3f rad/s, multiplier %.6f%+.6fi (%.2f deg)\n",
               gd_bifurcation_name(b->type), b->speed, b->mu_re, b->mu_im,
               atan2(b->mu_im, b->mu_re) * 180 / M_PI);
        if (b->type == GD_BIF_NEIMARK_SACKER && b->speed > 5560 && ns < 2) {
            if (!ns) ang = atan2(b->mu_im, b->mu_re) * 180 / M_PI;
            at[ns++] = b->speed;
        }
    }
    REQUIRE(ns == 2);
    CHECK(fabs(at[0] - 5583) < 2.0);
    CHECK(at[1] > 5740 && at[1] < 5760);
    CHECK(fabs(ang - 44.5) < 1.0);
    /* on the last pass over 5560..5800 (the branch's end part) stability changes there */
    int last = r->npoints - 1, bad = 0;
    for (int i = last; i >= 0 && r->points[i].speed >= 5560; i--) {
        const gd_periodic_point *p = &r->points[i];
        int inside = p->speed > at[0] && p->speed < at[1];
        bad += !p->converged || p->stable != !inside;
    }
    CHECK(bad == 0);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* ------------------------------------------------------------------ linear solvers */

/* max |X_a - X_b| / max |X_a| over the converged points of two runs of the same speeds
 * (-1 if the runs differ in their points, convergence or Newton iterations, or fewer than 4
 * converged). */
static double coef_difference(const gd_periodic_result *a, const gd_periodic_result *b)
{
    if (!a || !b || a->npoints != b->npoints) return -1.0;
    double d = 0.0, m = 0.0;
    int both = 0;
    for (int i = 0; i < a->npoints; i++) {
        const gd_periodic_point *p = &a->points[i], *q = &b->points[i];
        if (p->converged != q->converged || p->speed != q->speed) return -1.0;
        if (!p->converged) continue; /* the same failure in both (the same reason) */
        /* equal iteration counts: a Jacobian that were only near would still converge,
         * to the same solution, but in more iterations */
        if (p->harmonics != q->harmonics || p->iterations != q->iterations) return -1.0;
        both++;
        size_t n = (size_t)p->nfree * (2 * p->harmonics + 1);
        for (size_t j = 0; j < n; j++) {
            double e = fabs(p->coef[j] - q->coef[j]), v = fabs(p->coef[j]);
            d = e > d ? e : d;
            m = v > m ? v : m;
        }
    }
    if (both < 4) return -1.0;
    return m > 0 ? d / m : d;
}

/* The low-rank (Woodbury) Newton solver against the sparse LU of the whole system, on
 * every kind of term it groups: a mesh with TVMS, STE and backlash (two terms, one force
 * direction, the second following the driver angle), the SFD pair (four terms, two
 * directions) and a constant mesh (rank one). Sequential points (fixed speed, plain
 * Newton) and one arclength run (the bordered system). The same Newton iterates up to
 * rounding: equal iteration counts and coefficients within 1e-11 of the largest
 * (measured: 4e-16 to 7e-15). */
TEST(lowrank_solver_equals_sparse_lu)
{
    struct {
        const char *name;
        char *yaml;
        const char *path;
        double w0, w1;
        int H, method;
    } cases[4] = {
        {"backlash pair", backlash_yaml(), NULL, 300, 800, 12, GD_PER_SEQUENTIAL},
        {"backlash pair, arclength", backlash_yaml(), NULL, 450, 600, 12, GD_PER_ARCLENGTH},
        {"Chen SFD pair", NULL, GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", 900, 1500, 10,
         GD_PER_SEQUENTIAL},
        {"Chen pair, linear", NULL, NULL, 300, 2500, 3, GD_PER_SEQUENTIAL},
    };
    for (int c = 0; c < 4; c++) {
        fx f;
        gd_transient_model *tm = NULL;
        gd_error err;
        if (cases[c].yaml) {
            REQUIRE(load_spec(&f, cases[c].yaml, &tm));
        } else {
            REQUIRE(load(&f, cases[c].path, cases[c].path ? NULL : chen_linear));
            REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
        }
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = cases[c].H;
        o.stability = 0;
        o.method = cases[c].method;
        gd_periodic_result *r[2];
        for (int sv = 0; sv < 2; sv++) {
            o.solver = sv + 1;
            r[sv] = run_speeds(&f, &tm->spec, cases[c].w0, cases[c].w1, 7, &o, NULL, 0);
        }
        double d = coef_difference(r[0], r[1]);
        printf("  %-26s %d points: |X_lowrank - X_sparse| / max|X| = %.3g\n", cases[c].name,
               r[0] ? r[0]->npoints : 0, d);
        CHECK(d >= 0.0 && d <= 1e-11);
        gd_periodic_result_free(r[0]);
        gd_periodic_result_free(r[1]);
        gd_transient_model_free(tm);
        fx_free(&f);
    }
}

/* The iterative capacitance (GMRES on the AFT matvecs, capacitance.c) against the dense LU
 * of the same capacitance, on small models forced onto it (solver 3 against 4): a
 * backlash pair (mesh with TVMS and backlash: one group, the driver-angle term) by
 * sequential Newton and by arclength (the bordered solves), and the Chen SFD pair (two
 * groups, four terms). GMRES stops at 1e-12 of the right-hand side, so the Newton iterates
 * agree to about that: equal iteration counts and coefficients within 1e-10 of the
 * largest. */
TEST(iterative_capacitance_equals_dense)
{
    struct {
        const char *name;
        char *yaml;
        const char *path;
        double w0, w1;
        int H, method;
    } cases[3] = {
        {"backlash pair", backlash_yaml(), NULL, 300, 800, 8, GD_PER_SEQUENTIAL},
        {"backlash pair, arclength", backlash_yaml(), NULL, 450, 600, 8, GD_PER_ARCLENGTH},
        {"Chen SFD pair", NULL, GD_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", 900, 1500, 6,
         GD_PER_SEQUENTIAL},
    };
    for (int c = 0; c < 3; c++) {
        fx f;
        gd_transient_model *tm = NULL;
        if (cases[c].yaml) {
            REQUIRE(load_spec(&f, cases[c].yaml, &tm));
        } else {
            gd_error err;
            REQUIRE(load(&f, cases[c].path, NULL));
            REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
        }
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = cases[c].H;
        o.stability = 0;
        o.estimate = 0;
        o.method = cases[c].method;
        gd_periodic_result *r[2];
        for (int sv = 0; sv < 2; sv++) {
            o.solver = 3 + sv; /* iterative, dense */
            r[sv] = run_speeds(&f, &tm->spec, cases[c].w0, cases[c].w1, 5, &o, NULL, 0);
        }
        double d = coef_difference(r[0], r[1]);
        printf("  %-26s %d points: |X_iterative - X_dense| / max|X| = %.3g\n", cases[c].name,
               r[0] ? r[0]->npoints : 0, d);
        CHECK(d >= 0.0 && d <= 1e-10);
        gd_periodic_result_free(r[0]);
        gd_periodic_result_free(r[1]);
        gd_transient_model_free(tm);
        fx_free(&f);
    }
}

/* Two or four Magnus steps per period of a subharmonic-3 Mathieu orbit: each step spans
 * many natural periods, the step exponential overflows and the monodromy matrix is
 * +-inf. The multipliers are then not computed (stable -1, no multipliers) with the
 * reason and the fix, never an eigenvalue solve of non-finite numbers (which corrupted
 * the heap inside LAPACK). Issue 23. */
TEST(few_magnus_steps_leave_stability_undecided)
{
    fx f;
    gd_transient_model *tm = NULL;
    REQUIRE(load_spec(&f, mathieu_yaml(0.05, 0.005), &tm));
    const int steps[2] = {2, 4};
    for (int c = 0; c < 2; c++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = 4;
        o.subharmonic = 3;
        o.monodromy_steps = steps[c];
        gd_periodic_result *r = run_speeds(&f, &tm->spec, 0.5, 10.0, 4, &o, NULL, 0);
        REQUIRE(r);
        int undecided = 0;
        for (int i = 0; i < r->npoints; i++) {
            const gd_periodic_point *p = &r->points[i];
            if (!p->converged) continue;
            if (p->stable < 0) {
                undecided++;
                CHECK(p->nmult == 0 && isnan(p->mu_max));
                CHECK(strstr(p->reason, "monodromy") && strstr(p->reason, "monodromy_steps"));
            } else {
                CHECK(isfinite(p->mu_max));
            }
        }
        printf("  %d Magnus steps: %d of %d points without multipliers\n", steps[c], undecided,
               r->npoints);
        CHECK(undecided > 0);
        gd_periodic_result_free(r);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Option bounds in the library (Python calls it directly): 2^31 - 1 AFT samples asked
 * for about 100 GB; the limit 2^20 is named in the error, as are the Magnus step and
 * subharmonic bounds. Issue 23. */
TEST(option_bounds_named)
{
    fx f;
    gd_transient_model *tm = NULL;
    REQUIRE(load_spec(&f, mathieu_yaml(0.05, 0.005), &tm));
    const double v[1] = {700.0};
    for (int c = 0; c < 4; c++) {
        gd_periodic_options o;
        gd_periodic_options_init(&o);
        o.harmonics = 4;
        const char *field = c < 2 ? "samples" : c == 2 ? "monodromy_steps" : "subharmonic";
        if (c == 0) o.samples = 2147483647;
        if (c == 1) o.samples = -8;
        if (c == 2) o.monodromy_steps = 2147483647;
        if (c == 3) o.subharmonic = 2147483647;
        gd_periodic_result *r = NULL;
        gd_error err;
        CHECK(gd_periodic_run(f.s, &tm->spec, NULL, v, 1, &o, NULL, 0, &r, &err) == GD_EINPUT);
        CHECK(r == NULL);
        CHECK_STR(err.field, field);
        CHECK(c == 3 ? strstr(err.message, "1000") != NULL
                     : strstr(err.message, "1048576") != NULL);
        gd_periodic_result_free(r);
    }
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Speeds of 6e-154 and 8e-81 rad/s (subharmonic 3, 130 Magnus steps): a Magnus step
 * spans so many natural periods that its matrix norm is finite but above DBL_MAX / 2,
 * and the scaling exponent overflowed a float-to-int cast (undefined behaviour, caught
 * by the sanitizer build). Found by fuzz_inputs (its input, decoded). The run must end
 * with every converged point's multipliers finite or left undecided. */
TEST(extreme_low_speeds_scale_the_step_exponential)
{
    fx f;
    REQUIRE(load(&f, GD_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = 4;
    o.subharmonic = 3;
    o.monodromy_steps = 130;
    o.max_iter = 30;
    o.max_harmonics = 8;
    const double v[2] = {6.013469530795898e-154, 7.939827903423917e-81};
    gd_periodic_result *r = NULL;
    gd_status st = gd_periodic_run(f.s, &tm->spec, NULL, v, 2, &o, NULL, 0, &r, &err);
    CHECK(st == GD_OK || st == GD_EINPUT);
    int checked = 0;
    for (int i = 0; r && i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        if (!p->converged) continue;
        CHECK(p->stable < 0 ? p->nmult == 0 : isfinite(p->mu_max));
        checked++;
    }
    printf("  status %d, %d converged points checked\n", (int)st, checked);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* A record that is zero to rounding (the tilt of a spur gear in [JMSTHelical] at 0 deg:
 * 1e-20 rad against 5e-5 rad of torsion) has no truncation error: its relative changes
 * between H and 2 H + 1 are noise of order 1 (0.49-5.3 measured), which drove
 * --harmonics auto to H = 18943. A small but real record keeps its relative error. */
TEST(record_zero_to_rounding_has_no_truncation_error)
{
    const gd_tr_record rec[3] = {
        {GD_REC_DISP, 0, 0}, {GD_REC_VEL, 1, 0}, {GD_REC_MESH_FORCE, 0, 0}};
    const double X[4] = {5e-5, -1e-7, 2e-9, 0.0};
    double zero[3];
    gd_hb_record_zero(rec, 3, X, 4, 10, 20.0, zero);
    CHECK_ABS(zero[0], 5e-17, 1e-30);
    CHECK_ABS(zero[1], 5e-17 * 10 * 20.0, 1e-28);
    CHECK(zero[2] == 0.0); /* a force: no unit in common with the coefficients */
    gd_per_record_stats a[3], b[3];
    memset(a, 0, sizeof a);
    memset(b, 0, sizeof b);
    a[0].mean = 1.9e-20, a[0].peak_to_peak = 3.5e-20; /* noise at both H */
    b[0].mean = 5.8e-20, b[0].peak_to_peak = 4.2e-20;
    a[1].peak_to_peak = 1.0e-12, b[1].peak_to_peak = 1.1e-12; /* small, real: 10 % */
    a[2].mean = b[2].mean = 235.0, a[2].peak_to_peak = 73.8, b[2].peak_to_peak = 172.0;
    double p2p, amp;
    gd_hb_truncation(a, 10, b, 21, 3, zero, &p2p, &amp);
    CHECK(b[0].p2p_error == 0.0 && b[0].amp_error == 0.0);
    CHECK_ABS(b[1].p2p_error, 0.1 / 1.1, 1e-12);
    CHECK_ABS(b[2].p2p_error, (172.0 - 73.8) / 172.0, 1e-12);
    CHECK_ABS(p2p, (172.0 - 73.8) / 172.0, 1e-12);
    /* without the floors (NULL) the noise counts, as before */
    gd_hb_truncation(a, 10, b, 21, 3, NULL, &p2p, &amp);
    CHECK(b[0].p2p_error > 0.1);
}

/* A toy method for the natural-continuation driver (driver/sequential.c): one unknown on
 * y = v^2 up to v = 7, then flat at 49; its Newton converges from a start within 6.5 of the
 * solution and never at v = 4; its own start (cold) converges except at v = 4; no problem
 * can be made at v = 0. Every solve is logged as s<v>:<start> (c<v> for the cold start),
 * every between-rule call as b<la>-<lb>. */
typedef struct toy {
    char why[256], log[512], blog[128], fails[128];
    int steps, nemit;
} toy;

static double toy_y(double v)
{
    return v <= 7 ? v * v : 49.0;
}

static void toy_log(char *buf, size_t cap, const char *fmt, double a, double b)
{
    size_t len = strlen(buf);
    snprintf(buf + len, cap - len, fmt, a, b);
}

static int toy_size(void *m)
{
    (void)m;
    return 1;
}

static void toy_step(void *m)
{
    ((toy *)m)->steps++;
}

static int toy_prepare(void *m, double v)
{
    toy *t = m;
    if (v != 0) return 0;
    snprintf(t->why, sizeof t->why, "no problem at 0");
    return 1;
}

static int toy_solve(void *m, double *y, double v, int *it, double *res)
{
    toy *t = m;
    toy_log(t->log, sizeof t->log, " s%g:%g", v, y[0]);
    *it = 1;
    *res = 0;
    if (v == 4 || !(fabs(y[0] - toy_y(v)) < 6.5)) {
        snprintf(t->why, sizeof t->why, "toy Newton failed at %g", v);
        return 1;
    }
    y[0] = toy_y(v);
    return 0;
}

static int toy_cold(void *m, double **y, double v, int *it, double *res)
{
    toy *t = m;
    toy_log(t->log, sizeof t->log, " c%g", v, 0);
    *it = 5;
    *res = 0;
    if (v == 4) {
        snprintf(t->why, sizeof t->why, "toy start failed at %g", v);
        return 1;
    }
    (*y)[0] = toy_y(v);
    return 0;
}

static int toy_emit(void *m, const double *y, double v, int it, double res)
{
    toy *t = m;
    (void)it;
    (void)res;
    t->nemit++;
    return !(y[0] == toy_y(v));
}

static int toy_fail(void *m, double v)
{
    toy *t = m;
    size_t len = strlen(t->fails);
    snprintf(t->fails + len, sizeof t->fails - len, " %g(%s)", v, t->why);
    return 0;
}

static int toy_between(void *m, const double *ya, double la, const double *yb, double lb)
{
    toy *t = m;
    (void)ya;
    (void)yb;
    toy_log(t->blog, sizeof t->blog, " b%g-%g", la, lb);
    return 0;
}

/* The rules of the natural continuation, one method for all (issue 33 item 7): the first
 * point from the method's own start after a value whose problem cannot be made; then the
 * secant through the last two points, else the last point, else the method's own start (the
 * failed starts' reasons kept); a failed value keeps the history (5 starts from the secant
 * through 2 and 3); the bifurcation rule between consecutive points only; a step per value
 * after the first point. */
TEST(sequential_driver_rules)
{
    static const gd_per_arc_ops ops = {.size = toy_size,
                                       .step = toy_step,
                                       .prepare = toy_prepare,
                                       .cold = toy_cold,
                                       .cold_name = "the toy start",
                                       .solve_at = toy_solve,
                                       .emit = toy_emit,
                                       .fail = toy_fail,
                                       .between = toy_between};
    toy t;
    memset(&t, 0, sizeof t);
    const gd_per_arc a = {.ops = &ops, .m = &t, .why = t.why, .why_cap = sizeof t.why};
    const double v[9] = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    CHECK(gd_per_branch(&a, v, 9, 1) == 0);
    printf("  starts:%s\n  between:%s\n  failed:%s\n", t.log, t.blog, t.fails);
    CHECK(!strcmp(t.log, " c1 s2:1 s3:7 s4:14 s4:9 c4 s5:19 s6:33 s7:47 s8:62 s8:49"));
    CHECK(!strcmp(t.blog, " b1-2 b2-3 b5-6 b6-7 b7-8"));
    CHECK(!strcmp(t.fails, " 0(no problem at 0) 4(toy Newton failed at 4; from the toy "
                           "start: toy start failed at 4)"));
    CHECK(t.nemit == 7 && t.steps == 7);
}

RUN_TESTS(T(linear_equals_unbalance), T(mathieu_tongue_period_doubling),
          T(floquet_against_monodromy), T(backlash_against_transient),
          T(sfd_pair_against_transient), T(backlash_folds_traced_through_unstable_branch),
          T(backlash_wide_range_no_retrace), T(backlash_branch_with_auto_harmonics),
          T(chen_sfd_neimark_sacker_matches_transient), T(lowrank_solver_equals_sparse_lu),
          T(iterative_capacitance_equals_dense), T(few_magnus_steps_leave_stability_undecided),
          T(option_bounds_named), T(extreme_low_speeds_scale_the_step_exponential),
          T(record_zero_to_rounding_has_no_truncation_error), T(sequential_driver_rules))
