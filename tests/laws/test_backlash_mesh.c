/* The gear mesh as a registry law (gd_law_backlash_mesh, src/laws/backlash_mesh.c): its
 * force is the backlash law of [Benini2004] Eqs. 2-4 at the TVMS and STE of the driver's
 * angle, less the assembled linear part; its Jacobian terms match central differences in
 * every contact mode; its switches, modes, records, frequencies and flags say what the
 * integrators need. */
#include <math.h>
#include <string.h>

#include "geardyn/laws.h"
#include "harness.h"

/* A mesh on three local DOFs (say x of the pinion, rz of the pinion, rz of the gear; the
 * driver's rz is local DOF 1), a spline TVMS over one mesh period (20 teeth), a sinusoidal
 * STE, backlash 20 um. */
typedef struct sample {
    gd_table *tvms, *ste;
    gd_mesh_law_data m;
    gd_law L;
} sample;

static void sample_make(sample *s, gd_test_state *gd_ts_)
{
    const double P = 2.0 * M_PI / 20.0;
    double x[8], k[8], e[8];
    for (int i = 0; i < 8; i++) {
        x[i] = P * i / 8.0;
        k[i] = 2e8 * (1.0 + 0.2 * cos(2.0 * M_PI * i / 8.0));
        e[i] = 4e-6 * sin(2.0 * M_PI * i / 8.0);
    }
    gd_error err;
    REQUIRE(gd_table_new(8, x, k, P, GD_INTERP_SPLINE, &s->tvms, &err) == GD_OK);
    REQUIRE(gd_table_new(8, x, e, P, GD_INTERP_SPLINE, &s->ste, &err) == GD_OK);
    memset(&s->m, 0, sizeof s->m);
    s->m = (gd_mesh_law_data){.tvms = s->tvms,
                              .ste = s->ste,
                              .stiffness = 2e8,
                              .coast_scale = 0.8,
                              .damping = 300.0,
                              .damping_per_k = 2e-6,
                              .damping_free = 20.0,
                              .backlash = 1,
                              .gap = 2e-5,
                              .angle_offset = 0.01,
                              .na = 3,
                              .a = {0.34, 0.03, -0.06},
                              .drv = 1,
                              .sense = 1,
                              .drv_rate = 150.0,
                              .k_lin = 2e8,
                              .c_lin = 700.0};
    gd_law_init(&s->L, &gd_law_backlash_mesh, "mesh");
    s->L.ndofs = 3;
    for (int j = 0; j < 3; j++)
        s->L.dof[j] = j;
    s->L.data = &s->m;
    s->L.mode = GD_CONTACT_DRIVE;
}

static void sample_free(sample *s)
{
    gd_table_free(s->tvms);
    gd_table_free(s->ste);
}

static void force_at(const gd_law *L, double t, const double *q, const double *v, double *f)
{
    memset(f, 0, 3 * sizeof *f);
    gd_law_point x = {t, q, v};
    L->type->force(L, &x, f, NULL, NULL);
}

TEST(force_is_backlash_law_less_assembled_part)
{
    sample s;
    sample_make(&s, gd_ts_);
    gd_error err;
    REQUIRE(gd_law_check(&s.L, &err) == GD_OK);
    const double t = 0.0123, q[3] = {1e-5, 2e-4, -1e-4}, v[3] = {0.01, 0.3, -0.2};
    const gd_mesh_law_data *m = &s.m;
    /* by hand: angle, k(theta), e(theta), d, d', the flank's force */
    double th = m->angle_offset + (m->drv_rate * t + q[1]), thd = m->drv_rate + v[1];
    double e1, k = gd_table_eval(m->tvms, th, NULL, NULL), e = gd_table_eval(m->ste, th, &e1, NULL);
    double d = 0, dd = 0;
    for (int j = 0; j < 3; j++)
        d += m->a[j] * q[j], dd += m->a[j] * v[j];
    gd_backlash_params p = {.b = m->gap,
                            .k_drive = k,
                            .k_coast = m->coast_scale * k,
                            .c_drive = m->damping + m->damping_per_k * k,
                            .c_coast = m->damping + m->damping_per_k * m->coast_scale * k,
                            .c_free = m->damping_free};
    for (int mode = -1; mode <= 1; mode++) {
        s.L.mode = mode;
        double F = gd_backlash_force(&p, (gd_contact)mode, d - e, dd - e1 * thd);
        double g = F - m->k_lin * d - m->c_lin * dd, f[3];
        force_at(&s.L, t, q, v, f);
        /* the same sums in the same order: equal to rounding */
        for (int j = 0; j < 3; j++)
            CHECK_REL(f[j], -m->a[j] * g, 1e-12);
        gd_law_point x = {t, q, v};
        CHECK_REL(s.L.type->record(&s.L, GD_MESH_REC_FORCE, &x), F, 1e-13);
        CHECK(s.L.type->record(&s.L, GD_MESH_REC_DEFLECTION, &x) == d);
        CHECK(s.L.type->record(&s.L, GD_MESH_REC_STATE, &x) == mode);
        CHECK(s.L.type->record(&s.L, GD_MESH_REC_STIFFNESS, &x) == k);
        /* the switches are d_e -+ b */
        double sw[2];
        s.L.type->switches(&s.L, &x, sw);
        CHECK_REL(sw[0], d - e - m->gap, 1e-12);
        CHECK_REL(sw[1], d - e + m->gap, 1e-12);
    }
    /* one-sided contact: the coast mode acts as separated (c_free only) */
    s.m.coast_scale = 0.0;
    s.L.mode = GD_CONTACT_COAST;
    gd_law_point x = {t, q, v};
    CHECK_REL(s.L.type->record(&s.L, GD_MESH_REC_FORCE, &x), m->damping_free * (dd - e1 * thd),
              1e-13);
    /* the hold blends with the drive flank */
    s.m.coast_scale = 0.8;
    s.L.mode = GD_CONTACT_SEPARATED;
    s.L.hold = 0.25;
    double Fs = gd_backlash_force(&p, GD_CONTACT_SEPARATED, d - e, dd - e1 * thd);
    double Fd = gd_backlash_force(&p, GD_CONTACT_DRIVE, d - e, dd - e1 * thd);
    CHECK_REL(s.L.type->record(&s.L, GD_MESH_REC_FORCE, &x), 0.75 * Fs + 0.25 * Fd, 1e-13);
    sample_free(&s);
}

TEST(jacobian_terms_match_differences_in_every_mode)
{
    sample s;
    sample_make(&s, gd_ts_);
    const gd_law_type *T = s.L.type;
    const double t = 0.0071;
    for (int mode = -1; mode <= 1; mode++) {
        s.L.mode = mode;
        double q[3] = {2e-5, 1e-4, -3e-4}, v[3] = {0.02, 0.1, -0.3}, f[3] = {0};
        double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS];
        gd_law_point x = {t, q, v};
        T->force(&s.L, &x, f, jq, jv);
        double Jq[9] = {0}, Jv[9] = {0};
        for (int k = 0; k < T->nterms; k++) {
            double u[GD_LAW_MAX_DOFS] = {0}, w[GD_LAW_MAX_DOFS] = {0};
            T->term(&s.L, k, u, w);
            for (int a = 0; a < 3; a++)
                for (int b = 0; b < 3; b++) {
                    Jq[a + 3 * b] += jq[k] * u[a] * w[b];
                    Jv[a + 3 * b] += jv[k] * u[a] * w[b];
                }
        }
        /* central differences (the spline is smooth between its knots): 1e-6 of the
         * largest entry */
        for (int b = 0; b < 3; b++)
            for (int pass = 0; pass < 2; pass++) {
                double *x0 = pass ? v : q, h = pass ? 1e-6 : 1e-9, keep = x0[b], fp[3], fm[3];
                x0[b] = keep + h;
                force_at(&s.L, t, q, v, fp);
                x0[b] = keep - h;
                force_at(&s.L, t, q, v, fm);
                x0[b] = keep;
                double *J = pass ? Jv : Jq, scale = 0;
                for (int i = 0; i < 9; i++)
                    scale = fmax(scale, fabs(J[i]));
                for (int a = 0; a < 3; a++)
                    CHECK_ABS(J[a + 3 * b], (fp[a] - fm[a]) / (2 * h), 1e-6 * scale);
            }
    }
    sample_free(&s);
}

TEST(modes_switches_frequencies_and_flags)
{
    sample s;
    sample_make(&s, gd_ts_);
    const gd_law_type *T = s.L.type;
    CHECK(gd_law_nswitches(&s.L) == 2);
    /* CVODE's root directions to the new flank */
    int up0[2] = {1, 0}, down0[2] = {-1, 0}, down1[2] = {0, -1}, up1[2] = {0, 1}, none[2] = {0, 0};
    CHECK(T->mode_after(&s.L, GD_CONTACT_SEPARATED, up0) == GD_CONTACT_DRIVE);
    CHECK(T->mode_after(&s.L, GD_CONTACT_DRIVE, down0) == GD_CONTACT_SEPARATED);
    CHECK(T->mode_after(&s.L, GD_CONTACT_SEPARATED, down1) == GD_CONTACT_COAST);
    CHECK(T->mode_after(&s.L, GD_CONTACT_COAST, up1) == GD_CONTACT_SEPARATED);
    CHECK(T->mode_after(&s.L, GD_CONTACT_COAST, none) == GD_CONTACT_COAST);
    CHECK(T->switch_of(&s.L, GD_CONTACT_DRIVE, GD_CONTACT_SEPARATED) == 0);
    CHECK(T->switch_of(&s.L, GD_CONTACT_SEPARATED, GD_CONTACT_COAST) == 1);
    /* the mode from the motion: beyond the drive-side gap */
    double q[3] = {0, 0, 0}, v[3] = {0, 0, 0};
    q[0] = 1e-4 / s.m.a[0]; /* d = 1e-4 >> b + |e| */
    gd_law_point x = {0, q, v};
    CHECK(T->mode_at(&s.L, &x) == GD_CONTACT_DRIVE);
    q[0] = -q[0];
    CHECK(T->mode_at(&s.L, &x) == GD_CONTACT_COAST);
    /* a static equilibrium on the drive flank that pulls moves to the coast flank */
    s.L.mode = GD_CONTACT_DRIVE;
    CHECK(T->static_mode(&s.L, &x) == GD_CONTACT_COAST);
    /* TVMS and STE of one mesh period each: the mesh frequency, twice */
    double w[4];
    char msg[80];
    CHECK(T->frequencies(&s.L, w, 4, msg, sizeof msg) == 2);
    CHECK_REL(w[0], 20.0 * 150.0, 1e-12);
    CHECK_REL(w[1], 20.0 * 150.0, 1e-12);
    /* flags: nonlinear, tangent update, angle from a free driver (not piecewise) */
    unsigned f = gd_law_flags(&s.L);
    CHECK((f & GD_LAW_ASSEMBLED) && (f & GD_LAW_TANGENT));
    CHECK(!(f & GD_LAW_LINEAR) && !(f & GD_LAW_PIECEWISE) && !(f & GD_LAW_SMOOTH));
    s.m.angle_fixed = 1;
    CHECK(gd_law_flags(&s.L) & GD_LAW_PIECEWISE);
    /* a mesh at its assembled stiffness: linear, smooth, no switch, no tangent */
    s.m.tvms = s.m.ste = NULL;
    s.m.backlash = 0;
    s.m.c_lin = s.m.damping + s.m.damping_per_k * s.m.stiffness;
    f = gd_law_flags(&s.L);
    CHECK((f & GD_LAW_LINEAR) && (f & GD_LAW_SMOOTH) && !(f & GD_LAW_TANGENT));
    CHECK(gd_law_nswitches(&s.L) == 0);
    CHECK(T->frequencies(&s.L, w, 4, msg, sizeof msg) == 0);
    sample_free(&s);
}

RUN_TESTS(T(force_is_backlash_law_less_assembled_part),
          T(jacobian_terms_match_differences_in_every_mode),
          T(modes_switches_frequencies_and_flags))
