/* Oil whirl of examples/jeffcott_journal.yaml (issue 34): a rigid 20 kg rotor (one node,
 * no tilt) on two short plain journal bearings (D 50 mm, L 20 mm, c 50 um, 0.02 Pa s)
 * under gravity. campbell over 500-20000 rpm linearises the bearings about the static
 * equilibrium at every speed and reports the onset of whirl; the reference is Lund's
 * critical-mass criterion on the closed-form short-bearing coefficients
 * (tests/short_bearing_reference.h; Lund 1966, Childs 1993 ch. 3) along the rotor's own
 * eccentricity eps(w), and `transient` from the equilibrium, nudged, finds the orbit
 * decaying at the grid speed below the onset and growing at the one above. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/campbell.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"
#include "model_support.h"
#include "short_bearing_reference.h"

#define EXAMPLE "examples/jeffcott_journal.yaml"
static const double MU = 0.02, RAD = 0.025, LEN = 0.02, CL = 50e-6, GN = 9.81, MASS = 10;

/* Lund: the threshold w_th sqrt(c / g_n) at eps e (infinite where the bearing is stable) */
static double threshold(double e)
{
    double a[4], b[4];
    short_bearing_coefficients(e, a, b);
    double keq = (a[0] * b[3] + a[3] * b[0] - a[1] * b[2] - a[2] * b[1]) / (b[0] + b[3]);
    double g2 = ((keq - a[0]) * (keq - a[3]) - a[1] * a[2]) / (b[0] * b[3] - b[1] * b[2]);
    return g2 > 0 ? sqrt(keq / g2) : INFINITY;
}

/* The speed at which one bearing's film carries its share m g_n at eps (Ocvirk). */
static double speed_at(double e)
{
    double s2 = 1 - e * e;
    double cap = MU * RAD * pow(LEN, 3) / (4 * CL * CL) * e * sqrt(M_PI * M_PI * s2 + 16 * e * e) /
                 (s2 * s2);
    return MASS * GN / cap;
}

static double rpm(double w)
{
    return w * 30 / M_PI;
}

/* Largest distance of the journal from its equilibrium qs over samples [k0, k1). */
static double excursion(const gd_transient_result *r, const double *qs, int k0, int k1)
{
    double big = 0;
    for (int k = k0; k < k1; k++)
        big = fmax(big, hypot(r->values[k] - qs[0], r->values[r->nout + k] - qs[1]));
    return big;
}

TEST(whirl_onset_campbell_and_transient)
{
    /* the reference: eps where threshold(eps) sqrt(g_n / c) = speed_at(eps) */
    double lo = 0.05, hi = 0.75;
    for (int i = 0; i < 80; i++) {
        double mid = 0.5 * (lo + hi);
        if (threshold(mid) * sqrt(GN / CL) - speed_at(mid) < 0)
            lo = mid;
        else
            hi = mid;
    }
    double eps = 0.5 * (lo + hi), w_ref = speed_at(eps);

    fx f;
    REQUIRE(load(&f, EXAMPLE, NULL));
    REQUIRE(f.s->ndof == 2);
    const int ns = 40;
    double sp[40];
    for (int i = 0; i < ns; i++)
        sp[i] = (500 + (20000 - 500) * i / (ns - 1.0)) * M_PI / 30;
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = ns;
    o.nmodes = 0;
    o.nthreads = 1;
    gd_campbell_result *r = NULL;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->instability_track >= 0);
    double w = r->instability_onset;
    printf("  onset %.1f rpm (grid %.0f rpm), Lund's criterion %.1f rpm at eps %.4f: rel err "
           "%.2g\n",
           rpm(w), rpm(sp[1] - sp[0]), rpm(w_ref), eps, fabs(w - w_ref) / w_ref);
    /* the onset interpolates the damping linearly over a 500 rpm grid (2.2e-4 here): 2e-3 */
    CHECK_REL(w, w_ref, 2e-3);

    /* transient at the grid speeds either side of the onset, gravity as a constant load
       (the time integrators leave `gravity:` out, docs/transient.md) */
    int above = 0;
    while (above < ns && sp[above] < w)
        above++;
    REQUIRE(above > 0 && above < ns);
    char yaml[2048];
    char *text = NULL;
    {
        FILE *fp = fopen(EXAMPLE, "r");
        REQUIRE(fp);
        text = calloc(1, 4096);
        size_t got = fread(text, 1, 4095, fp);
        fclose(fp);
        REQUIRE(got > 0);
    }
    char *g = strstr(text, "gravity:");
    REQUIRE(g);
    char *eol = strchr(g, '\n');
    snprintf(yaml, sizeof yaml,
             "%.*s%s\nexcitations:\n  loads:\n    - {node: disk, dof: y, value: "
             "-196.2}\n",
             (int)(g - text), text, eol + 1);
    free(text);
    fx t;
    REQUIRE(load(&t, NULL, yaml));
    double growth[2];
    for (int side = 0; side < 2; side++) {
        double W = sp[above - 1 + side];
        double qs[2], v0[2] = {0, 0};
        REQUIRE(gd_system_law_state(t.s, W, qs) == 1);
        double q0[2] = {qs[0] + 0.5e-6, qs[1]};
        gd_transient_model *tm;
        REQUIRE(gd_transient_model_build(t.s, &tm, &err) == GD_OK);
        gd_transient *tr;
        REQUIRE(gd_transient_new(t.s, &tm->spec, W, &tr, &err) == GD_OK);
        gd_transient_options to;
        gd_transient_options_init(&to);
        /* 80 whirl periods (about half the speed) */
        double T = 2 * M_PI / (0.5 * W);
        to.t_end = 80 * T;
        to.output_interval = T / 20;
        to.init = GD_TR_INIT_GIVEN;
        to.q0 = q0;
        to.v0 = v0;
        to.rtol = 1e-9;
        to.atol_q = 1e-13;
        gd_tr_record rec[2] = {{GD_REC_DISP, 0, 0}, {GD_REC_DISP, 1, 0}};
        gd_transient_result *tres = NULL;
        REQUIRE(gd_transient_run(tr, &to, rec, 2, &tres, &err) == GD_OK);
        int n = tres->nout, per = 20;
        double first = excursion(tres, qs, per * 5, per * 15);
        double last = excursion(tres, qs, n - per * 10, n);
        growth[side] = last / first;
        printf("  transient at %.1f rpm: excursion %.3g um (periods 5-15), %.3g um (last 10): "
               "x %.3g\n",
               rpm(W), first * 1e6, last * 1e6, growth[side]);
        gd_transient_result_free(tres);
        gd_transient_free(tr);
        gd_transient_model_free(tm);
    }
    CHECK(growth[0] < 1.0); /* decays below the onset */
    CHECK(growth[1] > 1.0); /* grows above it */
    gd_campbell_free(r);
    fx_free(&t);
    fx_free(&f);
}

RUN_TESTS(T(whirl_onset_campbell_and_transient))
