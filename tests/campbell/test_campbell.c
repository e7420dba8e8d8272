/* Campbell diagrams: the sparse shift-invert eigensolver against the dense one,
 * gyroscopic splitting (forward up, backward down, equal pairs at rest), tracking,
 * critical speeds against a direct solve, instability onset, thread independence,
 * errors. */
#include <stdlib.h>

#include "campbell/campbell_impl.h"
#include "geardyn/campbell.h"
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

/* Shift-invert Krylov-Schur gives the dense solver's eigenvalues to 1e-9 and the same
 * shapes (MAC 1), rigid torsional mode included, at rest and at speed. */
TEST(sparse_equals_dense)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    const double speeds[2] = {0, 628.3};
    for (int k = 0; k < 2; k++) {
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.speed = speeds[k];
        o.nmodes = 13;
        o.want_left = 0;
        o.kind = GD_MODAL_DAMPED;
        gd_modal_result *d, *s;
        gd_error err;
        REQUIRE(gd_modal_solve(f.s, &o, &d, &err) == GD_OK);
        REQUIRE(gd_modal_solve_sparse(f.s, &o, 0, &s, &err) == GD_OK);
        REQUIRE(s->nmodes == 13);
        CHECK(s->modes[0].rigid_body && d->modes[0].rigid_body);
        for (int j = 1; j < 13; j++) {
            CHECK_REL(s->modes[j].lambda_im, d->modes[j].lambda_im, 1e-9);
            CHECK_ABS(s->modes[j].lambda_re, d->modes[j].lambda_re, 1e-9 * d->modes[j].omega_n);
            CHECK(s->modes[j].whirl == d->modes[j].whirl);
            int n = f.s->ndof;
            /* repeated eigenvalues (x/y pairs at rest) have no preferred vectors */
            int repeated =
                fabs(d->modes[j].omega_n - d->modes[j - 1].omega_n) < 1e-6 * d->modes[j].omega_n ||
                (j + 1 < 13 &&
                 fabs(d->modes[j].omega_n - d->modes[j + 1].omega_n) < 1e-6 * d->modes[j].omega_n);
            if (!repeated)
                CHECK(gd_mac(s->shape_re + (size_t)j * n, s->shape_im + (size_t)j * n,
                             d->shape_re + (size_t)j * n, d->shape_im + (size_t)j * n, n) > 0.999);
        }
        gd_modal_free(d);
        gd_modal_free(s);
    }
    fx_free(&f);
}

static const char ROTOR[] =
    "dofs: [x, y, rx, ry]\n"
    "materials:\n  steel: {density: 7800, E: 2.1e11, poisson: 0.3}\n"
    "shafts:\n  - name: rotor\n    material: steel\n    elements_per_section: 6\n"
    "    sections: [{length: 0.6, outer_diameter: 0.03}]\n"
    "    nodes: [{name: b1, at: 0}, {name: disk, at: 0.45}, {name: b2, at: 0.6}]\n"
    "disks:\n  - {name: disk, node: disk, mass: 8, polar_inertia: 0.12, diametral_inertia: 0.06}\n"
    "bearings:\n  - {name: B1, node: b1, k: 2e6, c: 30}\n  - {name: B2, node: b2, k: 2e6, c: 30}\n";

/* A gyroscopic rotor: pairs are equal at rest, then forward modes rise and backward
 * modes fall with speed, and each track keeps its whirl. */
TEST(gyroscopic_forward_rises_backward_falls)
{
    fx f;
    REQUIRE(load(&f, NULL, ROTOR));
    double *sp = linspace(0, 3000, 31);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 31;
    o.nmodes = 4;
    gd_campbell_result *r;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->ntracks == 4);
    CHECK(r->nrigid == 0);
    int nf = 0, nb = 0;
    for (int t = 0; t < 4; t++) {
        const gd_mode *md = r->modes + (size_t)t * 31;
        for (int k = 0; k < 31; k++)
            CHECK(md[k].rigid_body == 0); /* present everywhere */
        if (r->tracks[t].whirl == GD_WHIRL_FORWARD) {
            nf++;
            for (int k = 1; k < 31; k++)
                CHECK(md[k].omega_d > md[k - 1].omega_d);
        } else if (r->tracks[t].whirl == GD_WHIRL_BACKWARD) {
            nb++;
            for (int k = 1; k < 31; k++)
                CHECK(md[k].omega_d < md[k - 1].omega_d);
        }
        for (int k = 1; k < 31; k++)
            CHECK(md[k].whirl == r->tracks[t].whirl);
    }
    CHECK(nf == 2 && nb == 2);
    /* at rest the tracks come in equal pairs (isotropic bearings) */
    CHECK_REL(r->modes[0].omega_d, r->modes[31].omega_d, 1e-8);
    CHECK_REL(r->modes[62].omega_d, r->modes[93].omega_d, 1e-8);
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

/* The same sweep on 1 and 3 threads, dense and sparse, is bitwise identical; the
 * sparse and dense Campbell diagrams agree. */
static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The sparse Campbell starts each speed's Krylov space from the previous speed's modes
 * (chains of 8 speeds, campbell.c): its eigenvalues equal those of a cold solve at
 * every speed to within the solver's own accuracy. Both are converged to a residual
 * of 1e-9 (GD_SPARSE_TOL), so they may differ by that much whatever the start vector:
 * measured 2.2e-10 at most (rig366, 8 speeds), asserted at 1e-9 of omega_n. */
TEST(warm_start_equals_cold)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    int ns = 12, nm = 8;
    double *sp = linspace(0, 1256.6, ns);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = ns;
    o.nmodes = nm;
    o.method = GD_EIG_SPARSE;
    o.nthreads = 1;
    gd_campbell_result *r;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->sparse);
    double worst = 0;
    int compared = 0;
    for (int s = 0; s < ns; s++) {
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = sp[s];
        mo.nmodes = nm + r->nrigid;
        mo.want_left = 0;
        gd_modal_result *c;
        REQUIRE(gd_modal_solve_sparse(f.s, &mo, 0, &c, &err) == GD_OK);
        double wa[64], wb[64];
        int na = 0, nb = 0;
        for (int t = 0; t < r->ntracks && na < 64; t++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + s];
            if (md->rigid_body == 0) wa[na++] = md->omega_n;
        }
        for (int j = 0; j < c->nmodes && nb < 64; j++)
            if (!c->modes[j].rigid_body) wb[nb++] = c->modes[j].omega_n;
        CHECK(na == nm && nb == nm);
        qsort(wa, (size_t)na, sizeof *wa, cmp_double);
        qsort(wb, (size_t)nb, sizeof *wb, cmp_double);
        for (int j = 0; j < na && j < nb; j++, compared++)
            worst = fmax(worst, fabs(wa[j] - wb[j]) / wb[j]);
        gd_modal_free(c);
    }
    CHECK(compared == ns * nm);
    CHECK_ABS(worst, 0.0, 1e-9);
    printf("  warm vs cold: largest |omega_warm - omega_cold| / omega %.2e\n", worst);
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

/* An overhung disk on two oil-film bearings whose stiffness and damping change with
 * speed (speed tables, anisotropic and cross-coupled), gyroscopic: the non-symmetric
 * case of the continuation (sparse_track.c). */
static const char OILFILM[] =
    "dofs: [x, y, rx, ry, rz]\n"
    "materials:\n  steel: {density: 7850, E: 210 GPa, poisson: 0.3}\n"
    "shafts:\n  - name: rotor\n    material: steel\n    elements_per_section: 12\n"
    "    sections: [{length: 0.6, outer_diameter: 50 mm}, {length: 0.2, outer_diameter: 40 "
    "mm}]\n"
    "    nodes: [{name: b1, at: 0}, {name: b2, at: 0.6}, {name: tip, at: 0.8}]\n"
    "disks:\n  - {name: wheel, node: tip, mass: 12, polar_inertia: 0.12, "
    "diametral_inertia: 0.065}\n"
    "bearings:\n"
    "  - name: front\n    node: b1\n    table:\n"
    "      - {speed: 0, k: 5e7, c: 2e3}\n"
    "      - {speed: 3000 rpm, kxx: 4e7, kyy: 6e7, kxy: 1.5e7, kyx: -1.5e7, c: 1.5e3}\n"
    "      - {speed: 9000 rpm, kxx: 3e7, kyy: 5e7, kxy: 3e7, kyx: -3e7, c: 1.2e3}\n"
    "  - name: rear\n    node: b2\n    table:\n"
    "      - {speed: 0, k: 8e7, c: 3e3}\n"
    "      - {speed: 9000 rpm, kxx: 6e7, kyy: 9e7, kxy: 2e7, kyx: -2e7, c: 2e3}\n"
    "springs:\n  - {name: coupling, node: b1, dof: rz, stiffness: 1e4}\n";

/* The continuation of the modes from speed to speed (the default of the sparse sweep)
 * against the dense (LAPACK) eigenvalues at every speed and against Krylov-Schur at
 * every speed (the reference path), on the oil-film rotor (speed-dependent, cross-coupled
 * bearings) and on the geared rig (gyroscopic, a rigid torsional mode). The continuation
 * accepts a mode at a relative residual of 1e-10 (first-order eigenvalue error), Krylov-
 * Schur at 1e-9 in its own measure: measured |d lambda| / |lambda| from dense 4e-12
 * (oil film; Krylov-Schur 7e-12) and 2.3e-10 (rig; Krylov-Schur 5.4e-10), frequencies
 * 4.3e-10 apart at most; asserted 1e-9 from dense and 3e-9 between the paths. Most
 * speeds must have been continued (else this compares Krylov-Schur with itself). */
TEST(continuation_equals_reference)
{
    for (int model = 0; model < 2; model++) {
        fx f;
        REQUIRE(load(&f, model ? "examples/rig2018.yaml" : NULL, model ? NULL : OILFILM));
        /* the oil film from 50 rad/s, where its tables already make it anisotropic: at
         * rest its pairs are double and the window of 10 modes cuts one, which the
         * continuation leaves to Krylov-Schur (the trial in campbell.c) */
        int ns = 30, nm = 10;
        double *sp = linspace(model ? 0 : 50, 1256.6, ns);
        gd_campbell_options o;
        gd_campbell_options_init(&o);
        o.speeds = sp;
        o.nspeeds = ns;
        o.nmodes = nm;
        o.method = GD_EIG_SPARSE;
        o.nthreads = 1;
        gd_campbell_result *r[2];
        gd_campbell_stats st[2];
        gd_error err;
        for (int c = 0; c < 2; c++)
            REQUIRE(gd_campbell_run(f.s, &o, c, &st[c], &r[c], &err) == GD_OK);
        CHECK(st[0].continued == 0 && st[1].continued >= ns / 2);
        printf("  model %d: %d of %d speeds continued, %d fallbacks\n", model, st[1].continued, ns,
               st[1].fallbacks);
        double worst[2] = {0, 0}, between = 0;
        int compared = 0;
        for (int s = 0; s < ns; s++) {
            gd_modal_options mo;
            gd_modal_options_init(&mo);
            mo.speed = sp[s];
            mo.nmodes = 0;
            mo.want_left = 0;
            mo.kind = GD_MODAL_DAMPED;
            mo.method = GD_EIG_DENSE;
            gd_modal_result *d;
            REQUIRE(gd_modal_solve(f.s, &mo, &d, &err) == GD_OK);
            for (int c = 0; c < 2; c++)
                for (int t = 0; t < r[c]->ntracks; t++) {
                    const gd_mode *md = &r[c]->modes[(size_t)t * ns + s];
                    if (isnan(md->omega_n)) continue;
                    double near = INFINITY;
                    for (int q = 0; q < d->nmodes; q++)
                        if (!d->modes[q].rigid_body)
                            near = fmin(near, hypot(d->modes[q].lambda_re - md->lambda_re,
                                                    d->modes[q].lambda_im - md->lambda_im));
                    worst[c] = fmax(worst[c], near / md->omega_n);
                    compared += c;
                }
            gd_modal_free(d);
            double wa[64], wb[64];
            int na = 0, nb = 0;
            for (int t = 0; t < r[0]->ntracks && na < 64; t++)
                if (!isnan(r[0]->modes[(size_t)t * ns + s].omega_n))
                    wa[na++] = r[0]->modes[(size_t)t * ns + s].omega_n;
            for (int t = 0; t < r[1]->ntracks && nb < 64; t++)
                if (!isnan(r[1]->modes[(size_t)t * ns + s].omega_n))
                    wb[nb++] = r[1]->modes[(size_t)t * ns + s].omega_n;
            CHECK(na == nm && nb == nm);
            qsort(wa, (size_t)na, sizeof *wa, cmp_double);
            qsort(wb, (size_t)nb, sizeof *wb, cmp_double);
            for (int j = 0; j < na && j < nb; j++)
                between = fmax(between, fabs(wa[j] - wb[j]) / wa[j]);
        }
        CHECK(compared == ns * nm);
        CHECK_ABS(worst[1], 0.0, 1e-9);
        CHECK_ABS(worst[0], 0.0, 1e-9);
        CHECK_ABS(between, 0.0, 3e-9);
        printf("  model %d: |d lambda| / |lambda| from dense %.2e (continuation), %.2e "
               "(Krylov-Schur); frequencies between them %.2e\n",
               model, worst[1], worst[0], between);
        for (int c = 0; c < 2; c++)
            gd_campbell_free(r[c]);
        free(sp);
        fx_free(&f);
    }
}

/* The planetary set of bench/bench_planetary.sh: five planets between two 20-element FE
 * shafts, whose translational pairs (double at rest) split under the carrier's Coriolis
 * terms by several Hz per speed step, so the members of a pair move past each other's
 * predictions within the passes of the continuation (sparse_track.c, each member's
 * reference its previous pass' Ritz value). */
static const char PLANETARY[] =
    "materials:\n"
    "  steel: {density: 7850, E: 210 GPa, poisson: 0.3}\n"
    "dofs: [x, y, rx, ry, rz]\n"
    "speed: 1000 rpm\n"
    "shafts:\n"
    "  - name: input\n"
    "    material: steel\n"
    "    sections: [{length: 0.4, outer_diameter: 40 mm, elements: 20}]\n"
    "    nodes: [{name: in0, at: 0}, {name: in1, at: 0.1}, {name: sun, at: 0.4}]\n"
    "  - name: output\n"
    "    material: steel\n"
    "    sections: [{length: 0.4, outer_diameter: 60 mm, elements: 20}]\n"
    "    nodes: [{name: carrier, at: 0}, {name: out1, at: 0.3}, {name: out2, at: 0.4}]\n"
    "  - {name: housing, nodes: [{name: ring}]}\n"
    "bearings:\n"
    "  - {node: in0, k: 1e9 N/m}\n"
    "  - {node: in1, k: 1e9 N/m}\n"
    "  - {node: out1, k: 1e9 N/m}\n"
    "  - {node: out2, k: 1e9 N/m}\n"
    "springs:\n"
    "  - {node: out2, dof: rz, stiffness: 1e4 N*m/rad}\n"
    "disks:\n"
    "  - {node: in0, mass: 5, polar_inertia: 0.02}\n"
    "  - {node: out2, mass: 8, polar_inertia: 0.05}\n"
    "  - {node: sun, mass: 0.5, polar_inertia: 1e-4}\n"
    "  - {node: carrier, mass: 3, polar_inertia: 0.01}\n"
    "planetary_sets:\n"
    "  - name: ps\n"
    "    held: ring\n"
    "    sun: {node: sun}\n"
    "    ring: {node: ring, mass: 2, inertia: 0.01, k_support: 1e8, k_torsion: 1e8}\n"
    "    carrier: {node: carrier}\n"
    "    planets: {count: 5, mass: 0.4, inertia: 1.5e-4, bearing_stiffness: 1e8}\n"
    "    teeth: {sun: 30, ring: 60, planet: 15}\n"
    "    base_radius: {sun: 28.1908 mm, ring: 56.3816 mm, planet: 14.0954 mm}\n"
    "    carrier_radius: 45 mm\n"
    "    pressure_angle: 20 deg\n"
    "    mesh_stiffness: {sun: 4e8, ring: 5e8}\n";

/* The continuation on the planetary set against the dense eigenvalues at every speed:
 * the 12 modes of each speed (5 split pairs among them) within 1e-9 (measured 2.3e-11
 * at most), every speed but the two chains' first ones continued (9 of 11: the bench's
 * sweep), no fallback to Krylov-Schur. */
TEST(continuation_planetary_pairs)
{
    fx f;
    REQUIRE(load(&f, NULL, PLANETARY));
    int ns = 11, nm = 12;
    double *sp = linspace(0, 314.159265358979, ns);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = ns;
    o.nmodes = nm;
    o.method = GD_EIG_SPARSE;
    o.nthreads = 1;
    gd_campbell_result *r;
    gd_campbell_stats st;
    gd_error err;
    REQUIRE(gd_campbell_run(f.s, &o, 1, &st, &r, &err) == GD_OK);
    printf("  planetary: %d of %d speeds continued, %d fallbacks\n", st.continued, ns,
           st.fallbacks);
    CHECK(st.continued == 9 && st.fallbacks == 0);
    double worst = 0;
    int compared = 0;
    for (int s = 0; s < ns; s++) {
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = sp[s];
        mo.nmodes = 0;
        mo.want_left = 0;
        mo.kind = GD_MODAL_DAMPED;
        mo.method = GD_EIG_DENSE;
        gd_modal_result *d;
        REQUIRE(gd_modal_solve(f.s, &mo, &d, &err) == GD_OK);
        for (int t = 0; t < r->ntracks; t++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + s];
            if (isnan(md->omega_n)) continue;
            double near = INFINITY;
            for (int q = 0; q < d->nmodes; q++)
                if (!d->modes[q].rigid_body)
                    near = fmin(near, hypot(d->modes[q].lambda_re - md->lambda_re,
                                            d->modes[q].lambda_im - md->lambda_im));
            worst = fmax(worst, near / md->omega_n);
            compared++;
        }
        gd_modal_free(d);
    }
    CHECK(compared == ns * nm);
    CHECK_ABS(worst, 0.0, 1e-9);
    printf("  planetary: |d lambda| / |lambda| from dense %.2e\n", worst);
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

TEST(threads_and_methods_agree)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    double *sp = linspace(0, 1256.6, 21);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 21;
    o.nmodes = 8;
    gd_campbell_result *r[4];
    gd_error err;
    for (int k = 0; k < 4; k++) {
        o.method = k < 2 ? GD_EIG_DENSE : GD_EIG_SPARSE;
        o.nthreads = k % 2 ? 3 : 1;
        REQUIRE(gd_campbell(f.s, &o, &r[k], &err) == GD_OK);
    }
    CHECK(!r[0]->sparse && r[2]->sparse);
    for (int k = 0; k < 4; k += 2) {
        REQUIRE(r[k]->ntracks == r[k + 1]->ntracks);
        size_t n = (size_t)r[k]->ntracks * 21;
        int same = 1;
        for (size_t i = 0; i < n; i++)
            same &=
                !memcmp(&r[k]->modes[i].lambda_re, &r[k + 1]->modes[i].lambda_re, sizeof(double)) &&
                !memcmp(&r[k]->modes[i].lambda_im, &r[k + 1]->modes[i].lambda_im, sizeof(double));
        CHECK(same);
        CHECK(r[k]->ncritical == r[k + 1]->ncritical);
    }
    REQUIRE(r[0]->ntracks == r[2]->ntracks);
    for (size_t i = 0; i < (size_t)r[0]->ntracks * 21; i++)
        CHECK_REL(r[2]->modes[i].omega_d, r[0]->modes[i].omega_d, 1e-9);
    CHECK(r[0]->ncritical == r[2]->ncritical);
    for (int k = 0; k < 4; k++)
        gd_campbell_free(r[k]);
    free(sp);
    fx_free(&f);
}

/* Every critical speed's mode frequency, solved directly at that speed, is within the
 * linear interpolation error of order x speed; orders come from the shafts (1x at their
 * ratios) and the mesh (48 teeth x driving shaft). */
TEST(critical_speeds)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    double *sp = linspace(0, 1256.6, 41);
    double user[1] = {2};
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 41;
    o.nmodes = 4;
    o.orders = user;
    o.norders = 1;
    gd_campbell_result *r;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(r->norders == 4); /* 1x driving (1), 1x driven (1.5), 2x, mesh 48x */
    CHECK_REL(r->orders[0].order, 1.0, 1e-12);
    CHECK_REL(r->orders[1].order, 1.5, 1e-12);
    CHECK_REL(r->orders[2].order, 2.0, 1e-12);
    CHECK_REL(r->orders[3].order, 48.0, 1e-12);
    CHECK_STR(r->orders[3].label, "mesh mesh 48x driving");
    REQUIRE(r->ncritical >= 8);
    for (int c = 0; c < r->ncritical; c++) {
        const gd_critical_speed *cs = &r->critical[c];
        CHECK_REL(cs->frequency_hz, r->orders[cs->order].order * cs->speed / (2 * M_PI), 1e-4);
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = cs->speed;
        mo.nmodes = 5;
        gd_modal_result *mr;
        REQUIRE(gd_modal_solve(f.s, &mo, &mr, &err) == GD_OK);
        double best = INFINITY;
        for (int j = 0; j < mr->nmodes; j++)
            best = fmin(best, fabs(mr->modes[j].omega_d / (2 * M_PI) - cs->frequency_hz));
        CHECK(best < 1e-4 * cs->frequency_hz);
        gd_modal_free(mr);
    }
    CHECK(isnan(r->instability_onset));
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

/* An oil-film bearing whose cross-coupled stiffness grows with speed destabilises the
 * forward mode: the onset is where the damping ratio crosses zero. */
static const char UNSTABLE[] =
    "dofs: [x, y]\n"
    "shafts:\n  - name: rotor\n    nodes: [{name: j}]\n"
    "disks:\n  - {name: d, node: j, mass: 10}\n"
    "bearings:\n  - name: oil\n    node: j\n    table:\n"
    "      - {speed: 0, k: 1e6, c: 200}\n"
    "      - {speed: 1000, kxx: 1e6, kyy: 1e6, kxy: 1e5, kyx: -1e5, c: 200}\n";

TEST(instability_onset)
{
    fx f;
    REQUIRE(load(&f, NULL, UNSTABLE));
    double *sp = linspace(0, 1000, 101);
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 101;
    o.nmodes = 2;
    gd_campbell_result *r;
    gd_error err;
    REQUIRE(gd_campbell(f.s, &o, &r, &err) == GD_OK);
    REQUIRE(!isnan(r->instability_onset));
    /* forward mode: Re lambda = -c/2m + kxy/(2 m w) with kxy = 100 W:  w ~ sqrt(k/m) =
     * 316.2, so the onset is at 100 W / (2 * 10 * 316.2) = 10, i.e. W = 632.5 rad/s */
    CHECK_REL(r->instability_onset, 632.5, 0.01);
    const gd_mode *md = r->modes + (size_t)(r->instability_track - 1) * 101;
    CHECK(md[100].damping_ratio < 0 && md[100].log_decrement < 0);
    CHECK(md[50].damping_ratio > 0);
    gd_campbell_free(r);
    free(sp);
    fx_free(&f);
}

TEST(mac_and_hungarian)
{
    double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, c[3] = {1, 1, 0}, ci[3] = {0, 0, 0};
    CHECK_ABS(gd_mac(a, NULL, b, NULL, 3), 0, 1e-15);
    CHECK_REL(gd_mac(a, NULL, c, ci, 3), 0.5, 1e-15);
    double zi[3] = {1, 0, 0}; /* a times (1 + i) */
    CHECK_REL(gd_mac(a, NULL, a, zi, 3), 1.0, 1e-15);
}

TEST(errors)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    double sp[3] = {0, 100, 50};
    gd_campbell_options o;
    gd_campbell_options_init(&o);
    o.speeds = sp;
    o.nspeeds = 3;
    gd_campbell_result *r = (gd_campbell_result *)1;
    gd_error err;
    CHECK(gd_campbell(f.s, &o, &r, &err) == GD_EINPUT && r == NULL);
    CHECK(strstr(err.message, "not above the previous") != NULL);
    o.nspeeds = 0;
    CHECK(gd_campbell(f.s, &o, &r, &err) == GD_EINPUT);
    o.nspeeds = 2;
    o.nmodes = 0;
    o.method = GD_EIG_SPARSE;
    CHECK(gd_campbell(f.s, &o, &r, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "lowest modes") != NULL);
    o.nmodes = -1;
    o.method = GD_EIG_AUTO;
    CHECK(gd_campbell(f.s, &o, &r, &err) == GD_EINPUT);
    fx_free(&f);
}

RUN_TESTS(T(sparse_equals_dense), T(warm_start_equals_cold), T(continuation_equals_reference),
          T(continuation_planetary_pairs), T(gyroscopic_forward_rises_backward_falls),
          T(threads_and_methods_agree), T(critical_speeds), T(instability_onset),
          T(mac_and_hungarian), T(errors))
