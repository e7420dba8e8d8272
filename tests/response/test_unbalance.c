/* Unbalance response: a Jeffcott rotor in closed form, Chen et al. 1998 Fig. 5 (gear-a
 * unbalance excites every mode but the pure lateral mode of gear b), Kumar 2011
 * (lateral-torsional coupling turns unbalance into torsion; two shafts, two
 * harmonics), thread independence, errors. */
#include <complex.h>
#include <stdlib.h>

#include "geardyn/unbalance.h"
#include "harness.h"
#include "model_support.h"

/* fx, load, fx_free, dof: tests/model_support.h */

static double *linspace(double a, double b, int n)
{
    double *v = malloc((size_t)n * sizeof *v);
    for (int i = 0; i < n; i++)
        v[i] = n == 1 ? a : a + (b - a) * i / (n - 1);
    return v;
}

static const char JEFFCOTT[] =
    "dofs: [x, y]\n"
    "shafts:\n  - name: rotor\n    nodes: [{name: disk}]\n"
    "disks:\n  - {name: disk, node: disk, mass: 10}\n"
    "bearings:\n  - {name: B, node: disk, k: 1e6, c: 400}\n"
    "unbalances:\n  - {name: u, node: disk, amount: 1e-4, phase: 30 deg}\n";

/* x = U w^2 e^{i phase} / (k - m w^2 + i w c), y = -i x: a forward circle (major =
 * minor = |x|), and the
 * bearing transmits k x + c x'. */
TEST(jeffcott_closed_form)
{
    fx f;
    REQUIRE(load(&f, NULL, JEFFCOTT));
    double *sp = linspace(0, 600, 61);
    gd_probe out[3] = {{NULL, dof(&f, "disk", GD_X), GD_X, "x"},
                       {NULL, dof(&f, "disk", GD_Y), GD_X, "y"},
                       {&gd_element_bearing, 0, GD_X, "B.x"}};
    int node = gd_model_find_node(f.m, "disk");
    gd_unbalance_options o;
    gd_unbalance_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 61;
    o.outputs = out;
    o.noutputs = 3;
    o.orbit_nodes = &node;
    o.norbits = 1;
    gd_unbalance_result *r;
    gd_error err;
    REQUIRE(gd_unbalance_response(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->nharmonics == 1);
    CHECK_REL(r->harmonics[0].order, 1.0, 0);
    for (int s = 1; s < 61; s++) {
        double w = sp[s];
        double complex x = 1e-4 * w * w * cexp(I * M_PI / 6) / (1e6 - 10 * w * w + I * w * 400);
        CHECK_REL(r->re[s], creal(x), 1e-10);
        CHECK_REL(r->im[s], cimag(x), 1e-10);
        CHECK_REL(r->re[61 + s], creal(-I * x), 1e-10);
        CHECK_REL(r->im[61 + s], cimag(-I * x), 1e-10);
        double complex fb = (1e6 + I * w * 400) * x;
        CHECK_REL(r->re[122 + s], creal(fb), 1e-10);
        const gd_orbit *ob = &r->orbits[s];
        CHECK_REL(ob->major, cabs(x), 1e-10);
        CHECK_REL(ob->minor, cabs(x), 1e-10); /* a circle */
        CHECK(ob->whirl == GD_WHIRL_FORWARD);
    }
    CHECK(r->re[0] == 0 && r->orbits[0].whirl == GD_WHIRL_NONE); /* no force at rest */
    gd_unbalance_free(r);
    free(sp);
    fx_free(&f);
}

/* [Chen1998] Fig. 5: an unbalance on gear a excites every mode except the pure lateral mode of
 * gear b (its motion across the line of action, which nothing couples). Gear b's
 * motion across the line of action is zero at every speed, the response along it is
 * not, and the overall response peaks at the five other modes but not at 1674 rad/s. */
TEST(chen_fig5_all_modes_but_gear_b_lateral)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    gd_mesh_vector mv;
    gd_system_mesh_vector(f.s, 0, &mv);
    int bx = dof(&f, "gear_b", GD_X), by = dof(&f, "gear_b", GD_Y);
    double ax = 0, ay = 0;
    for (int j = 0; j < mv.n; j++) {
        if (mv.dof[j] == bx) ax = mv.a[j];
        if (mv.dof[j] == by) ay = mv.a[j];
    }
    REQUIRE(hypot(ax, ay) > 0);
    int nd = f.s->ndof, ns = 2401;
    double *sp = linspace(300, 7500, ns);
    gd_probe *out = calloc((size_t)nd, sizeof *out);
    for (int i = 0; i < nd; i++)
        out[i] = (gd_probe){NULL, i, GD_X, "q"};
    gd_unbalance_options o;
    gd_unbalance_options_init(&o);
    o.speeds = sp;
    o.nspeeds = ns;
    o.outputs = out;
    o.noutputs = nd;
    gd_unbalance_result *r;
    gd_error err;
    REQUIRE(gd_unbalance_response(f.s, &o, &r, &err) == GD_OK);
    double *norm = calloc((size_t)ns, sizeof *norm);
    for (int s = 0; s < ns; s++) {
        double complex X = r->re[(size_t)bx * ns + s] + I * r->im[(size_t)bx * ns + s];
        double complex Y = r->re[(size_t)by * ns + s] + I * r->im[(size_t)by * ns + s];
        double along = cabs(ax * X + ay * Y), across = cabs(-ay * X + ax * Y);
        CHECK(along > 0);
        CHECK(across <= 1e-12 * along);
        for (int i = 0; i < nd; i++) /* translations in m, rotations scaled by 0.05 m */
            norm[s] += hypot(r->re[(size_t)i * ns + s], r->im[(size_t)i * ns + s]) *
                       (f.s->dof_type[i] == GD_RZ ? 0.05 : 1.0);
    }
    double peaks[16];
    int np = 0;
    for (int s = 1; s + 1 < ns && np < 16; s++)
        if (norm[s] > norm[s - 1] && norm[s] > norm[s + 1]) peaks[np++] = sp[s];
    const double modes[5] = {669.6, 795.7, 1071.6, 1811.2, 5642.6};
    for (int k = 0; k < np; k++)
        printf("  response peak at %.0f rad/s\n", peaks[k]);
    for (int j = 0; j < 5; j++) {
        int near = 0;
        for (int k = 0; k < np; k++)
            near |= fabs(peaks[k] - modes[j]) < 0.03 * modes[j];
        CHECK(near);
    }
    for (int k = 0; k < np; k++)
        CHECK(fabs(peaks[k] - 1674.2) > 0.03 * 1674.2);
    free(norm);
    free(out);
    gd_unbalance_free(r);
    free(sp);
    fx_free(&f);
}

/* Kumar: unbalances on pinion (ratio 1) and gear (ratio -0.9468) are two harmonics;
 * lateral-torsional coupling makes both turn into torsion of the pinion, and the gear's
 * orbit whirls forward with its own (negative) rotation. */
TEST(kumar_two_harmonics_and_torsion)
{
    fx f;
    REQUIRE(load(&f, "examples/kumar2011_coupled.yaml", NULL));
    double sp[3] = {1000, 2000, 20000};
    gd_probe out[2] = {{NULL, dof(&f, "pinion", GD_RZ), GD_X, "pinion.rz"},
                       {&gd_element_mesh, 0, GD_X, "mesh"}};
    int nodes[2] = {gd_model_find_node(f.m, "pinion"), gd_model_find_node(f.m, "gear")};
    gd_unbalance_options o;
    gd_unbalance_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 3;
    o.outputs = out;
    o.noutputs = 2;
    o.orbit_nodes = nodes;
    o.norbits = 2;
    gd_unbalance_result *r;
    gd_error err;
    REQUIRE(gd_unbalance_response(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->nharmonics == 2);
    CHECK_REL(r->harmonics[0].order, 0.0445 / 0.047, 1e-9);
    CHECK_REL(r->harmonics[1].order, 1.0, 1e-12);
    for (int h = 0; h < 2; h++)
        for (int s = 0; s < 3; s++) {
            CHECK(hypot(r->re[((size_t)h * 2 + 0) * 3 + s], r->im[((size_t)h * 2 + 0) * 3 + s]) >
                  0);
            CHECK(hypot(r->re[((size_t)h * 2 + 1) * 3 + s], r->im[((size_t)h * 2 + 1) * 3 + s]) >
                  0);
        }
    /* harmonic 0 comes from the gear's unbalance: its orbit is the larger there */
    CHECK(r->orbits[(0 * 2 + 1) * 3 + 0].major > r->orbits[(0 * 2 + 0) * 3 + 0].major);
    CHECK(r->orbits[(1 * 2 + 0) * 3 + 0].major > r->orbits[(1 * 2 + 1) * 3 + 0].major);
    /* below the lateral modes each unbalanced gear whirls forward with its own shaft */
    CHECK(r->orbits[(0 * 2 + 1) * 3 + 0].whirl == GD_WHIRL_FORWARD);
    CHECK(r->orbits[(1 * 2 + 0) * 3 + 0].whirl == GD_WHIRL_FORWARD);
    gd_unbalance_free(r);
    fx_free(&f);
}

TEST(threads_identical)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    double *sp = linspace(0, 6000, 301);
    gd_probe out[2] = {{&gd_element_mesh, 0, GD_X, "mesh"},
                       {&gd_element_bearing, 1, GD_Y, "support_b.y"}};
    gd_unbalance_options o;
    gd_unbalance_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 301;
    o.outputs = out;
    o.noutputs = 2;
    gd_unbalance_result *a, *b;
    gd_error err;
    o.nthreads = 1;
    REQUIRE(gd_unbalance_response(f.s, &o, &a, &err) == GD_OK);
    o.nthreads = 3;
    REQUIRE(gd_unbalance_response(f.s, &o, &b, &err) == GD_OK);
    CHECK(!memcmp(a->re, b->re, 2 * 301 * sizeof(double)));
    CHECK(!memcmp(a->im, b->im, 2 * 301 * sizeof(double)));
    gd_unbalance_free(a);
    gd_unbalance_free(b);
    free(sp);
    fx_free(&f);
}

TEST(errors)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL)); /* no unbalances */
    double sp[1] = {100};
    gd_unbalance_options o;
    gd_unbalance_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 1;
    gd_unbalance_result *r = (gd_unbalance_result *)1;
    gd_error err;
    CHECK(gd_unbalance_response(f.s, &o, &r, &err) == GD_EINPUT && r == NULL);
    CHECK(strstr(err.message, "no unbalances") != NULL);
    fx_free(&f);
    REQUIRE(load(&f, "examples/kumar2011_coupled.yaml", NULL));
    gd_model_set_coupling(f.m, GD_COUPLING_TORSIONAL);
    REQUIRE(gd_model_restrict_dofs(f.m, GD_DOF_BIT(GD_RZ), &err) == GD_OK);
    gd_system_free(f.s);
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    CHECK(gd_unbalance_response(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "x and y are not active") != NULL);
    sp[0] = -1;
    CHECK(gd_unbalance_response(f.s, &o, &r, &err) == GD_EINPUT);
    o.nspeeds = 0;
    CHECK(gd_unbalance_response(f.s, &o, &r, &err) == GD_EINPUT);
    fx_free(&f);
}

RUN_TESTS(T(jeffcott_closed_form), T(chen_fig5_all_modes_but_gear_b_lateral),
          T(kumar_two_harmonics_and_torsion), T(threads_identical), T(errors))
