/* Rolling-element bearing from its geometry, in five directions: the Hertz contact of
 * every ball or roller (geardyn/bearing_geometry.h, gd_bearing_forces; [LimSingh1990]
 * Eqs. 9-14) couples the radial (x, y), axial (z) and tilt (rx, ry) motion of the inner
 * race relative to the outer race, so the full 5 x 5 stiffness at the static load enters
 * the linear analyses (docs/bearings.md, "Rolling bearings from geometry in a model").
 *
 * The inner race (node) moves by d = (x, y, z, rx, ry) relative to the outer race (node2,
 * or ground). The bearing's load on the inner race is -F(d), F of gd_bearing_forces, plus
 * a viscous damping c on the relative translations; the outer race takes the opposite.
 * The cage turns at its kinematic speed (rolling_bearing.c; [HarrisKotzalas2006] ch. 8),
 * so element 0 sits at phase + w_c t and the stiffness varies at the ball-pass frequency.
 *
 * Local DOFs [x, y, z, rx, ry] of node, then of node2; a direction the model leaves out
 * (`dofs:` without z, say) stays at zero (GD_LAW_MODEL_DIRS). Jacobian: 25 rank-one terms, term
 * a + 5 b with u = e_a - e_(a+5), w = e_b - e_(b+5), jq = -K[a + 5 b]. The force is C1
 * (balls: n = 3/2; rollers: n = 10/9). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/bearing_geometry.h"
#include "geardyn/law_type.h"
#include "laws/laws_impl.h"

enum {
    R5_Z,
    R5_D,
    R5_DM,
    R5_ALPHA,
    R5_GAP,
    R5_ROLLER,
    R5_LEN,
    R5_FI,
    R5_FO,
    R5_E,
    R5_NU,
    R5_K,
    R5_C,
    R5_PHASE,
    R5_NPARAMS
};

static const gd_law_param r5_params[R5_NPARAMS] = {
    {"elements", GD_QTY_DIMLESS, NAN, GD_LAW_POSITIVE, "number of balls or rollers Z (3 to 1000)"},
    {"element_diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "ball or roller diameter d"},
    {"pitch_diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "pitch diameter d_m of the elements"},
    {"contact_angle", GD_QTY_ANGLE, 0.0, GD_LAW_NONNEG, "unloaded contact angle alpha0"},
    {"clearance", GD_QTY_LENGTH, 0.0, GD_LAW_ANY,
     "radial internal clearance c_r (negative: an interference preload)"},
    {"roller", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "0: ball bearing, 1: roller bearing"},
    {"roller_length", GD_QTY_LENGTH, 0.0, GD_LAW_NONNEG,
     "effective roller length l (rollers without contact_stiffness)"},
    {"inner_curvature", GD_QTY_DIMLESS, 0.52, GD_LAW_POSITIVE,
     "inner groove radius over ball diameter f_i (balls)"},
    {"outer_curvature", GD_QTY_DIMLESS, 0.52, GD_LAW_POSITIVE,
     "outer groove radius over ball diameter f_o (balls)"},
    {"modulus", GD_QTY_PRESSURE, 206e9, GD_LAW_POSITIVE, "elastic modulus of elements and races"},
    {"poisson", GD_QTY_DIMLESS, 0.3, GD_LAW_NONNEG, "Poisson's ratio of elements and races"},
    {"contact_stiffness", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "contact constant K_n, N/m^n (SI number); 0: from the geometry"},
    {"damping", GD_QTY_DAMPING, 0.0, GD_LAW_NONNEG,
     "viscous damping c of the relative x, y, z motion, N s/m"},
    {"phase", GD_QTY_ANGLE, 0.0, GD_LAW_ANY, "cage angle of element 0 at t = 0"},
};

static const int r5_dirs[5] = {0, 1, 2, 3, 4};

/* The instance's geometry, its cage at angle phase (rad). */
static void geometry(const gd_law *law, double phase, gd_bearing_geometry *g)
{
    const double *p = law->value;
    gd_bearing_geometry_init(g);
    g->kind = p[R5_ROLLER] != 0 ? GD_BEARING_ROLLER : GD_BEARING_BALL;
    g->elements = p[R5_Z] >= 0 && p[R5_Z] <= 1e6 ? (int)p[R5_Z] : 0;
    g->element_diameter = p[R5_D];
    g->pitch_diameter = p[R5_DM];
    g->contact_angle = p[R5_ALPHA];
    g->clearance = p[R5_GAP];
    g->roller_length = p[R5_LEN];
    g->inner_curvature = p[R5_FI];
    g->outer_curvature = p[R5_FO];
    g->modulus = p[R5_E];
    g->poisson = p[R5_NU];
    g->contact_stiffness = p[R5_K];
    g->phase = phase;
}

static int r5_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    const double *p = law->value;
    if (p[R5_Z] != floor(p[R5_Z])) {
        *field = "elements";
        snprintf(msg, cap, "the number of elements is a whole number (got %g)", p[R5_Z]);
        return 1;
    }
    if (p[R5_ROLLER] != 0 && p[R5_ROLLER] != 1) {
        *field = "roller";
        snprintf(msg, cap, "roller is 0 (ball bearing) or 1 (roller bearing), not %g",
                 p[R5_ROLLER]);
        return 1;
    }
    gd_bearing_geometry g;
    geometry(law, p[R5_PHASE], &g);
    gd_error err;
    gd_error_clear(&err);
    if (!gd_bearing_geometry_check(&g, &err)) return 0;
    /* the geometry's field names are the law's, but for the bearing type */
    static const char *const names[] = {
        "elements",      "element_diameter", "pitch_diameter", "contact_angle",     "clearance",
        "roller_length", "inner_curvature",  "modulus",        "contact_stiffness", "phase"};
    *field = "roller";
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++)
        if (!strcmp(err.field, names[k])) *field = names[k];
    snprintf(msg, cap, "%s (%s)", err.message, err.hint);
    return 1;
}

/* cage speed, rad/s (pure rolling, as rolling_bearing.c) */
static double cage_speed(const gd_law *law)
{
    const double *p = law->value;
    double g = p[R5_D] / p[R5_DM] * cos(p[R5_ALPHA]);
    return 0.5 * (law->spin[0] * (1.0 - g) + law->spin[1] * (1.0 + g));
}

/* F(d) and K (may be NULL) at the motion x; 0 when the geometry or d is invalid (F = 0). */
static int contacts(const gd_law *law, const gd_law_point *x, double *F, double *K, int *loaded)
{
    gd_bearing_geometry g;
    geometry(law, law->value[R5_PHASE] + cage_speed(law) * x->t, &g);
    double d[5];
    for (int a = 0; a < 5; a++)
        d[a] = x->q[a] - x->q[5 + a];
    gd_error err;
    if (!gd_bearing_forces(&g, d, F, K, loaded, &err)) return 1;
    memset(F, 0, 5 * sizeof *F);
    if (K) memset(K, 0, 25 * sizeof *K);
    if (loaded) *loaded = 0;
    return 0;
}

static void r5_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    int a = k % 5, b = k / 5;
    u[a] = 1.0;
    u[5 + a] = -1.0;
    w[b] = 1.0;
    w[5 + b] = -1.0;
}

static void r5_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double F[5], K[25];
    const double c = law->value[R5_C];
    contacts(law, x, F, jq ? K : NULL, NULL);
    for (int a = 0; a < 5; a++) {
        double fa = -F[a] - (a < 3 ? c * (x->v[a] - x->v[5 + a]) : 0.0);
        f[a] += fa;
        f[5 + a] -= fa;
    }
    for (int k = 0; k < 25; k++) {
        if (jq) jq[k] = -K[k];
        if (jv) jv[k] = k % 5 == k / 5 && k % 5 < 3 ? -c : 0.0;
    }
}

static int r5_frequencies(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg)
{
    (void)msg, (void)cap_msg;
    double f = law->value[R5_Z] * fabs(cage_speed(law) - law->spin[1]);
    if (!(f > 0) || cap < 1) return 0;
    w[0] = f;
    return 1;
}

static const gd_law_record r5_records[] = {{"fx", "N"},   {"fy", "N"},   {"fz", "N"},
                                           {"mx", "N m"}, {"my", "N m"}, {"loaded", "-"}};

/* the bearing's force and moments on the inner race (with the damping), and the elements
 * in contact */
static double r5_record(const gd_law *law, int k, const gd_law_point *x)
{
    double F[5];
    int nl = 0;
    contacts(law, x, F, NULL, &nl);
    if (k == 5) return (double)nl;
    const double c = law->value[R5_C];
    return -F[k] - (k < 3 ? c * (x->v[k] - x->v[5 + k]) : 0.0);
}

const gd_law_type gd_law_rolling_bearing_5dof = {
    .name = "rolling_bearing_5dof",
    .summary = "ball or roller bearing from its geometry: Hertz contacts of every element, "
               "radial, axial and tilt motion coupled (5 x 5 stiffness), cage at its kinematic "
               "speed",
    .flags = GD_LAW_SMOOTH | GD_LAW_SUPPORT | GD_LAW_CONSTANT_SPEED | GD_LAW_MODEL_DIRS,
    .params = r5_params,
    .nparams = R5_NPARAMS,
    .dirs = r5_dirs,
    .ndirs = 5,
    .two_nodes = 1,
    .check = r5_check,
    .nterms = 25,
    .term = r5_term,
    .force = r5_force,
    .frequencies = r5_frequencies,
    .records = r5_records,
    .nrecords = 6,
    .record = r5_record,
    .linearize = gd_law_linearize_terms,
};
