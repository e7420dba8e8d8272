/* The planets' centrifugal geometric stiffness (docs/planetary.md, "Rotating carrier"): each
 * planet bearing carries the planet's centrifugal load F = m_p Omega^2 r_c, and the preload's
 * work on the bearing's second-order radial deformation in the turning carrier,
 * E = F (th_c e_t . (u_n - u_c) - r_c th_c^2 / 2), adds to K at carrier speed Omega (not in
 * [CooleyParker2012] Eq. 1: `centrifugal_stiffness: false` leaves it out).
 * - the element's term is the Hessian of F times the exact radial deformation (central
 *   differences), symmetric, and a rotation of the whole set loads no body;
 * - [LinParker1999]'s set (ring held, sun and carrier free: one rigid-body mode; or nothing
 *   held: two) keeps those modes at 0 Hz at speed with no unstable mode; without the term one
 *   diverges (8.50 Hz; 41.24 Hz). */
#include "elements/elements_impl.h"
#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "harness.h"

#define PI 3.14159265358979323846
#define RPM (PI / 30)

/* file with the overrides set[0..nset) (NULL on failure, reported) */
static gd_model *load(const char *file, int nset, const char *const *set)
{
    gd_load_options opt;
    gd_load_options_init(&opt);
    opt.nset = nset;
    opt.set = set;
    gd_model *m = NULL;
    gd_error err;
    if (gd_model_load_opts(file, &opt, &m, &err)) fprintf(stderr, "  %s\n", err.message);
    return m;
}

/* The planet bearing's radial deformation measured in the carrier turned by th_c, exact:
 * e_r(psi + th_c) . (r_c e_r(psi) + u_n - u_c) - r_c; q local (carrier x..rz, planet x..rz). */
static double radial_deformation(double psi, double rc, const double q[12])
{
    double a = psi + q[GD_RZ];
    double px = rc * cos(psi) + q[6 + GD_X] - q[GD_X], py = rc * sin(psi) + q[6 + GD_Y] - q[GD_Y];
    return cos(a) * px + sin(a) * py - rc;
}

/* The element's term against central differences of F times the exact deformation, on
 * [CooleyParker2012]'s set (the carrier the reference shaft) with unequally spaced planets;
 * symmetric; off with `centrifugal_stiffness: false`. */
TEST(term_is_the_hessian_of_the_preloads_work)
{
    static const char *const set[] = {"planetary_sets.cp.planets.angles=[0, 80 deg, 170 deg, "
                                      "265 deg]",
                                      "planetary_sets.cp.centrifugal_stiffness=false"};
    for (int off = 0; off < 2; off++) {
        gd_model *m = load("examples/planetary_cooley_parker.yaml", 1 + off, set);
        REQUIRE(m);
        const gd_planetary *g = &m->planetary[0];
        const gd_element_type *t = &gd_element_planetary;
        double W = 5000 * RPM, K0[144], K[144];
        for (int n = 0; n < g->nplanets; n++) {
            /* planet n's bearing, then its preload (after the set's 3 + 4N instances) */
            int i = 3 + 3 * g->nplanets + n, p = 3 + 4 * g->nplanets + n;
            CHECK(t->count(m) == 3 + (off ? 4 : 5) * g->nplanets);
            CHECK(t->terms(m, i) == GD_TERM_K);
            if (!off) {
                CHECK(t->terms(m, p) == (GD_TERM_K | GD_TERM_SPEED));
                CHECK(t->ncomponents(m) == 3 + 4 * g->nplanets);
                CHECK(t->component(m, p) == i); /* its energy is the bearing's */
            }
            t->matrices(m, i, 0.0, NULL, K0, NULL, NULL);
            t->matrices(m, i, W, NULL, K, NULL, NULL);
            if (!off) { /* the bearing's K, plus the preload's at W */
                double Kg[144];
                t->matrices(m, p, W, NULL, Kg, NULL, NULL);
                for (int a = 0; a < 144; a++)
                    K[a] += Kg[a];
            }
            double F = off ? 0 : g->planet_mass * W * W * g->carrier_radius, kmax = 0, err = 0;
            double h[12];
            for (int a = 0; a < 12; a++) /* steps: 1e-3 rad, 1e-3 r_c */
                h[a] = a % 6 == GD_RZ ? 1e-3 : 1e-3 * g->carrier_radius;
            for (int a = 0; a < 12; a++)
                for (int b = 0; b < 12; b++) {
                    double d = 0, q[12] = {0};
                    for (int sa = -1; sa <= 1; sa += 2)
                        for (int sb = -1; sb <= 1; sb += 2) {
                            q[a] += sa * h[a];
                            q[b] += sb * h[b];
                            d += sa * sb *
                                 radial_deformation(g->planet_angle[n], g->carrier_radius, q);
                            q[a] = q[b] = 0;
                        }
                    double hess = F * d / (4 * h[a] * h[b]), kg = K[a * 12 + b] - K0[a * 12 + b];
                    kmax = fmax(kmax, fabs(hess));
                    err = fmax(err, fabs(kg - hess));
                    CHECK(K[a * 12 + b] - K0[a * 12 + b] == K[b * 12 + a] - K0[b * 12 + a]);
                }
            if (off)
                CHECK(err == 0);
            else { /* the th_c th_c entry: -F r_c; the largest, th_c against a translation: F */
                CHECK_REL(K[GD_RZ * 13] - K0[GD_RZ * 13], -F * g->carrier_radius, 1e-12);
                CHECK(kmax > 0.9 * F && err <= 1e-6 * kmax);
            }
        }
        gd_model_free(m);
    }
}

/* A rotation th of the whole set (carrier and planets; the planets' centres move r_c th
 * along e_t) loads no planet and no carrier torsion at speed: the bearings' term cancels the
 * planets' centripetal softening -m_p Omega^2 (planet body and bearing instances, local K).
 * The carrier's translations get -F th sum_n e_t(psi_n): zero for equally spaced planets. */
TEST(rotation_of_the_set_loads_nothing)
{
    gd_model *m = load("examples/planetary_cooley_parker.yaml", 0, NULL);
    REQUIRE(m);
    const gd_planetary *g = &m->planetary[0];
    const gd_element_type *t = &gd_element_planetary;
    int N = g->nplanets;
    double W = 12000 * RPM, rc = g->carrier_radius, F = g->planet_mass * W * W * rc;
    double carrier[6] = {0}, Kb[144], Kp[36];
    double worst = 0;
    for (int n = 0; n < N; n++) {
        double psi = g->planet_angle[n], q[12] = {0}, f[12] = {0};
        q[GD_RZ] = 1;
        q[6 + GD_X] = -rc * sin(psi);
        q[6 + GD_Y] = rc * cos(psi);
        q[6 + GD_RZ] = 0.7; /* the planet's spin is free: any */
        double Kg[144];
        t->matrices(m, 3 + 3 * N + n, W, NULL, Kb, NULL, NULL);
        t->matrices(m, 3 + 4 * N + n, W, NULL, Kg, NULL, NULL); /* the bearing's preload */
        for (int a = 0; a < 144; a++)
            Kb[a] += Kg[a];
        t->matrices(m, 3 + n, W, NULL, Kp, NULL, NULL);
        for (int a = 0; a < 12; a++)
            for (int b = 0; b < 12; b++)
                f[a] += Kb[a * 12 + b] * q[b];
        for (int a = 0; a < 6; a++)
            for (int b = 0; b < 6; b++)
                f[6 + a] += Kp[a * 6 + b] * q[6 + b];
        for (int a = 0; a < 6; a++) {
            worst = fmax(worst, fabs(f[6 + a]));
            carrier[a] += f[a];
        }
    }
    CHECK(F > 1e4);            /* 1.86 kg at 44.3 mm, 12000 rpm: 1.30e5 N */
    CHECK(worst <= 1e-12 * F); /* planets */
    CHECK(fabs(carrier[GD_RZ]) <= 1e-12 * F * rc);
    CHECK(hypot(carrier[GD_X], carrier[GD_Y]) <= 1e-12 * F);
    gd_model_free(m);
}

/* modal at Omega of a set; fills the count of rigid-body and unstable modes, the largest
 * rigid frequency and the lowest unstable one (Hz). */
static int count_modes(const gd_model *m, double W, int *rigid, int *unstable, double *f_rigid,
                       double *f_unstable)
{
    gd_system *sys = NULL;
    gd_modal_result *r = NULL;
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    opt.speed = W;
    opt.kind = GD_MODAL_DAMPED;
    if (gd_system_build(m, &sys, NULL) || gd_modal_solve(sys, &opt, &r, NULL)) {
        gd_system_free(sys);
        return 0;
    }
    *rigid = *unstable = 0;
    *f_rigid = 0;
    *f_unstable = INFINITY;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body) {
            (*rigid)++;
            *f_rigid = fmax(*f_rigid, md->frequency_hz);
        }
        if (md->unstable) {
            (*unstable)++;
            *f_unstable = fmin(*f_unstable, md->frequency_hz);
        }
    }
    gd_modal_free(r);
    gd_system_free(sys);
    return 1;
}

/* examples/planetary_lin_parker.yaml (ring held, sun and carrier free) at 5000 rpm of the
 * sun (carrier 0.22 of it): the rigid-body mode stays at 0 Hz, nothing is unstable; with
 * `centrifugal_stiffness: false` ([CooleyParker2012] Eq. 1) that mode diverges at 8.50 Hz.
 * The same set as a differential (nothing held, carrier at 5000 rpm): both rigid-body modes
 * (the whole set turning, and the differential's free motion) at 0 Hz; without the term one
 * of them diverges at 41.24 Hz. */
TEST(free_set_keeps_its_rigid_body_modes)
{
    static const char *const set[] = {"planetary_sets.lp.held=none",
                                      "planetary_sets.lp.ring.k_torsion=0",
                                      "planetary_sets.lp.centrifugal_stiffness=false"};
    static const struct {
        int first, nset, rigid, unstable;
        double f_unstable;
    } cases[] = {{2, 0, 1, 0, 0}, {2, 1, 0, 1, 8.5012}, {0, 2, 2, 0, 0}, {0, 3, 1, 1, 41.2413}};
    for (int c = 0; c < 4; c++) {
        gd_model *m =
            load("examples/planetary_lin_parker.yaml", cases[c].nset, set + cases[c].first);
        REQUIRE(m);
        int rigid, unstable;
        double f_rigid, f_unstable;
        REQUIRE(count_modes(m, 5000 * RPM, &rigid, &unstable, &f_rigid, &f_unstable));
        CHECK(rigid == cases[c].rigid);
        CHECK(f_rigid < 1e-6);
        CHECK(unstable == cases[c].unstable);
        if (cases[c].unstable) CHECK_REL(f_unstable, cases[c].f_unstable, 1e-4);
        gd_model_free(m);
    }
}

RUN_TESTS(T(term_is_the_hessian_of_the_preloads_work), T(rotation_of_the_set_loads_nothing),
          T(free_set_keeps_its_rigid_body_modes))
