/* Multi-frequency (quasi-periodic) harmonic balance (src/periodic/multifreq, issue 33 item
 * 6) against three independent computations: a linear model under two loads of
 * incommensurate frequencies (the closed-form response to each), a two-stage train whose
 * mesh frequencies are commensurate (3:2: ordinary harmonic balance of their common
 * period), and the co-prime gearbox of examples/gearbox_coprime.yaml (a long transient). */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"
#include "periodic/multifreq/qphb_impl.h"

#define TWO_PI 6.28318530717958647692

static int cmp_desc(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x < y) - (x > y);
}

/* Solves the problem of f at speed on the torus of order H into *X (n; the caller frees). */
static int solve_torus(const fx *f, const gd_transient_model *tm, double speed, int H,
                       gd_transient **tr, gd_qp_bases *b, gd_qp *q, double **X)
{
    gd_error err;
    char msg[200] = "";
    if (gd_transient_new(f->s, &tm->spec, speed, tr, &err)) return 1;
    if (gd_qp_find_bases(*tr, f->s, &tm->spec, speed, b, msg, sizeof msg)) {
        printf("  bases: %s\n", msg);
        return 1;
    }
    if (gd_qp_init(q, *tr, b, H, msg, sizeof msg)) return 1;
    *X = calloc((size_t)q->n, sizeof **X);
    double res;
    int it;
    if (!*X || gd_qp_newton(q, *X, 1e-12, 30, &res, &it, msg, sizeof msg)) {
        printf("  newton: %s\n", msg);
        return 1;
    }
    printf("  torus order %d: %d harmonics, %ld unknowns, %d Newton steps, residual %.1e, %ld "
           "GMRES products\n",
           H, q->T.nk, q->n, it, res, q->matvecs);
    return 0;
}

/* Two disks on torsional springs, each under a load of its own frequency (50 Hz and
 * 50 sqrt 2 Hz: no common period). */
static const char *LINEAR = "dofs: [rz]\n"
                            "shafts:\n"
                            "  - {name: s, nodes: [{name: a}, {name: b}]}\n"
                            "disks:\n"
                            "  - {node: a, polar_inertia: 2e-3}\n"
                            "  - {node: b, polar_inertia: 5e-3}\n"
                            "springs:\n"
                            "  - {node: a, dof: rz, stiffness: 400, damping: 0.05}\n"
                            "  - {node: a, to: b, dof: rz, stiffness: 900, damping: 0.02}\n"
                            "  - {node: b, dof: rz, stiffness: 300}\n"
                            "excitations:\n"
                            "  loads:\n"
                            "    - {node: a, mean: 1.5, amplitude: 3, frequency: 50 Hz}\n"
                            "    - {node: b, amplitude: 2, frequency: 70.71067811865476 Hz, "
                            "phase: 30 deg}\n";

TEST(linear_two_frequencies_equal_the_closed_form)
{
    fx f;
    REQUIRE(load(&f, NULL, LINEAR));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_transient *tr = NULL;
    gd_qp_bases b;
    gd_qp q;
    double *X = NULL;
    memset(&b, 0, sizeof b);
    memset(&q, 0, sizeof q);
    REQUIRE(!solve_torus(&f, tm, 10.0, 4, &tr, &b, &q, &X));
    REQUIRE(b.d == 2);
    CHECK_REL(b.W[0], TWO_PI * 50, 1e-12);
    CHECK_REL(b.W[1], TWO_PI * 70.71067811865476, 1e-12);
    CHECK(b.common == 0.0); /* incommensurate: no common period of modest order */
    /* closed form: Z = (K - w^2 M + i w D)^-1 e_j F e^{i phi}, q = Re(Z e^{i w t}):
     * C = Re Z, S = -Im Z; the mean K^-1 e_a 1.5 */
    const double Ia = 2e-3, Ib = 5e-3, ka = 400, kc = 900, kb = 300, ca = 0.05, cc = 0.02;
    const int ia = 0, ib = 1; /* free DOFs in DOF order */
    double det = (ka + kc) * (kb + kc) - kc * kc;
    CHECK_REL(X[ia], 1.5 * (kb + kc) / det, 1e-10);
    CHECK_REL(X[ib], 1.5 * kc / det, 1e-10);
    double peak = 0.0, off = 0.0;
    for (int j = 1; j < q.T.nk; j++) {
        const int *k = q.T.k + 2 * j;
        double complex Z[2] = {0, 0};
        if (k[0] == 1 && k[1] == 0) {
            const double w = b.W[0];
            double complex A11 = ka + kc - w * w * Ia + I * w * (ca + cc), A12 = -kc - I * w * cc,
                           A22 = kb + kc - w * w * Ib + I * w * cc, dt = A11 * A22 - A12 * A12;
            Z[0] = A22 * 3.0 / dt;
            Z[1] = -A12 * 3.0 / dt;
        } else if (k[0] == 0 && k[1] == 1) {
            const double w = b.W[1];
            double complex A11 = ka + kc - w * w * Ia + I * w * (ca + cc), A12 = -kc - I * w * cc,
                           A22 = kb + kc - w * w * Ib + I * w * cc, dt = A11 * A22 - A12 * A12;
            double complex F = 2.0 * cexp(I * TWO_PI * 30 / 360);
            Z[0] = -A12 * F / dt;
            Z[1] = A11 * F / dt;
        }
        for (int i = 0; i < 2; i++) {
            double C = X[(2 * j - 1) * 2 + i], S = X[2 * j * 2 + i];
            double e = hypot(C - creal(Z[i]), S + cimag(Z[i]));
            peak = fmax(peak, cabs(Z[i]));
            off = fmax(off, e);
        }
    }
    printf("  largest amplitude %.6e rad, largest difference from the closed form %.2e\n", peak,
           off);
    CHECK(peak > 1e-4);
    CHECK(off <= 1e-10 * peak);
    free(X);
    gd_qp_free(&q);
    gd_qp_bases_free(&b);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* A two-stage train whose mesh frequencies are 20 W and 20 x 20 / 30 W = 2/3 of it: the
 * common period holds 3 cycles of mesh 1 and 2 of mesh 2. Each TVMS a sinusoid of 10 %
 * (a spline through 64 points: its own harmonics near 64, which each method's
 * samples fold differently, below 1e-9). */
static char *commensurate_model(void)
{
    static char buf[16384];
    char t1[2400] = "", t2[2400] = "", a1[2400] = "", a2[2400] = "";
    for (int j = 0; j < 64; j++) {
        char s[64];
        snprintf(s, sizeof s, "%s%.17g", j ? ", " : "", TWO_PI / 20 * j / 64);
        strcat(a1, s);
        strcat(a2, s);
        snprintf(s, sizeof s, "%s%.17g", j ? ", " : "", 2e8 * (1 + 0.1 * cos(TWO_PI * j / 64)));
        strcat(t1, s);
        snprintf(s, sizeof s, "%s%.17g", j ? ", " : "",
                 3e8 * (1 + 0.08 * cos(TWO_PI * j / 64 + 0.7)));
        strcat(t2, s);
    }
    snprintf(buf, sizeof buf,
             "dofs: [rz]\n"
             "speed: 300 rad/s\n"
             "shafts:\n"
             "  - {name: input, nodes: [{name: motor}, {name: p1}]}\n"
             "  - {name: mid, nodes: [{name: g2}, {name: p3}]}\n"
             "  - {name: output, nodes: [{name: g4}]}\n"
             "disks:\n"
             "  - {node: motor, polar_inertia: 0.02}\n"
             "  - {node: p1, polar_inertia: 1e-4}\n"
             "  - {node: g2, polar_inertia: 2e-3}\n"
             "  - {node: p3, polar_inertia: 1e-4}\n"
             "  - {node: g4, polar_inertia: 8e-3}\n"
             "springs:\n"
             "  - {node: motor, to: p1, dof: rz, stiffness: 2e4, damping: 1}\n"
             "  - {node: g2, to: p3, dof: rz, stiffness: 3e4, damping: 1}\n"
             "meshes:\n"
             "  - {name: m1, driver: p1, driven: g2, teeth: [20, 30], base_radius: [0.02, 0.03],\n"
             "     pressure_angle: 20 deg, coupling: torsional, damping: 400,\n"
             "     tvms: {interpolation: spline, angle: [%s], stiffness: [%s]}}\n"
             "  - {name: m2, driver: p3, driven: g4, teeth: [20, 40], base_radius: [0.02, 0.04],\n"
             "     pressure_angle: 20 deg, coupling: torsional, damping: 500,\n"
             "     tvms: {interpolation: spline, angle: [%s], stiffness: [%s]}}\n"
             "prescribed:\n"
             "  - {node: motor, motion: nominal}\n"
             "excitations:\n"
             "  loads: [{node: g4, value: -40}]\n",
             a1, t1, a2, t2);
    return buf;
}

TEST(commensurate_meshes_equal_ordinary_harmonic_balance)
{
    fx f;
    REQUIRE(load(&f, NULL, commensurate_model()));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double speed = 300.0;
    gd_transient *tr = NULL;
    gd_qp_bases b;
    gd_qp q;
    double *X = NULL;
    memset(&b, 0, sizeof b);
    memset(&q, 0, sizeof q);
    REQUIRE(!solve_torus(&f, tm, speed, 20, &tr, &b, &q, &X));
    REQUIRE(b.d == 2);
    CHECK_REL(b.W[0], 2.0 / 3.0 * 20 * speed, 1e-12);
    CHECK_REL(b.W[1], 20 * speed, 1e-12);
    CHECK(b.order == 3);
    /* ordinary harmonic balance of the common period (w0 = 20 W / 3): the torus of order
     * 20 holds orders up to 20 x 3 (its cut: 20 times the highest base) */
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = GD_PER_HB;
    o.harmonics = 64;
    o.estimate = 0;
    o.stability = 0;
    o.tol = 1e-12;
    o.method = GD_PER_SEQUENTIAL;
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, &speed, 1, &o, NULL, 0, &r, &err) == GD_OK);
    REQUIRE(r->npoints == 1 && r->points[0].converged);
    const gd_periodic_point *p = &r->points[0];
    CHECK_REL(p->omega, 20 * speed / 3, 1e-12);
    const int nf = p->nfree;
    REQUIRE(nf == q.nf);
    double dmax = 0.0, amp = 0.0;
    double qt[16], vt[16];
    for (int s = 0; s < 60; s++) {
        const double t = TWO_PI / p->omega * s / 60.0;
        gd_qp_eval(&q, X, t, qt, vt);
        for (int i = 0; i < nf; i++) {
            double h = p->coef[i];
            for (int k = 1; k <= p->harmonics; k++)
                h += p->coef[(2 * k - 1) * nf + i] * cos(k * p->omega * t) +
                     p->coef[2 * k * nf + i] * sin(k * p->omega * t);
            dmax = fmax(dmax, fabs(h - qt[i]));
            amp = fmax(amp, fabs(qt[i] - X[i]));
        }
    }
    printf("  largest vibration %.4e rad, largest difference from ordinary HB (H = 64) %.2e "
           "(%.1e of it)\n",
           amp, dmax, dmax / amp);
    CHECK(amp > 1e-7);
    CHECK(dmax <= 1e-8 * amp);
    gd_periodic_result_free(r);
    free(X);
    gd_qp_free(&q);
    gd_qp_bases_free(&b);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The co-prime gearbox with default options (auto method and harmonics, stability on)
 * against a long transient at 900 and 1700 rpm: the dynamic mesh forces (the standard
 * deviation and the peak-to-peak of each mesh force) within 3 % (measured: 1.55 % and
 * 0.83 % at most), every point stable by the Floquet multipliers of its common period.
 * The transient's numbers are stored (integrating them took 30 s CPU): each from
 *   geardyn transient examples/gearbox_coprime.yaml --speed RPMrpm --duration (700 + 134) Tm
 *     --from 700 Tm --output-interval Tm/512 --rtol 1e-9 --record mesh:stage1 --record mesh:stage2
 * (Tm = 2 pi / (23 W): 700 mesh cycles settled to 1e-4 of the mean force, then two common
 * periods of 67 cycles, sampled at 512 per cycle as the slice); bench/bench_multifreq.sh
 * BUILD --check recomputes them and compares with these. */
static const double REF_RPM[2] = {900, 1700};
/* per speed, per mesh: mean, standard deviation, peak-to-peak (N) */
static const double REF[2][2][3] = {{{255.02, 19.943, 283.94}, {719.44, 26.023, 291.88}},
                                    {{255.02, 42.541, 426.67}, {719.44, 89.255, 652.69}}};

TEST(coprime_gearbox_equals_long_transient)
{
    fx f;
    REQUIRE(load(&f, "examples/gearbox_coprime.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    double speeds[2];
    for (int i = 0; i < 2; i++)
        speeds[i] = REF_RPM[i] * TWO_PI / 60;
    gd_tr_record rec[2] = {{GD_REC_MESH_FORCE, 0, 0}, {GD_REC_MESH_FORCE, 1, 0}};
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = GD_PER_AUTO;
    o.adaptive = 1; /* the CLI's defaults */
    o.method = GD_PER_SEQUENTIAL;
    gd_periodic_result *r = NULL;
    REQUIRE(gd_periodic_run(f.s, &tm->spec, NULL, speeds, 2, &o, rec, 2, &r, &err) == GD_OK);
    printf("  %s\n", r->method_note);
    CHECK(r->method == GD_PER_MULTIFREQ);
    REQUIRE(r->npoints == 2);
    for (int i = 0; i < 2; i++) {
        const gd_periodic_point *p = &r->points[i];
        REQUIRE(p->converged);
        printf("  %.0f rpm: |mu|max %.6g (%d multipliers, %s)\n", REF_RPM[i], p->mu_max, p->nmult,
               p->stability_method == GD_PER_MULTIFREQ ? "the common period's monodromy" : "?");
        CHECK(p->stable == 1);
        CHECK(p->stability_method == GD_PER_MULTIFREQ);
        CHECK(p->nmult == 2 * 5);
        CHECK(p->mu_max > 1e-4 && p->mu_max < 0.1); /* measured 0.0017 at 900 rpm */
        for (int m = 0; m < 2; m++) {
            const gd_per_record_stats *s = &p->records[m];
            const double *t = REF[i][m];
            double std_qp = sqrt(fmax(0.0, s->rms * s->rms - s->mean * s->mean));
            printf(
                "  %.0f rpm mesh %d (order %d): mean %.5g / %.5g N, std %.5g / %.5g N (%.2f %%), "
                "p2p %.5g / %.5g N (%.2f %%)\n",
                REF_RPM[i], m + 1, p->harmonics, s->mean, t[0], std_qp, t[1],
                100 * fabs(std_qp - t[1]) / t[1], s->peak_to_peak, t[2],
                100 * fabs(s->peak_to_peak - t[2]) / t[2]);
            CHECK_REL(s->mean, t[0], 1e-3);
            CHECK_REL(std_qp, t[1], 0.03);
            CHECK_REL(s->peak_to_peak, t[2], 0.03);
        }
    }
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The condensed torus (the laws' coordinates, gd_qpc) equals the full one (every DOF,
 * gd_qp) at the same order on the co-prime gearbox: the same equations, other unknowns. */
TEST(condensed_torus_equals_full_torus)
{
    fx f;
    REQUIRE(load(&f, "examples/gearbox_coprime.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double speed = 1300 * TWO_PI / 60;
    gd_transient *tr = NULL;
    gd_qp_bases b;
    gd_qp q;
    double *X = NULL;
    memset(&b, 0, sizeof b);
    memset(&q, 0, sizeof q);
    REQUIRE(!solve_torus(&f, tm, speed, 8, &tr, &b, &q, &X));
    REQUIRE(gd_qpc_applies(tr) > 0);
    char msg[200] = "";
    gd_qpc *c = gd_qpc_new(tr, &b, 8, msg, sizeof msg);
    REQUIRE(c != NULL);
    double *Xc = calloc((size_t)q.n, sizeof *Xc), res = 0.0;
    int it = 0;
    REQUIRE(Xc && !gd_qpc_newton(c, Xc, 1e-12, 30, &res, &it, msg, sizeof msg));
    double dmax = 0.0, xmax = 0.0;
    for (long i = q.nf; i < q.n; i++) { /* the vibration (the means are 1e3 times larger) */
        dmax = fmax(dmax, fabs(Xc[i] - X[i]));
        xmax = fmax(xmax, fabs(X[i]));
    }
    printf("  condensed: %d Newton steps, %ld products; largest harmonic %.4e, largest "
           "difference from the full torus %.2e (%.1e of it)\n",
           it, gd_qpc_matvecs(c), xmax, dmax, dmax / xmax);
    CHECK(xmax > 1e-7);
    CHECK(dmax <= 1e-9 * xmax);
    free(Xc);
    gd_qpc_free(c);
    free(X);
    gd_qp_free(&q);
    gd_qp_bases_free(&b);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* The stability of a torus point (gd_qp_stability: the Magnus monodromy over the common
 * period on the slice's local Jacobians) equals the integrated monodromy
 * (gd_transient_monodromy, CVODE at rtol 1e-7) from the slice's state at t = 0: every
 * multiplier's modulus, on the co-prime gearbox at 1700 rpm (torus order 16); and so does
 * the reduced basis that takes models over shoot_dense_max states, forced here. */
TEST(magnus_monodromy_equals_the_integrated_one)
{
    fx f;
    REQUIRE(load(&f, "examples/gearbox_coprime.yaml", NULL));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    const double speed = 1700 * TWO_PI / 60;
    gd_transient *tr = NULL;
    gd_qp_bases b;
    gd_qp q;
    double *X = NULL;
    memset(&b, 0, sizeof b);
    memset(&q, 0, sizeof q);
    REQUIRE(!solve_torus(&f, tm, speed, 16, &tr, &b, &q, &X));
    REQUIRE(b.common > 0);
    const int nf = q.nf, n = 2 * nf;
    gd_periodic_point p;
    memset(&p, 0, sizeof p);
    char note[200] = "";
    gd_periodic_options po;
    gd_periodic_options_init(&po);
    REQUIRE(!gd_qp_stability(tr, &b, X, q.T.k, q.T.nk, nf, &po, &p, note, sizeof note));
    REQUIRE(p.nmult == n && p.mu_re && p.mu_im);
    /* the slice's state at t = 0, as gd_qp_stability takes it */
    double *y0 = calloc((size_t)n, sizeof *y0), *phi = malloc((size_t)n * n * sizeof *phi);
    REQUIRE(y0 && phi);
    gd_qp_eval(&q, X, 0.0, y0, y0 + nf);
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = 1e-7;
    o.atol_q *= 0.1;
    o.atol_v *= 0.1;
    REQUIRE(gd_transient_monodromy(tr, 0.0, TWO_PI / b.common, y0, &o, phi, NULL, &err) == GD_OK);
    double complex ev[64];
    double wr[64], wi[64], ma[64], mb[64];
    REQUIRE(!LAPACKE_dgeev(LAPACK_COL_MAJOR, 'N', 'N', n, phi, n, wr, wi, NULL, 1, NULL, 1));
    for (int i = 0; i < n; i++) {
        ev[i] = wr[i] + I * wi[i];
        ma[i] = cabs(ev[i]);
        mb[i] = hypot(p.mu_re[i], p.mu_im[i]);
    }
    qsort(ma, (size_t)n, sizeof *ma, cmp_desc);
    qsort(mb, (size_t)n, sizeof *mb, cmp_desc);
    double dmax = 0.0;
    for (int i = 0; i < n; i++)
        dmax = fmax(dmax, fabs(ma[i] - mb[i]));
    printf("  1700 rpm: |mu|max %.7f by Magnus, %.7f integrated; largest difference of the "
           "moduli %.2e\n",
           mb[0], ma[0], dmax);
    CHECK(mb[0] > 1e-3);
    CHECK_REL(mb[0], ma[0], 1e-4);
    CHECK(dmax <= 1e-4 * ma[0]);
    /* over shoot_dense_max states the reduced basis of floquet_reduced.c takes the slice
     * (the full model's 274 states): here forced at 10 states (limit 4), its multipliers
     * against the integrated monodromy's (measured: 1.3e-3 of |mu|max, the reduced steps'
     * own count settling to 1 % of each modulus' distance from the unit circle) */
    gd_periodic_point pr;
    memset(&pr, 0, sizeof pr);
    po.shoot_dense_max = 4;
    REQUIRE(!gd_qp_stability(tr, &b, X, q.T.k, q.T.nk, nf, &po, &pr, note, sizeof note));
    REQUIRE(pr.nmult == n && pr.mu_re && pr.mu_im);
    CHECK(strstr(note, "reduced basis") != NULL);
    double dred = 0.0;
    for (int i = 0; i < n; i++)
        mb[i] = hypot(pr.mu_re[i], pr.mu_im[i]);
    qsort(mb, (size_t)n, sizeof *mb, cmp_desc);
    for (int i = 0; i < n; i++)
        dred = fmax(dred, fabs(ma[i] - mb[i]));
    printf("  reduced basis (%s): |mu|max %.7f, largest difference of the moduli %.2e\n", note,
           mb[0], dred);
    CHECK_REL(mb[0], ma[0], 3e-3);
    CHECK(dred <= 3e-3 * ma[0]);
    free(pr.mu_re);
    free(pr.mu_im);
    free(p.mu_re);
    free(p.mu_im);
    free(y0);
    free(phi);
    free(X);
    gd_qp_free(&q);
    gd_qp_bases_free(&b);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    fx_free(&f);
}

/* Four base frequencies (the two meshes and two loads at 101 and 103 times the common
 * fundamental W 23 / 67) with a memory limit that harmonic balance of the common period
 * cannot meet: `auto` refuses before solving, naming the period and the H. */
TEST(auto_refuses_when_nothing_fits)
{
    static char text[8192];
    FILE *fp = fopen("examples/gearbox_coprime.yaml", "r");
    REQUIRE(fp != NULL);
    size_t len = fread(text, 1, sizeof text - 1, fp);
    fclose(fp);
    text[len] = '\0';
    const double W = 900 * TWO_PI / 60, w0 = 23 * W / 67;
    char loads[400];
    snprintf(loads, sizeof loads,
             "    - {name: load_torque, node: load, value: -60 N*m}\n"
             "    - {node: gear2, amplitude: 1, frequency: %.17g Hz}\n"
             "    - {node: gear4, amplitude: 1, frequency: %.17g Hz}\n",
             101 * w0 / TWO_PI, 103 * w0 / TWO_PI);
    char *at = strstr(text, "    - {name: load_torque");
    REQUIRE(at != NULL);
    char *eol = strchr(at, '\n');
    REQUIRE(eol != NULL);
    static char model[9000];
    snprintf(model, sizeof model, "%.*s%s%s", (int)(at - text), text, loads, eol + 1);
    fx f;
    REQUIRE(load(&f, NULL, model));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = GD_PER_AUTO;
    o.adaptive = 1;
    o.memory_limit = 1e6;
    gd_periodic_result *r = NULL;
    CHECK(gd_periodic_run(f.s, &tm->spec, NULL, &W, 1, &o, NULL, 0, &r, &err) == GD_EINPUT);
    printf("  %s\n", err.message);
    CHECK(r == NULL);
    CHECK(strstr(err.message, "2.91304 input revolutions") != NULL); /* W / w0 = 67 / 23 */
    CHECK(strstr(err.message, "H >= 2472") != NULL);                 /* 103 periods x 24 */
    CHECK(strstr(err.message, "more than 3 independent base frequencies") != NULL);
    gd_periodic_result_free(r);
    gd_transient_model_free(tm);
    fx_free(&f);
}

RUN_TESTS(T(linear_two_frequencies_equal_the_closed_form),
          T(commensurate_meshes_equal_ordinary_harmonic_balance),
          T(coprime_gearbox_equals_long_transient), T(condensed_torus_equals_full_torus),
          T(magnus_monodromy_equals_the_integrated_one), T(auto_refuses_when_nothing_fits))
