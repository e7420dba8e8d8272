/* The law registry (include/geardyn/law_type.h): every built-in type's table is valid,
 * its Jacobian terms reproduce central differences of its force, its linearisation is
 * minus the same Jacobian, its records and checks behave; a user-defined type is
 * accepted through the same calls. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/laws.h"
#include "harness.h"

TEST(registry_tables_are_valid)
{
    CHECK(gd_nlaw_types == 12);
    for (int i = 0; i < gd_nlaw_types; i++) {
        const gd_law_type *t = gd_law_types[i];
        gd_error err;
        CHECK(gd_law_type_validate(t, &err) == GD_OK);
        CHECK(gd_law_type_find(t->name) == t);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(gd_law_types[j]->name, t->name) != 0);
        for (int k = 0; k < t->nrecords; k++)
            CHECK(gd_law_record_index(t, t->records[k].name) == k);
        for (int k = 0; k < t->nparams; k++)
            CHECK(gd_law_param_index(t, t->params[k].name) == k);
    }
    CHECK(gd_law_type_find("journal_bearing_that_does_not_exist") == NULL);
    CHECK(gd_law_type_find(NULL) == NULL);
}

/* An instance of each built-in type with parameters that make every term matter. */
static gd_load_law harmonic_angle_load = {
    .kind = GD_LOAD_HARMONIC_ANGLE, .mean = 3.0, .amplitude = 2.0, .frequency = 3.0, .phase = 0.4};

static void sample_law(const gd_law_type *t, gd_law *L)
{
    gd_law_init(L, t, "sample");
    if (t == &gd_law_sfd) {
        gd_sfd_params p = {.viscosity = 6.9e-3,
                           .radius = 0.0178,
                           .length = 0.0171,
                           .clearance = 7.6e-5,
                           .film = GD_SFD_PI_FILM};
        gd_sfd_law_values(&p, L);
    } else if (t == &gd_law_load) {
        L->data = &harmonic_angle_load;
        L->rate[0] = 50.0;
    } else if (t == &gd_law_polynomial_spring) {
        L->value[0] = 2e6, L->value[1] = -3e9, L->value[2] = 4e13, L->value[3] = 35.0;
    } else if (t == &gd_law_friction) {
        L->value[0] = 40.0, L->value[1] = 0.02;
    } else if (t == &gd_law_journal_bearing) {
        L->value[0] = 0.02, L->value[1] = 0.05, L->value[2] = 0.02, L->value[3] = 1e-4;
        L->spin[0] = 400.0;
    } else if (t == &gd_law_rolling_bearing) {
        /* 9 balls, clearance 10 um, cage turning: a few elements in contact */
        L->value[0] = 9, L->value[1] = 1e10, L->value[3] = 1e-5, L->value[4] = 0.05;
        L->value[5] = 0.01, L->value[7] = 50.0, L->spin[0] = 300.0;
    } else if (t == &gd_law_rolling_bearing_5dof) {
        /* a 6205-size ball bearing, 2 um clearance, damped, cage turning */
        L->value[0] = 9, L->value[1] = 7.94e-3, L->value[2] = 39.04e-3, L->value[4] = 2e-6;
        L->value[12] = 50.0, L->spin[0] = 300.0;
    } else if (t == &gd_law_unilateral_spring) {
        /* in contact at the sample point (d = 4.5e-5 > gap) */
        L->value[0] = 3e7, L->value[1] = 1e-5, L->value[2] = 25.0;
    } else if (t == &gd_law_churning_drag) {
        /* an idler at 150 rad/s, half immersed, with a face wall: both terms matter */
        L->value[0] = 0.04, L->value[2] = 0.04, L->value[3] = 0.015, L->value[4] = 0.02;
        L->value[7] = 2e-3;
        L->rate[0] = 150.0, L->rate[1] = 20.0;
    } else if (t == &gd_law_bearing_drag) {
        /* a needle bearing at nu n well above 2000 with a load term */
        L->value[0] = 3.0, L->value[1] = 0.035, L->value[2] = 0.04, L->value[4] = 5e-4;
        L->value[5] = 800.0;
        L->rate[0] = 150.0, L->rate[1] = 20.0;
    } else if (t == &gd_law_synchro_cone) {
        /* locked after its shift at 0.01 s: the viscous lock's Jacobian */
        L->value[0] = 0.01, L->value[1] = 9.7, L->value[2] = 500.0;
        L->mode = 2;
    } else if (t == &gd_law_gear_release) {
        /* released at 0.01 s: the opposite of the lock spring */
        L->value[0] = 0.01, L->value[1] = 1e6, L->value[2] = 2.0;
        L->mode = 1;
    }
}

/* A motion point of the law's local DOFs at a scale that suits it. */
static void sample_point(const gd_law *L, double *q, double *v)
{
    int film = L->type == &gd_law_sfd || L->type == &gd_law_journal_bearing;
    double sq = film ? 3e-5 : (L->type == &gd_law_load ? 0.3 : 1e-4);
    if (L->type == &gd_law_rolling_bearing_5dof) sq = 1e-6; /* a few um beyond the clearance */
    double sv = film ? 2e-3 : (L->type == &gd_law_friction ? 0.015 : 0.05);
    for (int j = 0; j < L->ndofs; j++) {
        q[j] = sq * (0.7 - 0.45 * j + 0.2 * j * j);
        v[j] = sv * (0.3 + 0.55 * j - 0.3 * j * j);
    }
}

static void eval(const gd_law *L, double t, const double *q, const double *v, double *f)
{
    memset(f, 0, (size_t)L->ndofs * sizeof *f);
    gd_law_point x = {t, q, v};
    L->type->force(L, &x, f, NULL, NULL);
}

TEST(jacobian_terms_match_differences)
{
    for (int i = 0; i < gd_nlaw_types; i++) {
        gd_law L;
        sample_law(gd_law_types[i], &L);
        gd_error err;
        REQUIRE(gd_law_check(&L, &err) == GD_OK);
        const gd_law_type *t = L.type;
        int n = L.ndofs;
        double q[GD_LAW_MAX_DOFS], v[GD_LAW_MAX_DOFS], f[GD_LAW_MAX_DOFS];
        double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS];
        sample_point(&L, q, v);
        memset(f, 0, sizeof f);
        gd_law_point x = {0.013, q, v};
        t->force(&L, &x, f, jq, jv);
        /* the same force without the Jacobian */
        double f2[GD_LAW_MAX_DOFS];
        eval(&L, 0.013, q, v, f2);
        for (int a = 0; a < n; a++)
            CHECK(f[a] == f2[a]);
        /* assembled Jacobians from the terms */
        double Jq[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS] = {0},
                                    Jv[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS] = {0};
        for (int k = 0; k < t->nterms; k++) {
            double u[GD_LAW_MAX_DOFS] = {0}, w[GD_LAW_MAX_DOFS] = {0};
            t->term(&L, k, u, w);
            for (int a = 0; a < n; a++)
                for (int b = 0; b < n; b++) {
                    Jq[a + n * b] += jq[k] * u[a] * w[b];
                    Jv[a + n * b] += jv[k] * u[a] * w[b];
                }
        }
        /* central differences, column by column; the damper's own Jacobian is itself a
         * difference (steps 1e-6 of its scales), hence its looser tolerance */
        double tol = t == &gd_law_sfd || t == &gd_law_journal_bearing ? 1e-5 : 1e-7;
        for (int b = 0; b < n; b++)
            for (int pass = 0; pass < 2; pass++) {
                double *x0 = pass ? v : q, h = 1e-6 * (fabs(x0[b]) + 1e-3 * (pass ? 0.05 : 1e-4));
                double fp[GD_LAW_MAX_DOFS], fm[GD_LAW_MAX_DOFS], keep = x0[b];
                x0[b] = keep + h;
                eval(&L, 0.013, q, v, fp);
                x0[b] = keep - h;
                eval(&L, 0.013, q, v, fm);
                x0[b] = keep;
                double scale = 0, fbig = 0;
                for (int a = 0; a < n; a++) {
                    scale = fmax(scale, fabs((pass ? Jv : Jq)[a + n * b]));
                    fbig = fmax(fbig, fabs(fp[a]));
                }
                /* the difference's own rounding, 1e-16 |f| / h, bounds it from below */
                double floor = 1e-14 * fbig / h;
                for (int a = 0; a < n; a++) {
                    double fd = (fp[a] - fm[a]) / (2 * h);
                    CHECK_ABS((pass ? Jv : Jq)[a + n * b], fd,
                              tol * (scale > 0 ? scale : 1.0) + floor);
                }
            }
        /* the linearisation is minus the Jacobian */
        if (t->linearize) {
            double K[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS] = {0},
                                       C[GD_LAW_MAX_DOFS * GD_LAW_MAX_DOFS] = {0};
            t->linearize(&L, &x, K, C);
            for (int a = 0; a < n * n; a++) {
                CHECK_ABS(K[a], -Jq[a], 1e-12 * (fabs(Jq[a]) + 1e-300) + 1e-9 * fabs(Jq[0]));
                if (t == &gd_law_sfd || t == &gd_law_load) continue;
                CHECK_ABS(C[a], -Jv[a], 1e-12 * fabs(Jv[a]) + 1e-300);
            }
        }
    }
}

TEST(polynomial_spring_and_friction_values)
{
    gd_law L;
    gd_law_init(&L, &gd_law_polynomial_spring, "s");
    L.value[0] = 1.0, L.value[2] = 0.1, L.value[3] = 0.05;
    double q[2] = {2.0, 0.5}, v[2] = {0.3, 0.1}, f[2] = {0};
    gd_law_point x = {0, q, v};
    gd_law_polynomial_spring.force(&L, &x, f, NULL, NULL);
    double F = 1.5 + 0.1 * 1.5 * 1.5 * 1.5 + 0.05 * 0.2; /* k1 d + k3 d^3 + c d' */
    CHECK_REL(f[0], -F, 1e-15);
    CHECK_REL(f[1], F, 1e-15);
    CHECK_REL(gd_law_polynomial_spring.record(&L, 0, &x), F, 1e-15);
    CHECK_REL(gd_law_polynomial_spring.record(&L, 1, &x), 1.5, 1e-15);
    gd_law R;
    gd_law_init(&R, &gd_law_friction, "r");
    R.value[0] = 10.0, R.value[1] = 1e-3;
    double vr[2] = {0.5, 0.0}, fr[2] = {0};
    gd_law_point xr = {0, q, vr};
    gd_law_friction.force(&R, &xr, fr, NULL, NULL);
    CHECK_REL(fr[0], -10.0, 1e-15); /* fully slipping: the Coulomb level */
    vr[0] = 1e-5;                   /* well below v_reg: viscous with slope F / v_reg */
    memset(fr, 0, sizeof fr);
    gd_law_friction.force(&R, &xr, fr, NULL, NULL);
    CHECK_REL(fr[0], -10.0 * tanh(1e-2), 1e-15);
    /* friction only dissipates: F s >= 0 at any slip */
    for (double s = -1; s <= 1; s += 0.125) {
        vr[0] = s;
        CHECK(gd_law_friction.record(&R, 0, &xr) * s >= 0);
    }
}

TEST(instance_checks_name_the_field)
{
    gd_law L;
    gd_error err;
    gd_law_init(&L, &gd_law_friction, "rub");
    CHECK(gd_law_check(&L, &err) == GD_EINPUT); /* force and velocity are required */
    CHECK_STR(err.field, "force");
    CHECK(strstr(err.message, "required") != NULL);
    L.value[0] = 1.0;
    L.value[1] = 0.0;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK_STR(err.field, "velocity");
    CHECK(strstr(err.message, "> 0") != NULL);
    L.value[1] = INFINITY;
    CHECK(gd_law_check(&L, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "finite") != NULL);
    gd_law S;
    gd_sfd_params p = {.viscosity = 1e-2, .radius = 0.02, .length = 0.01, .clearance = 1e-4};
    gd_law_init(&S, &gd_law_sfd, "d");
    gd_sfd_law_values(&p, &S);
    CHECK(gd_law_check(&S, &err) == GD_OK);
    S.value[4] = 2; /* film */
    CHECK(gd_law_check(&S, &err) == GD_EINPUT);
    CHECK_STR(err.field, "film");
    S.value[4] = 0;
    S.value[6] = 1.0; /* max_eccentricity */
    CHECK(gd_law_check(&S, &err) == GD_EINPUT);
    CHECK_STR(err.field, "max_eccentricity");
    /* the damper's values and parameters round-trip */
    gd_sfd_params back;
    S.value[6] = 0.9;
    gd_sfd_params_of_law(&S, &back);
    CHECK(back.radius == 0.02 && back.clearance == 1e-4 && back.max_eccentricity == 0.9);
    gd_law D;
    gd_law_init(&D, &gd_law_load, "l");
    CHECK(gd_law_check(&D, &err) == GD_EINPUT); /* no gd_load_law */
    CHECK_STR(err.field, "data");
}

/* A user's own law: the cubic spring k3 d^3 to ground, written here as a user would. */
static void user_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law, (void)k;
    u[0] = w[0] = 1.0;
}
static void user_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double k3 = *(const double *)law->user, d = x->q[0];
    f[0] -= k3 * d * d * d;
    if (jq) jq[0] = -3.0 * k3 * d * d;
    if (jv) jv[0] = 0.0;
}
static const gd_law_type user_cubic = {.name = "user_cubic",
                                       .flags = GD_LAW_SMOOTH,
                                       .nterms = 1,
                                       .term = user_term,
                                       .force = user_force};

TEST(user_type_is_accepted_and_bad_tables_refused)
{
    gd_error err;
    CHECK(gd_law_type_validate(&user_cubic, &err) == GD_OK);
    double k3 = 2.5;
    gd_law L;
    gd_law_init(&L, &user_cubic, "mine");
    L.user = &k3;
    CHECK(L.ndofs == 1);
    CHECK(gd_law_check(&L, &err) == GD_OK);
    double q = 0.2, v = 0, f = 0;
    gd_law_point x = {0, &q, &v};
    user_cubic.force(&L, &x, &f, NULL, NULL);
    CHECK_REL(f, -2.5 * 0.008, 1e-15);
    gd_law_type bad = user_cubic;
    bad.force = NULL;
    CHECK(gd_law_type_validate(&bad, &err) == GD_EINPUT);
    CHECK(strstr(err.message, "force") != NULL);
    bad = user_cubic;
    bad.nterms = GD_LAW_MAX_TERMS + 1;
    CHECK(gd_law_type_validate(&bad, &err) == GD_EINPUT);
    bad = user_cubic;
    static const int dirs7[] = {7};
    bad.dirs = dirs7, bad.ndirs = 1;
    CHECK(gd_law_type_validate(&bad, &err) == GD_EINPUT);
}

RUN_TESTS(T(registry_tables_are_valid), T(jacobian_terms_match_differences),
          T(polynomial_spring_and_friction_values), T(instance_checks_name_the_field),
          T(user_type_is_accepted_and_bad_tables_refused))
