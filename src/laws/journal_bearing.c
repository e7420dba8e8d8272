/* Plain hydrodynamic journal bearing, short-bearing (Ocvirk) theory with a cavitated
 * (pi) film: the squeeze film damper's Reynolds solution (src/laws/sfd.c) with the
 * journal spinning. With the journal turning at w relative to the bush, the film sees
 * the squeeze velocity plus the wedge term (w / 2) dh/dtheta, which is the squeeze film
 * of a journal whirling at phi' - w / 2 (Childs, Turbomachinery Rotordynamics, 1993,
 * ch. 3; San Andres's notes on short bearings): the force at (x, y, x', y') is the
 * damper's at the velocity relative to a frame turning at w / 2,
 *
 *   F(x, y, x', y') = F_sfd(x, y, x' + (w / 2) y, y' - (w / 2) x).
 *
 * Static check: a journal held at eccentricity ratio eps carries the Ocvirk load
 * W = mu w R L^3 / (4 c^2) eps sqrt(pi^2 (1 - eps^2) + 16 eps^2) / (1 - eps^2)^2 at the
 * attitude angle tan(phi) = pi sqrt(1 - eps^2) / (4 eps) from the line of centres
 * (tests/laws/test_journal_bearing.c). The spin w is the spin of the journal node's
 * shaft minus that of the bush node's (law->spin). Local DOFs [x, y] of the journal,
 * then [x, y] of the bush (absent: ground). */
#include <math.h>

#include "geardyn/laws.h"
#include "laws/laws_impl.h"

enum { JB_MU, JB_D, JB_L, JB_C, JB_FILM, JB_EMAX, JB_NPARAMS };

static const gd_law_param jb_params[JB_NPARAMS] = {
    {"viscosity", GD_QTY_VISCOSITY, NAN, GD_LAW_POSITIVE, "the oil's dynamic viscosity, Pa s"},
    {"diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the journal diameter D"},
    {"length", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the bearing length L (short: L/D <= 0.5)"},
    {"clearance", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the radial clearance c"},
    {"film", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "0: pi (cavitated) film, 1: 2pi film"},
    {"max_eccentricity", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "cap of the eccentricity ratio, below 1 (0: 0.995)"},
};

static void jb_params_of(const gd_law *law, gd_sfd_params *p)
{
    const double *v = law->value;
    p->viscosity = v[JB_MU];
    p->radius = 0.5 * v[JB_D];
    p->length = v[JB_L];
    p->clearance = v[JB_C];
    p->film = v[JB_FILM] != 0.0 ? GD_SFD_2PI_FILM : GD_SFD_PI_FILM;
    p->correction = -1.0; /* Ocvirk's short bearing as it is */
    p->max_eccentricity = v[JB_EMAX];
}

static int jb_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    return gd_law_check_film(law->value[JB_FILM], law->value[JB_EMAX], field, msg, cap);
}

/* force on the journal and, if J, its Jacobians (row-major 2 x 2: jq, jv) */
static void jb_eval(const gd_law *law, const gd_law_point *x, double *fx, double *fy, double *jq,
                    double *jv)
{
    gd_sfd_params p;
    jb_params_of(law, &p);
    double h = 0.5 * (law->spin[0] - law->spin[1]);
    double rx = x->q[0] - x->q[2], ry = x->q[1] - x->q[3];
    double vx = x->v[0] - x->v[2] + h * ry, vy = x->v[1] - x->v[3] - h * rx;
    if (!jq && !jv) {
        gd_sfd_force(&p, rx, ry, vx, vy, fx, fy);
        return;
    }
    double a[4], b[4];
    gd_sfd_force_jacobian(&p, rx, ry, vx, vy, fx, fy, a, b);
    /* chain rule through the turning frame: d(vx)/dy = h, d(vy)/dx = -h */
    if (jq) {
        jq[0] = a[0] - h * b[1];
        jq[1] = a[1] + h * b[0];
        jq[2] = a[2] - h * b[3];
        jq[3] = a[3] + h * b[2];
    }
    if (jv)
        for (int k = 0; k < 4; k++)
            jv[k] = b[k];
}

static void jb_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double fx, fy;
    jb_eval(law, x, &fx, &fy, jq, jv);
    f[0] += fx;
    f[1] += fy;
    f[2] -= fx;
    f[3] -= fy;
}

static const gd_law_record jb_records[] = {{"fx", "N"}, {"fy", "N"}, {"ecc", "-"}};

static double jb_record(const gd_law *law, int k, const gd_law_point *x)
{
    if (k == 2) return hypot(x->q[0] - x->q[2], x->q[1] - x->q[3]) / law->value[JB_C];
    double fx, fy;
    jb_eval(law, x, &fx, &fy, NULL, NULL);
    return k == 0 ? fx : fy;
}

const gd_law_type gd_law_journal_bearing = {
    .name = "journal_bearing",
    .summary = "plain journal bearing, short-bearing (Ocvirk) theory with film rupture",
    .flags = GD_LAW_SMOOTH | GD_LAW_SUPPORT,
    .params = jb_params,
    .nparams = JB_NPARAMS,
    .dirs = gd_law_xy_dirs,
    .ndirs = 2,
    .two_nodes = 1,
    .check = jb_check,
    .nterms = 4,
    .term = gd_law_xy_term,
    .force = jb_force,
    .records = jb_records,
    .nrecords = 3,
    .record = jb_record,
    .linearize = gd_law_linearize_terms,
};
