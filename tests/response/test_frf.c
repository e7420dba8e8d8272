/* Frequency response: direct against modal summation (rig2018, [MMT2018] Eqs. 14-15),
 * driving-point peaks at the modal frequencies, Kumar 2011's mesh force to a motor
 * torque ([Kumar2011] Fig. 3: torsion-only one tooth-mesh peak, coupled the lateral-torsional
 * split), directional FRFs of a gyroscopic rotor, threads, errors. */
#include <complex.h>
#include <stdlib.h>

#include "geardyn/frf.h"
#include "harness.h"
#include "model_support.h"

/* fx, load, fx_free, dof: tests/model_support.h */

static gd_probe probe_dof(int i)
{
    gd_probe p = {NULL, i, GD_X, "dof"};
    return p;
}

static double *linspace(double a, double b, int n)
{
    double *v = malloc((size_t)n * sizeof *v);
    for (int i = 0; i < n; i++)
        v[i] = n == 1 ? a : a + (b - a) * i / (n - 1);
    return v;
}

/* Frequencies of sharp peaks: local maxima at least 10x the values 1% (at least six
 * points) away on both sides. */
static int sharp_peaks(const gd_frf_result *r, int out, double *pk, int max)
{
    int n = 0, nf = r->nfreq;
    for (int i = 1; i < nf - 1; i++) {
        double m = hypot(r->re[(size_t)out * nf + i], r->im[(size_t)out * nf + i]);
        double a = hypot(r->re[(size_t)out * nf + i - 1], r->im[(size_t)out * nf + i - 1]);
        double b = hypot(r->re[(size_t)out * nf + i + 1], r->im[(size_t)out * nf + i + 1]);
        if (!(m > a && m > b)) continue;
        int k = i / 100 > 6 ? i / 100 : 6;
        if (i - k < 0 || i + k >= nf) continue;
        double l = hypot(r->re[(size_t)out * nf + i - k], r->im[(size_t)out * nf + i - k]);
        double u = hypot(r->re[(size_t)out * nf + i + k], r->im[(size_t)out * nf + i + k]);
        if (m >= 10 * l && m >= 10 * u && n < max) pk[n++] = r->freqs[i];
    }
    return n;
}

/* [MMT2018] Eqs. 14-15: the modal sum over left/right eigenvectors (all modes, the rigid
 * torsional mode added exactly) equals the direct solve to 1e-6 away from resonance,
 * for displacement, torsion (which the rigid mode dominates), mesh and bearing forces. */
TEST(rig_direct_equals_modal)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    double freqs[6] = {100, 400, 2500, 6000, 12000, 20000}; /* modes: 795, 854, ..., 4630 */
    int inputs[2] = {dof(&f, "gear48", GD_X), dof(&f, "gear48", GD_RZ)};
    gd_probe outs[5] = {probe_dof(dof(&f, "gear48", GD_X)),
                        probe_dof(dof(&f, "gear32", GD_Y)),
                        probe_dof(dof(&f, "gear32", GD_RZ)),
                        {&gd_element_mesh, 0, GD_X, "mesh"},
                        {&gd_element_bearing, 0, GD_X, "A1.x"}};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = freqs;
    o.nfreq = 6;
    o.speed = 314.159;
    o.inputs = inputs;
    o.ninputs = 2;
    o.outputs = outs;
    o.noutputs = 5;
    gd_frf_result *rd, *rm;
    gd_error err;
    REQUIRE(gd_frf(f.s, &o, &rd, &err) == GD_OK);
    o.method = GD_FRF_MODAL;
    REQUIRE(gd_frf(f.s, &o, &rm, &err) == GD_OK);
    CHECK(rm->nrigid == 1);
    CHECK(rm->nmodes_used == f.s->ndof - 1);
    double worst = 0;
    for (size_t k = 0; k < (size_t)6 * 2 * 5; k++) {
        double complex a = rd->re[k] + I * rd->im[k], b = rm->re[k] + I * rm->im[k];
        CHECK(cabs(a) > 0);
        double e = cabs(a - b) / cabs(a);
        if (e > worst) worst = e;
    }
    CHECK(worst < 1e-6);
    printf("  direct vs modal, worst relative difference %.2e\n", worst);
    /* truncating the modal sum is an approximation, and a visible one */
    o.nmodes = 6;
    gd_frf_result *rt;
    REQUIRE(gd_frf(f.s, &o, &rt, &err) == GD_OK);
    CHECK(rt->nmodes_used == 5);
    double diff = 0;
    for (size_t k = 0; k < (size_t)6 * 2 * 5; k++)
        diff = fmax(diff, cabs((rd->re[k] - rt->re[k]) + I * (rd->im[k] - rt->im[k])) /
                              cabs(rd->re[k] + I * rd->im[k]));
    CHECK(diff > 1e-4);
    gd_frf_free(rt);
    gd_frf_free(rd);
    gd_frf_free(rm);
    fx_free(&f);
}

/* The driving-point receptance of gear48.x peaks at the damped frequencies of the
 * modes that move gear48 in x. */
TEST(rig_driving_point_peaks_at_modes)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.nmodes = 12;
    gd_modal_result *mr;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &mo, &mr, &err) == GD_OK);
    int in = dof(&f, "gear48", GD_X);
    double *fr = linspace(600, 10000, 47001); /* 0.2 rad/s steps */
    gd_probe out = probe_dof(in);
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = 47001;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = &out;
    o.noutputs = 1;
    gd_frf_result *r;
    REQUIRE(gd_frf(f.s, &o, &r, &err) == GD_OK);
    double pk[64], hmax = 0;
    int np = sharp_peaks(r, 0, pk, 64);
    for (int i = 0; i < r->nfreq; i++)
        hmax = fmax(hmax, hypot(r->re[i], r->im[i]));
    int matched = 0;
    for (int j = 0; j < mr->nmodes; j++) {
        const gd_mode *md = &mr->modes[j];
        double part = cabs(mr->shape_re[in + (size_t)j * f.s->ndof] +
                           I * mr->shape_im[in + (size_t)j * f.s->ndof]) *
                      cabs(mr->left_re[in + (size_t)j * f.s->ndof] +
                           I * mr->left_im[in + (size_t)j * f.s->ndof]);
        /* modes whose own resonance |u v| / |Re lambda| stands out of the FRF */
        if (md->rigid_body || md->omega_d > 10000 || part / fabs(md->lambda_re) < 0.01 * hmax)
            continue;
        /* a local maximum of |H| within 1 rad/s of the damped frequency */
        int near = 0;
        for (int i = 1; i + 1 < r->nfreq; i++) {
            if (fabs(fr[i] - md->omega_d) > 1.0) continue;
            double a = hypot(r->re[i - 1], r->im[i - 1]), b = hypot(r->re[i], r->im[i]),
                   c = hypot(r->re[i + 1], r->im[i + 1]);
            near |= b > a && b > c;
        }
        CHECK(near);
        matched += near;
    }
    for (int k = 0; k < np; k++) { /* and every sharp peak is a mode */
        int near = 0;
        for (int j = 0; j < mr->nmodes; j++)
            near |= fabs(pk[k] - mr->modes[j].omega_d) < 1.0;
        CHECK(near);
    }
    CHECK(matched >= 3 && np >= 4);
    printf("  %d sharp peaks, %d matched to modes\n", np, matched);
    gd_frf_free(r);
    gd_modal_free(mr);
    free(fr);
    fx_free(&f);
}

/* [Kumar2011] Fig. 3: mesh force per 1 N m of motor torque, 0-26000 rad/s. Torsion only: peaks
 * at the two low modes and one tooth-mesh peak (25543 rad/s); coupled: the low modes and
 * 23288 in that band, and over 0-60000 the split into three coupled modes (23288,
 * 40462, 57295) while the pure x modes (38660, 54673) give no peak. */
static int kumar_peaks(const char *path, double top, double *pk)
{
    fx f;
    if (!load(&f, path, NULL)) return -1;
    int nf = (int)top + 1;
    double *fr = linspace(0, top, nf);
    int in = dof(&f, "motor", GD_RZ);
    gd_probe out = {&gd_element_mesh, 0, GD_X, "mesh"};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = nf;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = &out;
    o.noutputs = 1;
    gd_frf_result *r;
    gd_error err;
    int n = -1;
    if (gd_frf(f.s, &o, &r, &err) == GD_OK) {
        n = sharp_peaks(r, 0, pk, 16);
        if (r->nsingular != 1 || !r->singular[0]) n = -2; /* rigid body at 0 only */
        gd_frf_free(r);
    }
    free(fr);
    fx_free(&f);
    return n;
}

TEST(kumar_mesh_force_fig3)
{
    double pk[16];
    int n = kumar_peaks("examples/kumar2011_torsional.yaml", 26000, pk);
    REQUIRE(n == 3);
    CHECK_ABS(pk[0], 122.3, 1.0);
    CHECK_ABS(pk[1], 308.0, 1.0);
    CHECK_ABS(pk[2], 25542.7, 1.0);
    n = kumar_peaks("examples/kumar2011_coupled.yaml", 26000, pk);
    REQUIRE(n == 3);
    CHECK_ABS(pk[0], 122.3, 1.0);
    CHECK_ABS(pk[1], 308.0, 1.0);
    CHECK_ABS(pk[2], 23288.5, 1.0);
    n = kumar_peaks("examples/kumar2011_coupled.yaml", 60000, pk);
    REQUIRE(n == 5);
    CHECK_ABS(pk[2], 23288.5, 1.0);
    CHECK_ABS(pk[3], 40461.7, 1.0);
    CHECK_ABS(pk[4], 57294.9, 1.0);
}

/* A gyroscopic rotor on isotropic bearings: the forward dFRF peaks at the forward
 * whirl mode only and the backward dFRF at the backward one. */
static const char ROTOR[] =
    "dofs: [x, y, rx, ry]\n"
    "materials:\n  steel: {density: 7800, E: 2.1e11, poisson: 0.3}\n"
    "shafts:\n  - name: rotor\n    material: steel\n    elements_per_section: 6\n"
    "    sections: [{length: 0.6, outer_diameter: 0.03}]\n"
    "    nodes: [{name: b1, at: 0}, {name: disk, at: 0.45}, {name: b2, at: 0.6}]\n"
    "disks:\n  - {name: disk, node: disk, mass: 8, polar_inertia: 0.12, diametral_inertia: 0.06}\n"
    "bearings:\n  - {name: B1, node: b1, k: 2e6, c: 30}\n  - {name: B2, node: b2, k: 2e6, c: 30}\n";

TEST(directional_frf_separates_forward_and_backward)
{
    fx f;
    REQUIRE(load(&f, NULL, ROTOR));
    double W = 2000;
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.speed = W;
    mo.nmodes = 2;
    gd_modal_result *mr;
    gd_error err;
    REQUIRE(gd_modal_solve(f.s, &mo, &mr, &err) == GD_OK);
    REQUIRE(mr->modes[0].whirl == GD_WHIRL_BACKWARD && mr->modes[1].whirl == GD_WHIRL_FORWARD);
    double wb = mr->modes[0].omega_d, wf = mr->modes[1].omega_d;
    CHECK(wf > 1.05 * wb);
    int in[2] = {dof(&f, "disk", GD_X), dof(&f, "disk", GD_Y)};
    gd_probe out[2] = {probe_dof(in[0]), probe_dof(in[1])};
    double fr[2] = {wb, wf};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = 2;
    o.speed = W;
    o.inputs = in;
    o.ninputs = 2;
    o.outputs = out;
    o.noutputs = 2;
    gd_frf_result *r;
    REQUIRE(gd_frf(f.s, &o, &r, &err) == GD_OK);
    double fre[2], fim[2], bre[2], bim[2];
    gd_frf_directional(r, 0, 1, fre, fim, bre, bim);
    /* at the backward frequency the backward dFRF dominates, at the forward the forward */
    CHECK(hypot(bre[0], bim[0]) > 20 * hypot(fre[0], fim[0]));
    CHECK(hypot(fre[1], fim[1]) > 20 * hypot(bre[1], bim[1]));
    /* isotropic: H_f + H_b = H_xx + H_yy */
    CHECK_REL(fre[1] + bre[1], r->re[1 * 0 + 0 * 2 + 1] + r->re[(1 * 2 + 1) * 2 + 1], 1e-12);
    gd_frf_free(r);
    gd_modal_free(mr);
    fx_free(&f);
}

/* Mobility and accelerance are i w and -w^2 times the receptance. */
TEST(quantities_scale_by_iw)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    int in = dof(&f, "gear_a", GD_X);
    gd_probe out = probe_dof(dof(&f, "gear_b", GD_RZ));
    double fr[1] = {900};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = 1;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = &out;
    o.noutputs = 1;
    gd_frf_result *r[3];
    gd_error err;
    for (int q = 0; q < 3; q++) {
        o.quantity = (gd_frf_quantity)q;
        REQUIRE(gd_frf(f.s, &o, &r[q], &err) == GD_OK);
    }
    double complex h = r[0]->re[0] + I * r[0]->im[0];
    CHECK(cabs(h) > 0);
    CHECK_REL(r[1]->re[0], creal(I * 900 * h), 1e-12);
    CHECK_REL(r[1]->im[0], cimag(I * 900 * h), 1e-12);
    CHECK_REL(r[2]->re[0], -900.0 * 900 * creal(h), 1e-12);
    for (int q = 0; q < 3; q++)
        gd_frf_free(r[q]);
    fx_free(&f);
}

TEST(threads_give_identical_results)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    double *fr = linspace(0, 20000, 401);
    int in = dof(&f, "gear32", GD_Y);
    gd_probe out[2] = {probe_dof(dof(&f, "gear48", GD_Y)), {&gd_element_mesh, 0, GD_X, "mesh"}};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = 401;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = out;
    o.noutputs = 2;
    o.speed = 500;
    gd_frf_result *a, *b;
    gd_error err;
    o.nthreads = 1;
    REQUIRE(gd_frf(f.s, &o, &a, &err) == GD_OK);
    o.nthreads = 3;
    REQUIRE(gd_frf(f.s, &o, &b, &err) == GD_OK);
    CHECK(a->nsingular == 1 && a->singular[0]); /* the rigid torsional mode at 0 */
    CHECK(!memcmp(a->re + 1, b->re + 1, (2 * 401 - 1) * sizeof(double)));
    CHECK(!memcmp(a->im + 1, b->im + 1, (2 * 401 - 1) * sizeof(double)));
    gd_frf_free(a);
    gd_frf_free(b);
    free(fr);
    fx_free(&f);
}

/* The mesh-force probe uses the damping the system assembles: with damping
 * proportional to stiffness (per_stiffness 1e-5 s on the Chen gear pair, c = 384.35 +
 * 1e-5 k_m), the probe's force equals (k + i w c) a . u computed from the
 * displacement FRFs of the same run. Before the element registry the probe took the
 * constant damping alone and was 1% off at 1000 rad/s. */
TEST(mesh_force_probe_uses_assembled_damping)
{
    fx f;
    REQUIRE(load(&f, "examples/chen1998_gear_pair.yaml", NULL));
    gd_system_free(f.s);
    f.m->meshes[0].dyn.damping_per_stiffness = 1e-5;
    gd_error err;
    REQUIRE(gd_system_build(f.m, &f.s, &err) == GD_OK);
    const gd_mesh *g = &f.m->meshes[0];
    double c = g->damping + 1e-5 * g->stiffness;
    CHECK_REL(gd_mesh_linear_damping(g), c, 1e-15);
    gd_mesh_vector a;
    gd_system_mesh_vector(f.s, 0, &a);
    REQUIRE(a.n > 0);
    gd_probe outs[13];
    outs[0] = (gd_probe){&gd_element_mesh, 0, GD_X, "mesh"};
    for (int j = 0; j < a.n; j++)
        outs[1 + j] = probe_dof(a.dof[j]);
    int in = dof(&f, "gear_a", GD_RZ);
    double freqs[3] = {300, 1000, 4000};
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = freqs;
    o.nfreq = 3;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = outs;
    o.noutputs = 1 + a.n;
    gd_frf_result *r;
    REQUIRE(gd_frf(f.s, &o, &r, &err) == GD_OK);
    for (int q = 0; q < 3; q++) {
        double complex d = 0;
        for (int j = 0; j < a.n; j++)
            d += a.a[j] * (r->re[(size_t)(1 + j) * 3 + q] + I * r->im[(size_t)(1 + j) * 3 + q]);
        double complex want = (g->stiffness + I * freqs[q] * c) * d;
        double complex got = r->re[q] + I * r->im[q];
        CHECK_ABS(cabs(got - want) / cabs(want), 0, 1e-12);
    }
    gd_frf_free(r);
    fx_free(&f);
}

TEST(errors)
{
    fx f;
    REQUIRE(load(&f, "examples/rig2018.yaml", NULL));
    int in = 0;
    double fr[2] = {10, -1};
    gd_probe out = probe_dof(0);
    gd_frf_options o;
    gd_frf_options_init(&o);
    o.freqs = fr;
    o.nfreq = 2;
    o.inputs = &in;
    o.ninputs = 1;
    o.outputs = &out;
    o.noutputs = 1;
    gd_frf_result *r = (gd_frf_result *)1;
    gd_error err;
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT && r == NULL);
    CHECK(strstr(err.message, "negative") != NULL);
    o.nfreq = 0;
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT);
    o.nfreq = 1;
    in = f.s->ndof;
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT);
    in = 0;
    out.index = f.s->ndof + 3;
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT);
    out = (gd_probe){&gd_element_mesh, 4, GD_X, "m"};
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT);
    o.ninputs = 0;
    CHECK(gd_frf(f.s, &o, &r, &err) == GD_EINPUT);
    fx_free(&f);
}

RUN_TESTS(T(rig_direct_equals_modal), T(rig_driving_point_peaks_at_modes), T(kumar_mesh_force_fig3),
          T(directional_frf_separates_forward_and_backward), T(quantities_scale_by_iw),
          T(threads_give_identical_results), T(mesh_force_probe_uses_assembled_damping), T(errors))
