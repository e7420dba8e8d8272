/* Unequally spaced planets ([LinParker2000], docs/planetary.md "Unequal spacing"): on
 * [LinParker1999]'s Table 1 set with identical planets at unequal angles,
 * - the planet modes survive any spacing: central members still, each planet moving in the
 *   single planet's own shape p times a weight c_n with sum c_n = 0 and
 *   sum c_n exp(i psi_n) = 0, at the equally spaced set's planet frequencies, N - 3 times;
 * - the other 18 modes mix rotation and translation of the central members
 *   (rotational-translational modes) and are simple;
 * - diametrically opposed planets keep the three classes: 6 rotational modes at the equally
 *   spaced set's rotational frequencies (all planets alike), 12 translational modes whose
 *   pairs split (each planet opposite its partner);
 * and, derived here from the same equations (not the paper's), the conditions behind the
 * last case: S1 = sum exp(i psi_n) = 0 gives pure rotational and translational classes,
 * S1 = S2 = sum exp(2 i psi_n) = 0 the equally spaced set's whole spectrum. The paper's text
 * was not available: docs/planetary.md ("Unequal spacing") says which statements are its. */
#include <complex.h>

#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "harness.h"

#define PI 3.14159265358979323846
#define NMAX 6
#define NDOF (9 + 3 * NMAX)

/* [LinParker1999]'s Table 1 set, examples/planetary_lin_parker.yaml, with N planets at the
 * given angles (NULL: equally spaced). */
static gd_model *lp_set(int N, const double *angles_deg)
{
    char count[64], ang[200] = "planetary_sets.lp.planets.angles=[";
    snprintf(count, sizeof count, "planetary_sets.lp.planets.count=%d", N);
    for (int n = 0; n < N && angles_deg; n++) {
        size_t k = strlen(ang);
        snprintf(ang + k, sizeof ang - k, "%s%.17g deg", n ? ", " : "", angles_deg[n]);
    }
    strcat(ang, "]");
    const char *sets[2] = {count, ang};
    gd_load_options opt;
    gd_load_options_init(&opt);
    opt.nset = angles_deg ? 2 : 1;
    opt.set = sets;
    gd_model *m = NULL;
    gd_error err;
    if (gd_model_load_opts("examples/planetary_lin_parker.yaml", &opt, &m, &err))
        fprintf(stderr, "  %s\n", err.message);
    return m;
}

/* A set's modes in [LinParker1999]'s coordinates, all lengths: the central members'
 * x, y, u = r theta (sun, ring, carrier: rows 0..8), each planet's zeta, eta, u (rows 9 + 3 n). */
typedef struct {
    int N, nmodes;
    double f[NDOF];       /* Hz, ascending */
    double q[NDOF][NDOF]; /* q[mode][coordinate] */
    gd_planetary_class cls[NDOF];
    double psi[NMAX];
} set_modes;

static int solve(int N, const double *angles_deg, set_modes *s)
{
    gd_model *m = lp_set(N, angles_deg);
    if (!m) return 0;
    gd_system *sys = NULL;
    gd_modal_result *r = NULL;
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    opt.kind = GD_MODAL_UNDAMPED;
    int ok = !gd_system_build(m, &sys, NULL) && !gd_modal_solve(sys, &opt, &r, NULL) &&
             r->nmodes == 9 + 3 * N;
    if (ok) {
        const gd_planetary *g = &m->planetary[0];
        const double rad[3] = {g->base_radius[0], g->base_radius[1], g->carrier_radius};
        s->N = N;
        s->nmodes = r->nmodes;
        for (int n = 0; n < N; n++)
            s->psi[n] = g->planet_angle[n];
        for (int k = 0; k < r->nmodes; k++) {
            const double *v = r->shape_re + (size_t)k * (size_t)r->ndof;
            s->f[k] = r->modes[k].frequency_hz;
            s->cls[k] = gd_modal_planetary_class(sys, r, k, 0);
            for (int j = 0; j < 3; j++) {
                int node = g->member[j].node;
                s->q[k][3 * j] = v[gd_system_dof(sys, node, GD_X)];
                s->q[k][3 * j + 1] = v[gd_system_dof(sys, node, GD_Y)];
                s->q[k][3 * j + 2] = rad[j] * v[gd_system_dof(sys, node, GD_RZ)];
            }
            for (int n = 0; n < N; n++) {
                int node = g->first_planet + n;
                double x = v[gd_system_dof(sys, node, GD_X)], y = v[gd_system_dof(sys, node, GD_Y)];
                double c = cos(s->psi[n]), sn = sin(s->psi[n]);
                s->q[k][9 + 3 * n] = x * c + y * sn;
                s->q[k][10 + 3 * n] = -x * sn + y * c;
                s->q[k][11 + 3 * n] = g->base_radius[2] * v[gd_system_dof(sys, node, GD_RZ)];
            }
        }
    }
    gd_modal_free(r);
    gd_system_free(sys);
    gd_model_free(m);
    return ok;
}

static double norm(const double *a, int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += a[i] * a[i];
    return sqrt(s);
}

/* The central members' translations and rotations in mode k, each relative to the set's
 * largest coordinate. */
static void central_parts(const set_modes *s, int k, double *translation, double *rotation)
{
    double big = 0, t = 0, r = 0;
    for (int i = 0; i < 9 + 3 * s->N; i++)
        big = fmax(big, fabs(s->q[k][i]));
    for (int j = 0; j < 3; j++) {
        t = fmax(t, fmax(fabs(s->q[k][3 * j]), fabs(s->q[k][3 * j + 1])));
        r = fmax(r, fabs(s->q[k][3 * j + 2]));
    }
    *translation = t / big;
    *rotation = r / big;
}

/* The frequencies of class c, ascending; returns their count. */
static int of_class(const set_modes *s, gd_planetary_class c, double *f)
{
    int n = 0;
    for (int k = 0; k < s->nmodes; k++)
        if (s->cls[k] == c) f[n++] = s->f[k];
    return n;
}

/* The smallest relative gap between consecutive frequencies above 1 Hz. */
static double smallest_gap(const double *f, int n)
{
    double gap = 1e30;
    for (int i = 1; i < n; i++)
        if (f[i - 1] > 1) gap = fmin(gap, (f[i] - f[i - 1]) / f[i]);
    return gap;
}

static const double GENERIC4[4] = {0, 80, 170, 265}, GENERIC5[5] = {0, 60, 150, 220, 290},
                    GENERIC6[6] = {0, 45, 110, 200, 250, 300};
static const double *const GENERIC[3] = {GENERIC4, GENERIC5, GENERIC6};

/* Planet modes at any spacing: central members still, every planet in one shape p (its
 * local zeta, eta, u) times c_n, sum c_n = 0 = sum c_n exp(i psi_n), at the equally spaced
 * set's planet frequencies (their sensitivity to the spacing is zero), N - 3 times each. */
TEST(planet_modes_at_any_spacing)
{
    for (int N = 4; N <= NMAX; N++) {
        set_modes *eq = calloc(2, sizeof *eq), *s = eq + 1;
        REQUIRE(eq);
        REQUIRE(solve(N, NULL, eq) && solve(N, GENERIC[N - 4], s));
        double fp[NDOF], fe[NDOF];
        CHECK(of_class(eq, GD_PCLASS_PLANET, fe) == 3 * (N - 3));
        CHECK(of_class(s, GD_PCLASS_PLANET, fp) == 3 * (N - 3));
        for (int i = 0; i < 3 * (N - 3); i++)
            CHECK_REL(fp[i], fe[i], 1e-9);
        double worst_shape = 0, worst_sum = 0, worst_still = 0;
        for (int k = 0; k < s->nmodes; k++) {
            if (s->cls[k] != GD_PCLASS_PLANET) continue;
            const double *q = s->q[k];
            /* p: the planet with the largest motion; c_n = v_n . p / |p|^2 */
            int big = 0;
            for (int n = 1; n < N; n++)
                if (norm(q + 9 + 3 * n, 3) > norm(q + 9 + 3 * big, 3)) big = n;
            const double *p = q + 9 + 3 * big;
            double pp = norm(p, 3) * norm(p, 3), c[NMAX], sum = 0;
            double complex sum1 = 0;
            for (int n = 0; n < N; n++) {
                const double *v = q + 9 + 3 * n;
                c[n] = (v[0] * p[0] + v[1] * p[1] + v[2] * p[2]) / pp;
                double res[3] = {v[0] - c[n] * p[0], v[1] - c[n] * p[1], v[2] - c[n] * p[2]};
                worst_shape = fmax(worst_shape, norm(res, 3) / sqrt(pp));
                sum += c[n];
                sum1 += c[n] * cexp(I * s->psi[n]);
            }
            worst_sum = fmax(worst_sum, fmax(fabs(sum), cabs(sum1)));
            worst_still = fmax(worst_still, norm(q, 9) / sqrt(pp));
        }
        printf("  N = %d: planet shapes off one p by %.1e, |sum c|, |sum c e^(i psi)| <= %.1e, "
               "central members %.1e\n",
               N, worst_shape, worst_sum, worst_still);
        CHECK(worst_shape < 1e-8 && worst_sum < 1e-8 && worst_still < 1e-8);
        free(eq);
    }
}

/* The other 18 modes (3 (N + 3) - 3 (N - 3)): the central members both rotate and
 * translate (class mixed; the rigid rotation of the set alone stays rotational), each
 * frequency simple, and they move with the spacing. */
TEST(rotational_translational_modes_mix)
{
    for (int N = 4; N <= NMAX; N++) {
        set_modes *eq = calloc(2, sizeof *eq), *s = eq + 1;
        REQUIRE(eq);
        REQUIRE(solve(N, NULL, eq) && solve(N, GENERIC[N - 4], s));
        double f[NDOF], least = 1;
        int mixed = of_class(s, GD_PCLASS_MIXED, f);
        CHECK(mixed == 17);
        CHECK(of_class(s, GD_PCLASS_ROTATIONAL, f) == 1 && f[0] < 1e-3);
        for (int k = 0; k < s->nmodes; k++)
            if (s->cls[k] == GD_PCLASS_MIXED) {
                double t, r;
                central_parts(s, k, &t, &r);
                least = fmin(least, fmin(t, r));
            }
        of_class(s, GD_PCLASS_MIXED, f);
        double gap = smallest_gap(f, mixed);
        /* the lowest elastic mode against the equal set's translational pair (727 Hz for
           N = 4) */
        double move = fabs(f[0] / eq->f[1] - 1);
        printf("  N = %d: 17 mixed modes, smallest central rotation or translation %.2e, "
               "smallest gap %.2e, lowest %.2f Hz (equal spacing %.2f Hz)\n",
               N, least, gap, f[0], eq->f[1]);
        CHECK(least > 1e-4 && gap > 1e-4 && move > 1e-3);
        free(eq);
    }
}

/* Spacings with S1 = sum exp(i psi_n) = 0, diametrically opposed planets among them: 6
 * rotational modes at the equally spaced set's rotational frequencies with all planets alike,
 * 12 translational modes (pairs split unless S2 = 0 too), 3 (N - 3) planet modes; none mixed.
 * Diametrically opposed pairs: each planet's motion is its partner's in the rotational
 * modes and its negative in the translational ones. */
typedef struct {
    int N;
    double angles[NMAX];
    int diametric; /* planet n + N/2 opposite planet n */
    int s2_zero;   /* sum exp(2 i psi_n) = 0 too */
} zero_sum_case;

static const zero_sum_case ZERO_SUM[] = {
    {4, {0, 80, 180, 260}, 1, 0},
    {6, {0, 50, 130, 180, 230, 310}, 1, 0},
    {5, {0, 90, 180, 210, 330}, 0, 0},      /* derived here: S1 = 0, not opposed */
    {6, {0, 40, 120, 160, 240, 280}, 0, 1}, /* derived here: two triangles, S1 = S2 = 0 */
};

TEST(zero_sum_spacing_keeps_the_classes)
{
    for (size_t v = 0; v < sizeof ZERO_SUM / sizeof ZERO_SUM[0]; v++) {
        const zero_sum_case *z = &ZERO_SUM[v];
        int N = z->N;
        set_modes *eq = calloc(2, sizeof *eq), *s = eq + 1;
        REQUIRE(eq);
        REQUIRE(solve(N, NULL, eq) && solve(N, z->angles, s));
        double fr[NDOF], fe[NDOF], ft[NDOF], fte[NDOF];
        CHECK(of_class(s, GD_PCLASS_ROTATIONAL, fr) == 6);
        CHECK(of_class(eq, GD_PCLASS_ROTATIONAL, fe) == 6);
        for (int i = 1; i < 6; i++)
            CHECK_REL(fr[i], fe[i], 1e-9);
        CHECK(of_class(s, GD_PCLASS_TRANSLATIONAL, ft) == 12);
        CHECK(of_class(eq, GD_PCLASS_TRANSLATIONAL, fte) == 12);
        CHECK(of_class(s, GD_PCLASS_PLANET, fe) == 3 * (N - 3));
        CHECK(of_class(s, GD_PCLASS_MIXED, fe) == 0);
        double gap = smallest_gap(ft, 12), worst_pair = 0, worst_spectrum = 0;
        if (z->s2_zero) {
            /* the equally spaced set's whole spectrum, translational pairs included */
            for (int k = 0; k < s->nmodes; k++)
                if (eq->f[k] > 1)
                    worst_spectrum = fmax(worst_spectrum, fabs(s->f[k] / eq->f[k] - 1));
            CHECK(worst_spectrum < 1e-9);
        } else {
            CHECK(gap > 1e-3); /* the pairs split */
        }
        for (int k = 0; k < s->nmodes && z->diametric; k++) {
            int sign = s->cls[k] == GD_PCLASS_ROTATIONAL      ? 1
                       : s->cls[k] == GD_PCLASS_TRANSLATIONAL ? -1
                                                              : 0;
            if (!sign) continue;
            double big = norm(s->q[k], 9 + 3 * N);
            for (int n = 0; n < N / 2; n++)
                for (int i = 0; i < 3; i++)
                    worst_pair = fmax(worst_pair, fabs(s->q[k][9 + 3 * (n + N / 2) + i] -
                                                       sign * s->q[k][9 + 3 * n + i]) /
                                                      big);
        }
        printf("  N = %d at", N);
        for (int n = 0; n < N; n++)
            printf(" %g", z->angles[n]);
        printf(": translational %.2f %.2f Hz (equal spacing %.2f twice), smallest gap %.2e, "
               "pairs %.1e, spectrum %.1e\n",
               ft[0], ft[1], fte[0], gap, worst_pair, worst_spectrum);
        CHECK(worst_pair < 1e-9);
        free(eq);
    }
}

RUN_TESTS(T(planet_modes_at_any_spacing), T(rotational_translational_modes_mix),
          T(zero_sum_spacing_keeps_the_classes))
