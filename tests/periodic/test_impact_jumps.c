/* The clearance oscillator of Comparin & Singh (J. Sound Vib. 134, 1989, 259) in closed
 * form against geardyn (docs/rattle.md, "Jumps of a clearance oscillator", Eqs. R1-R12):
 * examples/impact_oscillator.yaml is x'' + 2 zeta x' + f(x) = F_m + F_a cos(Omega tau),
 * f the dead zone of half-width 1. Its periodic motion with one separation per period is
 * exact on each linear piece; the crossing times follow from a 2 x 2 Newton, the branch
 * from a pseudo-arclength in (t_s, Omega, s) and its folds from the extrema of Omega along
 * it. Checked: shooting's orbits (their sampled peak-to-peak, mean and first harmonic)
 * and stability, its two folds (the jump frequencies), harmonic balance within its
 * truncation estimate, and a stepped sweep up and down in transient that jumps within a
 * step of the folds.
 *
 * With GD_IMPACT_CURVE=FILE the closed-form branch and shooting's points are written to
 * FILE (bench/impact_figure.py draws docs/figures/impact_response.svg from it). */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"

/* The example's numbers: m_e = J / r_b^2 = 1 kg, k = 1e8 N/m, c = 1000 N s/m, b = 10 um,
 * T_m = 5 N m, T_a = 1 N m at r_b = 50 mm. */
static const double WN = 1e4;                 /* sqrt(k / m_e), rad/s */
static const double GAP = 1e-5;               /* b, m */
static const double ZETA = 0.05;              /* c / (2 sqrt(k m_e)) */
static const double FM = 5.0 / 0.05 / 1000.0; /* T_m / (r_b k b) */
static const double FA = 1.0 / 0.05 / 1000.0; /* T_a / (r_b k b) */

/* Particular solutions (Eq. R3, R4): y = x - 1 and y' at tau, in contact or apart. */
static void particular(int contact, double om, double tau, double p[2])
{
    double complex h = contact ? 1.0 / (1.0 - om * om + 2.0 * I * ZETA * om)
                               : 1.0 / (-om * om + 2.0 * I * ZETA * om);
    double complex e = FA * h * cexp(I * om * tau);
    p[0] = (contact ? FM : FM * tau / (2.0 * ZETA)) + creal(e);
    p[1] = (contact ? 0.0 : FM / (2.0 * ZETA)) + creal(I * om * e);
}

/* The state at tau from s0 at tau0 on one piece (Eq. R5, R6). */
static void propagate(int contact, double om, const double s0[2], double tau0, double tau,
                      double s[2])
{
    double p0[2], p[2], h = tau - tau0, f[4];
    particular(contact, om, tau0, p0);
    particular(contact, om, tau, p);
    if (contact) {
        double wd = sqrt(1.0 - ZETA * ZETA), e = exp(-ZETA * h), c = cos(wd * h), sn = sin(wd * h);
        f[0] = e * (c + ZETA / wd * sn), f[1] = e * sn / wd;
        f[2] = -e * sn / wd, f[3] = e * (c - ZETA / wd * sn);
    } else {
        double e = exp(-2.0 * ZETA * h);
        f[0] = 1.0, f[1] = (1.0 - e) / (2.0 * ZETA), f[2] = 0.0, f[3] = e;
    }
    double d0 = s0[0] - p0[0], d1 = s0[1] - p0[1];
    s[0] = f[0] * d0 + f[1] * d1 + p[0];
    s[1] = f[2] * d0 + f[3] * d1 + p[1];
}

/* An orbit: separation at ts with speed vs, flight fraction frac of the period. */
typedef struct orbit {
    double ts, om, frac, vs, sc[2]; /* sc: the state at the re-contact */
} orbit;

/* Eq. R7-R9: the flight from (0, vs) at ts returns to y = 0 at tc = ts + frac T (which
 * fixes vs, the flight being linear in it); the contact from tc must end at (0, vs). */
static void residual(orbit *o, double g[2])
{
    double T = 2.0 * M_PI / o->om, tc = o->ts + o->frac * T, s0[2] = {0.0, 0.0}, a[2], b[2];
    propagate(0, o->om, s0, o->ts, tc, a);
    s0[1] = 1.0;
    propagate(0, o->om, s0, o->ts, tc, b);
    o->vs = -a[0] / (b[0] - a[0]);
    s0[1] = o->vs;
    propagate(0, o->om, s0, o->ts, tc, o->sc);
    double e[2];
    propagate(1, o->om, o->sc, tc, o->ts + T, e);
    g[0] = e[0], g[1] = e[1] - o->vs;
}

/* y, y' of the orbit at any tau (the period folded onto [ts, ts + T)). */
static void orbit_state(const orbit *o, double tau, double s[2])
{
    double T = 2.0 * M_PI / o->om, tc = o->ts + o->frac * T;
    double t = o->ts + fmod(fmod(tau - o->ts, T) + T, T), s0[2] = {0.0, o->vs};
    if (t < tc)
        propagate(0, o->om, s0, o->ts, t, s);
    else
        propagate(1, o->om, o->sc, tc, t, s);
}

/* Unknown k of (ts, om, frac). */
static double *var(orbit *o, int k)
{
    return k == 0 ? &o->ts : k == 1 ? &o->om : &o->frac;
}

/* dG/du_k by central differences. */
static void column(const orbit *o, int k, double col[2])
{
    orbit a = *o, b = *o;
    double h = 1e-7 * fmax(1.0, fabs(*var(&a, k))), ga[2], gb[2];
    *var(&a, k) += h;
    *var(&b, k) -= h;
    residual(&a, ga);
    residual(&b, gb);
    col[0] = (ga[0] - gb[0]) / (2 * h), col[1] = (ga[1] - gb[1]) / (2 * h);
}

/* Newton on two of the unknowns (i, j), the third held. Returns 1 when |G| < 1e-13. */
static int newton2(orbit *o, int i, int j)
{
    for (int it = 0; it < 40; it++) {
        double g[2], a[2], b[2];
        residual(o, g);
        if (hypot(g[0], g[1]) < 1e-13) return o->frac > 0.0 && o->frac < 1.0;
        column(o, i, a);
        column(o, j, b);
        double det = a[0] * b[1] - b[0] * a[1];
        if (det == 0.0) return 0;
        double di = -(g[0] * b[1] - b[0] * g[1]) / det, dj = -(a[0] * g[1] - g[0] * a[1]) / det;
        double lim = fmax(fabs(di), fabs(dj)) > 0.05 ? 0.05 / fmax(fabs(di), fabs(dj)) : 1.0;
        *var(o, i) += lim * di;
        *var(o, j) += lim * dj;
    }
    return 0;
}

/* The linear (no-impact) response x = 1 + F_m + F_a Re(H e^{i Omega tau}) (Eq. R1) holds
 * while F_a |H| <= F_m; it grazes at (Eq. R2) Omega^2 = 1 - 2 zeta^2 -+ sqrt(...). */
static double grazing(int upper)
{
    double r = FA / FM, a = 1.0 - 2.0 * ZETA * ZETA;
    return sqrt(a + (upper ? 1 : -1) * sqrt(a * a - 1.0 + r * r));
}

static double linear_y(double om, double tau)
{
    double p[2];
    particular(1, om, tau, p);
    return p[0];
}

/* The closed-form branch from the lower grazing point to the upper one. */
typedef struct branch {
    int n;
    orbit *o;
    double fold[2];   /* the folds: Omega's local maximum, then its minimum (Eq. R12) */
    int fold_node[2]; /* the node after each fold */
} branch;

/* Omega at flight fraction frac (Newton in ts, om from o). */
static double om_at_frac(orbit *o, double frac)
{
    o->frac = frac;
    return newton2(o, 0, 1) ? o->om : NAN;
}

/* The extremum of Omega(frac) over [a, b] (golden section; sgn +1 max, -1 min). */
static double extremum(orbit o, double a, double b, int sgn)
{
    const double r = 0.5 * (sqrt(5.0) - 1.0);
    double x1 = b - r * (b - a), x2 = a + r * (b - a);
    double f1 = sgn * om_at_frac(&o, x1), f2 = sgn * om_at_frac(&o, x2);
    while (b - a > 1e-10) {
        if (f1 > f2)
            b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = sgn * om_at_frac(&o, x1);
        else
            a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = sgn * om_at_frac(&o, x2);
    }
    return sgn * fmax(f1, f2);
}

/* Pseudo-arclength in (ts, om, frac): the tangent is the cross product of G's two
 * gradients (its om component is det dG/d(ts, frac), zero at a fold). */
static int trace(branch *br)
{
    memset(br, 0, sizeof *br);
    int cap = 4000;
    br->o = malloc(cap * sizeof *br->o);
    if (!br->o) return 0;
    orbit o;
    o.om = grazing(0);
    double complex h = 1.0 / (1.0 - o.om * o.om + 2.0 * I * ZETA * o.om);
    o.ts = (M_PI - carg(h)) / o.om - 0.005 * 2.0 * M_PI / o.om; /* at the linear minimum */
    o.frac = 0.01;
    if (!newton2(&o, 0, 1)) return 0;
    double tprev[3] = {0.0, 0.0, 1.0}, ds = 0.004;
    int nfold = 0;
    br->o[br->n++] = o;
    while (br->n < cap) {
        double c[3][2], t[3];
        for (int k = 0; k < 3; k++)
            column(&o, k, c[k]);
        t[0] = c[1][0] * c[2][1] - c[2][0] * c[1][1];
        t[1] = c[2][0] * c[0][1] - c[0][0] * c[2][1];
        t[2] = c[0][0] * c[1][1] - c[1][0] * c[0][1];
        double nt = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
        double sg = (t[0] * tprev[0] + t[1] * tprev[1] + t[2] * tprev[2]) < 0 ? -1.0 : 1.0;
        for (int k = 0; k < 3; k++)
            t[k] *= sg / nt;
        if (br->n > 1 && t[1] * tprev[1] < 0.0 && nfold < 2) { /* a fold between two nodes */
            orbit a = br->o[br->n - 2];
            double f0 = br->o[br->n - 2].frac, f1 = o.frac;
            br->fold[nfold] = extremum(a, fmin(f0, f1), fmax(f0, f1), tprev[1] > 0 ? 1 : -1);
            br->fold_node[nfold++] = br->n - 1;
        }
        memcpy(tprev, t, sizeof t);
        orbit p = o;
        for (int k = 0; k < 3; k++)
            *var(&p, k) += ds * t[k];
        int ok = 0;
        for (int it = 0; it < 30 && !ok; it++) { /* corrector on the hyperplane normal to t */
            double g[2], a[3][2], r[3], m[3][3];
            residual(&p, g);
            double hp = 0.0;
            for (int k = 0; k < 3; k++)
                hp += t[k] * (*var(&p, k) - *var(&o, k));
            if (hypot(g[0], g[1]) < 1e-13 && fabs(hp - ds) < 1e-13) ok = 1;
            for (int k = 0; k < 3; k++)
                column(&p, k, a[k]);
            for (int k = 0; k < 3; k++)
                m[0][k] = a[k][0], m[1][k] = a[k][1], m[2][k] = t[k];
            r[0] = -g[0], r[1] = -g[1], r[2] = ds - hp;
            double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
            for (int k = 0; k < 3 && !ok; k++) { /* Cramer */
                double q[3][3];
                memcpy(q, m, sizeof q);
                for (int i = 0; i < 3; i++)
                    q[i][k] = r[i];
                double dk = q[0][0] * (q[1][1] * q[2][2] - q[1][2] * q[2][1]) -
                            q[0][1] * (q[1][0] * q[2][2] - q[1][2] * q[2][0]) +
                            q[0][2] * (q[1][0] * q[2][1] - q[1][1] * q[2][0]);
                *var(&p, k) += dk / det;
            }
        }
        if (!ok) return 0;
        o = p;
        residual(&o, (double[2]){0});
        if (o.frac < 0.01) break; /* back at grazing, the upper one */
        br->o[br->n++] = o;
    }
    return nfold == 2;
}

/* Segment of node i: 0 from the lower grazing to the first fold (stable), 1 between the
 * folds (unstable), 2 from the second fold to the upper grazing (stable). */
static int segment(const branch *br, int i)
{
    return i < br->fold_node[0] ? 0 : i < br->fold_node[1] ? 1 : 2;
}

/* The orbit of segment seg at om (Newton in ts, frac from the nearest node). */
static int orbit_at(const branch *br, int seg, double om, orbit *out)
{
    for (int i = 0; i + 1 < br->n; i++) {
        const orbit *a = &br->o[i], *b = &br->o[i + 1];
        if (segment(br, i) != seg || (a->om - om) * (b->om - om) > 0.0) continue;
        *out = fabs(a->om - om) < fabs(b->om - om) ? *a : *b;
        out->om = om;
        return newton2(out, 0, 2);
    }
    return 0;
}

/* Sampled peak-to-peak, mean and first harmonic amplitude of d = b (1 + y) at the
 * record's n samples t_j = j T / n (as geardyn samples its records). */
static void sampled(const orbit *o, int linear, double om, int n, double st[3])
{
    double lo = INFINITY, hi = -INFINITY, sum = 0.0;
    double complex a1 = 0.0;
    for (int j = 0; j < n; j++) {
        double tau = j * 2.0 * M_PI / (om * n), s[2];
        if (linear)
            s[0] = linear_y(om, tau);
        else
            orbit_state(o, tau, s);
        double d = GAP * (1.0 + s[0]);
        lo = fmin(lo, d), hi = fmax(hi, d), sum += d;
        a1 += d * cexp(-2.0 * M_PI * I * j / n);
    }
    st[0] = hi - lo, st[1] = sum / n, st[2] = 2.0 * cabs(a1) / n;
}

/* The true peak-to-peak (x): the extremes where y' = 0, by bisection between samples. */
static double true_p2p(const orbit *o)
{
    double T = 2.0 * M_PI / o->om, lo = INFINITY, hi = -INFINITY, prev[2], s[2];
    const int n = 2000;
    orbit_state(o, o->ts, prev);
    for (int j = 1; j <= n; j++) {
        double t1 = o->ts + j * T / n;
        orbit_state(o, t1, s);
        if (prev[1] * s[1] <= 0.0) {
            double a = t1 - T / n, b = t1, sa = prev[1], m[2];
            for (int it = 0; it < 60; it++) {
                orbit_state(o, 0.5 * (a + b), m);
                if ((m[1] <= 0.0) == (sa <= 0.0))
                    a = 0.5 * (a + b), sa = m[1];
                else
                    b = 0.5 * (a + b);
            }
            orbit_state(o, 0.5 * (a + b), m);
            lo = fmin(lo, m[0]), hi = fmax(hi, m[0]);
        }
        memcpy(prev, s, sizeof s);
    }
    return hi - lo;
}

/* No flank is left beyond the flight and the contact (Eq. R10, R11): y < 0 apart (and
 * above -2: the coast flank never reached), y > 0 in contact. */
static int orbit_valid(const orbit *o)
{
    double T = 2.0 * M_PI / o->om, s[2];
    for (int j = 1; j < 400; j++) {
        double t = o->ts + j * T / 400;
        orbit_state(o, t, s);
        int apart = t < o->ts + o->frac * T;
        if (apart ? (s[0] > 1e-12 || s[0] < -2.0) : s[0] < -1e-12) return 0;
    }
    return o->vs < 0.0 && o->sc[1] > 0.0;
}

TEST(closed_form_branch_and_folds)
{
    branch br;
    REQUIRE(trace(&br));
    printf("  closed form: %d nodes, grazing %.9f, %.9f, folds %.9f (max), %.9f (min)\n", br.n,
           grazing(0), grazing(1), br.fold[0], br.fold[1]);
    /* the folds lie where the branch says: the first above the lower grazing, the
     * second below it; every node a valid single-sided impact orbit */
    CHECK(br.fold[0] > grazing(0) && br.fold[1] < grazing(0));
    int bad = 0;
    for (int i = 0; i < br.n; i += 10)
        bad += !orbit_valid(&br.o[i]);
    CHECK(bad == 0);
    /* at grazing the impact orbit's peak-to-peak joins the linear one's, 2 F_a |H| = 2 F_m */
    CHECK_REL(true_p2p(&br.o[0]), 2.0 * FM, 2e-3);
    CHECK_REL(true_p2p(&br.o[br.n - 1]), 2.0 * FM, 2e-3);
    /* an orbit solved at a fixed Omega has a zero residual and is periodic */
    orbit o;
    REQUIRE(orbit_at(&br, 2, 0.85, &o));
    double s0[2], s1[2];
    orbit_state(&o, 0.3, s0);
    orbit_state(&o, 0.3 + 2.0 * M_PI / 0.85, s1);
    CHECK_ABS(s1[0], s0[0], 1e-12);
    CHECK_ABS(s1[1], s0[1], 1e-12);
    free(br.o);
}

/* Requested load frequencies (rad/s): a 250 rad/s grid and 9080 between the lower
 * grazing (9064.9) and the first fold (9093.3). */
static int values(double *v)
{
    int n = 0;
    for (double w = 7500; w <= 11000; w += 250) {
        v[n++] = w;
        if (w == 9000) v[n++] = 9080;
    }
    return n;
}

/* geardyn's point against the nearest closed-form orbit at its frequency (segments 0..2
 * of the branch, or the linear response -1 where it is valid); returns the relative
 * error of the peak-to-peak and sets the segment. */
static double compare(const branch *br, const gd_periodic_point *p, int n, int *seg,
                      double st_out[3], double *p2p_true)
{
    double om = p->parameter / WN, best = INFINITY;
    *seg = -2;
    for (int s = -1; s < 3; s++) {
        orbit o;
        double st[3];
        if (s < 0) {
            double complex h = 1.0 / (1.0 - om * om + 2.0 * I * ZETA * om);
            if (FA * cabs(h) > FM) continue;
            sampled(NULL, 1, om, n, st);
        } else {
            if (!orbit_at(br, s, om, &o) || !orbit_valid(&o)) continue;
            sampled(&o, 0, om, n, st);
        }
        double e = fabs(p->records[0].peak_to_peak - st[0]) / st[0];
        if (e < best) {
            best = e, *seg = s;
            memcpy(st_out, st, sizeof st);
            *p2p_true =
                s < 0 ? 2.0 * FA * cabs(1.0 / (1.0 - om * om + 2.0 * I * ZETA * om)) : true_p2p(&o);
        }
    }
    return best;
}

/* The closed-form branch and the example; both freed by the caller (or here on failure). */
static int setup(branch *br, fx *f)
{
    if (!trace(br)) {
        free(br->o);
        return 0;
    }
    if (load(f, GD_SOURCE_DIR "/examples/impact_oscillator.yaml", NULL)) return 1;
    free(br->o);
    return 0;
}

static gd_periodic_result *run(const fx *f, gd_per_kind kind, const double *v, int nv, int H)
{
    gd_transient_model *tm = NULL;
    gd_error err;
    gd_periodic_result *r = NULL;
    if (gd_transient_model_build(f->s, &tm, &err)) return NULL;
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = kind;
    o.harmonics = H;
    o.estimate = kind == GD_PER_HB;
    o.shoot_rtol = 1e-10;
    gd_periodic_param prm = {.name = "load frequency", .speed = 0.0, .load_frequency = 1};
    gd_tr_record rec = {GD_REC_MESH_DEFLECTION, 0, 0};
    if (gd_periodic_run(f->s, &tm->spec, &prm, v, nv, &o, &rec, 1, &r, &err))
        fprintf(stderr, "  %s\n", err.message);
    gd_transient_model_free(tm);
    return r;
}

TEST(shooting_equals_closed_form_and_jumps_at_its_folds)
{
    branch br;
    fx f;
    REQUIRE(setup(&br, &f));
    double v[32];
    int nv = values(v);
    gd_periodic_result *r = run(&f, GD_PER_SHOOTING, v, nv, 10);
    REQUIRE(r);
    const char *curve = getenv("GD_IMPACT_CURVE");
    FILE *out = curve && *curve ? fopen(curve, "w") : NULL;
    double worst[3] = {0, 0, 0};
    int nseg[4] = {0, 0, 0, 0}, wrong_stability = 0, unmatched = 0;
    for (int k = 0; k < r->npoints; k++) {
        const gd_periodic_point *p = &r->points[k];
        if (!p->converged) {
            unmatched++;
            continue;
        }
        int seg;
        double st[3], p2p;
        /* the records' samples: 256 per period at H = 10 (docs/periodic.md) */
        double e = compare(&br, p, 256, &seg, st, &p2p);
        if (seg < -1) {
            unmatched++;
            continue;
        }
        nseg[seg + 1]++;
        worst[0] = fmax(worst[0], e);
        worst[1] = fmax(worst[1], fabs(p->records[0].mean - st[1]) / st[1]);
        worst[2] = fmax(worst[2], fabs(p->records[0].amplitude[1] - st[2]) / st[2]);
        /* stable on the linear response and segments 0 and 2, unstable between the folds */
        wrong_stability += p->stable != (seg == 1 ? 0 : 1);
        if (out)
            fprintf(out, "point %.10g %.10g %d %d\n", p->parameter / WN,
                    p->records[0].peak_to_peak / GAP, seg, p->stable);
    }
    printf("  shooting: %d points (linear %d, branch segments %d %d %d), sampled p2p within "
           "%.1e, mean %.1e, 1st harmonic %.1e\n",
           r->npoints, nseg[0], nseg[1], nseg[2], nseg[3], worst[0], worst[1], worst[2]);
    CHECK(unmatched == 0 && wrong_stability == 0);
    CHECK(nseg[0] >= 8 && nseg[1] >= 1 && nseg[2] >= 4 && nseg[3] >= 8);
    /* shooting at rtol 1e-10 (Newton to a scaled residual of 1e-8): 1e-6 */
    CHECK(worst[0] < 1e-6 && worst[1] < 1e-6 && worst[2] < 1e-6);
    /* the jump frequencies: sweeping up the response leaves the lower branch at the
     * first fold (not at grazing: segment 0 is stable), sweeping down the upper one at
     * the second. Shooting locates a fold to 1e-8 in lambda (measured 9e-10, 1.5e-8) */
    int nf = 0;
    for (int b = 0; b < r->nbifurcations; b++) {
        const gd_bifurcation *bf = &r->bifurcations[b];
        if (bf->type != GD_BIF_FOLD) continue;
        double ref = br.fold[nf < 2 ? nf : 1];
        printf("  fold %.9f against the closed form %.9f (%.1e)\n", bf->parameter / WN, ref,
               fabs(bf->parameter / WN - ref) / ref);
        CHECK_REL(bf->parameter / WN, ref, 1e-7);
        nf++;
    }
    CHECK(nf == 2);
    if (out) {
        for (int i = 0; i < br.n; i++)
            fprintf(out, "branch %.10g %.10g %d\n", br.o[i].om, true_p2p(&br.o[i]),
                    segment(&br, i));
        fprintf(out, "grazing %.10g %.10g\nfold %.10g %.10g\n", grazing(0), grazing(1), br.fold[0],
                br.fold[1]);
        for (int b = 0; b < r->nbifurcations; b++)
            fprintf(out, "gdfold %.10g\n", r->bifurcations[b].parameter / WN);
        fclose(out);
    }
    gd_periodic_result_free(r);
    fx_free(&f);
    free(br.o);
}

/* Harmonic balance on the same branch: its error against the closed form (sampled as its
 * records are) within its own truncation estimate (the change from H to 2 H). */
TEST(harmonic_balance_within_its_estimate)
{
    branch br;
    fx f;
    REQUIRE(setup(&br, &f));
    const double v[4] = {8000, 8500, 9500, 10500};
    /* the default method (auto) takes shooting for a backlash law: the test above */
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.kind = GD_PER_AUTO;
    gd_periodic_param prm = {.name = "load frequency", .speed = 0.0, .load_frequency = 1};
    CHECK(gd_periodic_choose(f.s, &tm->spec, &prm, v[0], &o, NULL) == GD_PER_SHOOTING);
    gd_transient_model_free(tm);
    gd_periodic_result *r = run(&f, GD_PER_HB, v, 4, 20);
    REQUIRE(r);
    int n = 0, within = 0;
    double worst = 0.0, worst_est = 0.0;
    for (int k = 0; k < r->npoints; k++) {
        const gd_periodic_point *p = &r->points[k];
        int seg;
        double st[3], p2p;
        if (!p->converged) continue;
        double e = compare(&br, p, 256, &seg, st, &p2p);
        printf("  HB H = 20 at %.0f rad/s (segment %d): p2p error %.2e, estimate %.2e\n",
               p->parameter, seg, e, p->harmonic_error_p2p);
        n++;
        within += seg >= -1 && e <= 2.0 * p->harmonic_error_p2p + 1e-9;
        worst = fmax(worst, e), worst_est = fmax(worst_est, p->harmonic_error_p2p);
    }
    printf("  HB: %d points, largest error %.2e, largest estimate %.2e\n", n, worst, worst_est);
    CHECK(n >= 8 && within == n);
    gd_periodic_result_free(r);
    fx_free(&f);
    free(br.o);
}

/* A stepped sweep in transient: at each load frequency the run goes on from the previous
 * one's end state (the load's phase w t continued, as `transient --sweep-speeds` does),
 * in chunks of 20 periods until the peak-to-peak of the last period settles to 1e-4 (at
 * most 300 periods). Returns the first frequency whose peak-to-peak (in b) is on the other
 * side of level than at the start, or NAN. */
static double sweep(const fx *f, gd_transient_model *tm, const orbit *start, int linear, double w0,
                    double w1, double dw, double level, int *periods)
{
    gd_error err;
    int above = 0;
    double n_ = 1.0, t = 0.0, q[2] = {0.0, 0.0}, v[2] = {0.0, 0.0}, found = NAN, wprev = w0;
    gd_tr_record rec = {GD_REC_MESH_DEFLECTION, 0, 0};
    int steps = (int)lround((w1 - w0) / dw), gear = dof(f, "gear", GD_RZ);
    *periods = 0;
    for (int i = 0; i <= steps && isnan(found); i++) {
        double w = w0 + i * dw, T = 2.0 * M_PI / w, prev = NAN, p2p = NAN;
        tm->loads[0].law.frequency = w;
        gd_transient *tr = NULL;
        if (gd_transient_new(f->s, &tm->spec, 0.0, &tr, &err)) return NAN;
        if (i == 0) { /* the closed-form orbit at t = 0; d = n_ q_gear (n_ from the mesh) */
            double y[2] = {1.0, 0.0}, s[2];
            n_ = gd_transient_record_value(tr, &rec, 0.0, y);
            if (linear)
                particular(1, w / WN, 0.0, s);
            else
                orbit_state(start, 0.0, s);
            q[gear] = GAP * (1.0 + s[0]) / n_, v[gear] = GAP * WN * s[1] / n_;
        } else
            t *= wprev / w; /* the load's phase goes on */
        for (int chunk = 0; chunk < 15; chunk++) {
            gd_transient_options o;
            gd_transient_options_init(&o);
            o.t_start = t, o.t_end = t + 20 * T, o.record_from = o.t_end - T;
            o.output_interval = T / 256, o.rtol = 1e-8, o.init = GD_TR_INIT_GIVEN;
            o.q0 = q, o.v0 = v;
            gd_transient_result *r = NULL;
            if (gd_transient_run(tr, &o, &rec, 1, &r, &err)) {
                fprintf(stderr, "  %s\n", err.message);
                break;
            }
            memcpy(q, r->q_end, sizeof q);
            memcpy(v, r->v_end, sizeof v);
            t = o.t_end, p2p = r->stats[0].peak_to_peak, *periods += 20;
            gd_transient_result_free(r);
            if (fabs(p2p - prev) < 1e-4 * p2p) break;
            prev = p2p;
        }
        gd_transient_free(tr);
        if (i == 0) above = p2p > level * GAP;
        if (i > 0 && (p2p > level * GAP) != above) found = w;
        wprev = w;
    }
    return found;
}

TEST(transient_sweeps_jump_at_the_folds)
{
    branch br;
    fx f;
    REQUIRE(setup(&br, &f));
    gd_transient_model *tm = NULL;
    gd_error err;
    REQUIRE(gd_transient_model_build(f.s, &tm, &err) == GD_OK);
    orbit up;
    REQUIRE(orbit_at(&br, 2, 8010.0 / WN, &up));
    int n1, n2;
    /* up from the linear response at 9050: the lower branch (p2p 0.2 b) is left for the
     * upper one (0.37 b) at the first 10 rad/s step past the first fold */
    double jup = sweep(&f, tm, NULL, 1, 9050, 9130, 10, 0.3, &n1);
    /* down from the upper branch at 8010 (0.47 b) to the linear response (0.11 b) */
    double jdn = sweep(&f, tm, &up, 0, 8010, 7950, -10, 0.2, &n2);
    printf("  transient sweeps (10 rad/s steps): jump up at %.0f rad/s (fold %.2f), down at "
           "%.0f rad/s (fold %.2f); %d + %d periods integrated\n",
           jup, br.fold[0] * WN, jdn, br.fold[1] * WN, n1, n2);
    CHECK(jup >= br.fold[0] * WN && jup < br.fold[0] * WN + 10);
    CHECK(jdn <= br.fold[1] * WN && jdn > br.fold[1] * WN - 10);
    gd_transient_model_free(tm);
    fx_free(&f);
    free(br.o);
}

RUN_TESTS(T(closed_form_branch_and_folds), T(shooting_equals_closed_form_and_jumps_at_its_folds),
          T(harmonic_balance_within_its_estimate), T(transient_sweeps_jump_at_the_folds))
