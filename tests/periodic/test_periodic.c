/* Harmonic balance (periodic.h): the linear case against the unbalance response, the
 * damped Mathieu tongue of a TVMS pair against its closed form, Floquet multipliers
 * against the integrated monodromy, and backlash / SFD steady states against time
 * integration. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/periodic.h"
#include "geardyn/transient_model.h"
#include "geardyn/unbalance.h"
#include "harness.h"
#include "model_support.h"

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

/* Linear, constant stiffness: HB equals the unbalance response (two shafts at different
 * speeds: harmonics 1 and r_a/r_b of gear a's speed... both multiples of the common
 * fundamental). Tolerance 1e-9: both solve the same linear equations, the difference is
 * rounding. */
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
    const double speeds[3] = {300.0, 1100.0, 2500.0};
    gd_periodic_result *r = run_speeds(&f, &tm->spec, speeds[0], speeds[2], 3, &o, NULL, 0);
    /* middle value differs from the grid: solve it separately below */
    REQUIRE(r);
    REQUIRE(r->npoints == 3);
    gd_probe pr[6];
    int np = 0;
    const char *nodes[2] = {"gear_a", "gear_b"};
    const gd_dof ds[3] = {GD_X, GD_Y, GD_RZ};
    for (int a = 0; a < 2; a++)
        for (int d = 0; d < 3; d++)
            pr[np++] = (gd_probe){.kind = GD_PROBE_DOF, .index = dof(&f, nodes[a], ds[d])};
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

RUN_TESTS(T(linear_equals_unbalance))
