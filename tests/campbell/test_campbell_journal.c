/* Oil whirl from campbell: a rigid symmetric rotor on two short journal bearings
 * (examples/journal_rotor.yaml) becomes unstable where the forward mode near half the
 * speed loses its damping. The reference is the short-bearing stability curve: the
 * closed-form coefficients (Friswell et al. 2010 Sec. 5.5.2, Childs 1993 ch. 3) in
 * Lund's critical-mass criterion for a rigid rotor (Lund, "Self-excited, stationary
 * whirl orbits of a journal in a sleeve bearing", 1966): with a = K c / W, b = C c w / W,
 *   K_eq = (a_xx b_yy + a_yy b_xx - a_xy b_yx - a_yx b_xy) / (b_xx + b_yy),
 *   g^2  = [(K_eq - a_xx)(K_eq - a_yy) - a_xy a_yx] / (b_xx b_yy - b_xy b_yx),
 * the whirl frequency ratio g, and the rotor of mass m = W / g_n per bearing is unstable
 * above w_th sqrt(c / g_n) = sqrt(K_eq) / g. The curve's published landmarks: g -> 1/2
 * as eps -> 0 (half-speed whirl), and the short bearing stable at every speed above
 * eps = 0.756 where g^2 vanishes. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/campbell.h"
#include "harness.h"
#include "model_support.h"
#include "short_bearing_reference.h"

static const double MU = 0.02, RAD = 0.025, LEN = 0.01, CL = 50e-6, GN = 9.81, MASS = 20;

/* Lund: the squared whirl ratio g^2 and the threshold w_th sqrt(c / g_n) at eps e. */
static double threshold(double e, double *g2)
{
    double a[4], b[4];
    short_bearing_coefficients(e, a, b);
    double keq = (a[0] * b[3] + a[3] * b[0] - a[1] * b[2] - a[2] * b[1]) / (b[0] + b[3]);
    *g2 = ((keq - a[0]) * (keq - a[3]) - a[1] * a[2]) / (b[0] * b[3] - b[1] * b[2]);
    return *g2 > 0 ? sqrt(keq / *g2) : INFINITY;
}

/* The speed at which the film carries W at eps (Ocvirk), for viscosity mu. */
static double speed_at(double e, double mu)
{
    double s2 = 1 - e * e;
    double cap = mu * RAD * pow(LEN, 3) / (4 * CL * CL) * e * sqrt(M_PI * M_PI * s2 + 16 * e * e) /
                 (s2 * s2);
    return MASS * GN / cap;
}

static double *linspace(double a, double b, int n)
{
    double *v = malloc((size_t)n * sizeof *v);
    for (int i = 0; i < n; i++)
        v[i] = a + (b - a) * i / (n - 1);
    return v;
}

/* The curve's landmarks, from the closed forms themselves. */
TEST(short_bearing_stability_curve)
{
    double g2;
    threshold(0.01, &g2);
    CHECK_ABS(sqrt(g2), 0.5, 1e-3); /* half-speed whirl of a lightly loaded bearing */
    double lo = 0.7, hi = 0.8;      /* where g^2 vanishes */
    for (int i = 0; i < 60; i++) {
        double mid = 0.5 * (lo + hi);
        threshold(mid, &g2);
        if (g2 > 0)
            lo = mid;
        else
            hi = mid;
    }
    printf("  stable at every speed above eps %.4f\n", lo);
    CHECK_ABS(lo, 0.756, 1e-3);
}

/* The onset from campbell on a 5 rad/s grid, interpolated, against the curve: the
 * speed where w^2 c / g_n = threshold(eps(w))^2 along the rotor's own eps(w). The grid
 * and the linear interpolation of the damping between speeds allow 0.1 %; the whirl
 * frequency there (interpolated alike) against g to 1e-4. */
TEST(oil_whirl_onset_against_stability_curve)
{
    /* eps of the onset: threshold(eps) sqrt(g_n / c) = speed_at(eps), by bisection */
    double lo = 0.1, hi = 0.75, g2;
    for (int i = 0; i < 80; i++) {
        double mid = 0.5 * (lo + hi);
        double d = threshold(mid, &g2) * sqrt(GN / CL) - speed_at(mid, MU);
        /* at small eps the rotor runs fast (above the threshold): d < 0 */
        if (d < 0)
            lo = mid;
        else
            hi = mid;
    }
    double eps = 0.5 * (lo + hi), w_ref = speed_at(eps, MU);
    threshold(eps, &g2);

    fx f;
    REQUIRE(load(&f, "examples/journal_rotor.yaml", NULL));
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.nspeeds = 61;
    double *sp = linspace(1000, 1300, o.nspeeds);
    o.speeds = sp;
    o.nmodes = 0;
    o.shaft_orders = 0;
    gd_campbell_result *r = NULL;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->instability_track >= 0);
    double w = r->instability_onset;
    printf("  onset %.3f rad/s (eps %.4f), curve %.3f rad/s: rel err %.2g\n", w, eps, w_ref,
           fabs(w - w_ref) / w_ref);
    CHECK_REL(w, w_ref, 1e-3);
    /* the unstable mode whirls forward at g times the speed near the onset */
    int t = 0, s = (int)((w - 1000) / 5.0);
    while (t < r->ntracks && r->tracks[t].id != r->instability_track)
        t++;
    REQUIRE(t < r->ntracks);
    const gd_mode *m = &r->modes[t * r->nspeeds + s], *m1 = m + 1;
    double u = (w - sp[s]) / (sp[s + 1] - sp[s]);
    double ratio = (1 - u) * m->omega_d / sp[s] + u * m1->omega_d / sp[s + 1];
    printf("  whirl %.4f x speed (curve %.4f), %s\n", ratio, sqrt(g2),
           m->whirl == GD_WHIRL_FORWARD ? "forward" : "not forward");
    CHECK_REL(ratio, sqrt(g2), 1e-4);
    CHECK(m->whirl == GD_WHIRL_FORWARD);
    /* the sparse eigensolver sees the laws through the same dynamic matrix */
    gd_campbell_result *rs = NULL;
    o.method = GD_EIG_SPARSE;
    o.nmodes = 2;
    REQUIRE(gd_campbell(f.s, &o, &rs, &err) == GD_OK);
    CHECK(rs->sparse);
    CHECK_REL(rs->instability_onset, w, 1e-6);
    gd_campbell_free(rs);
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

/* Above eps 0.756 the short bearing is stable at every speed: thinner oil (1 mPa s)
 * keeps eps above 0.8 up to 3000 rad/s, and campbell finds no onset; with the example's
 * oil the same range is unstable. */
TEST(heavily_loaded_bearing_is_stable)
{
    fx f;
    REQUIRE(load(&f, "examples/journal_rotor.yaml", NULL));
    for (int i = 0; i < f.m->nlaws; i++)
        f.m->laws[i].value[0] = 0.001;
    gd_system_free(f.s);
    gd_error err;
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    int n = f.s->ndof;
    double *q = malloc((size_t)n * sizeof *q);
    REQUIRE(gd_system_law_state(f.s, 3000, q) == 1);
    double e = hypot(q[0], q[1]) / CL;
    printf("  1 mPa s: eps %.4f at 3000 rad/s\n", e);
    CHECK(e > 0.8);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.nspeeds = 30;
    double *sp = linspace(100, 3000, o.nspeeds);
    o.speeds = sp;
    o.nmodes = 0;
    gd_campbell_result *r = NULL;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    CHECK(isnan(r->instability_onset) && r->instability_track < 0);
    gd_campbell_free(r);
    free(sp);
    free(q);
    fx_free(&f);
}

RUN_TESTS(T(short_bearing_stability_curve), T(oil_whirl_onset_against_stability_curve),
          T(heavily_loaded_bearing_is_stable))
