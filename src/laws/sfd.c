/* Squeeze film damper forces by short-bearing (Ocvirk) theory, pi (cavitated) and 2pi
 * (uncavitated) film, with a finite-length correction factor ([Chen1998], Barrett, Allaire &
 * Gunter 1980). Derivation (docs/transient.md):
 *
 * Journal centre at e (e, phi) from the housing centre, no spin. With theta measured from
 * the point of maximum film (opposite to the eccentricity), h = c (1 + eps cos theta) and
 * dh/dt = c (eps' cos theta + eps phi' sin theta). Short-bearing Reynolds equation with
 * p = 0 at both ends: p = 6 mu (dh/dt) (z^2 - L^2/4) / h^3, so int p dz = -mu L^3 h_t / h^3.
 * The force on the journal is -int p n R dtheta dz with n the outward normal; its
 * components along e (radial) and +90 deg from it (tangential) are
 *   F_r = -(mu R L^3 / c^2) [eps' J1 + eps phi' J2]
 *   F_t = -(mu R L^3 / c^2) [eps' J2 + eps phi' J3]
 * with J1..J3 the integrals of cos^2, sin cos, sin^2 over (1 + eps cos theta)^3 on the
 * film: all of [0, 2 pi) for the 2pi film; for the pi film the half where the film is
 * squeezed (p > 0): theta in (psi0 + pi/2, psi0 + 3 pi/2), psi0 = atan2(eps phi', eps').
 * Closed forms through the eccentric anomaly gamma, cos gamma = (eps + cos theta) /
 * (1 + eps cos theta), which turns every integrand into a trigonometric polynomial:
 *   J1 = [(1/2 + eps^2) gamma + sin(2 gamma)/4 - 2 eps sin gamma] / s^5
 *   J2 = [sin^2(gamma)/2 + eps cos gamma] / s^4
 *   J3 = [gamma/2 - sin(2 gamma)/4] / s^3,            s = sqrt(1 - eps^2). */
#include <math.h>

#include "geardyn/laws.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

double gd_sfd_correction_factor(double l_over_d)
{
    double l = l_over_d;
    if (!(l > 0)) return 1.0;
    if (l < 1e-3) return 1.0 - 0.4 * l * l; /* series: 1 - 2 l^2/5 + O(l^4) */
    return 3.0 / (l * l) * (1.0 - tanh(l) / l);
}

/* Continuous eccentric anomaly of theta: gamma - theta lies in (-pi, pi) and both agree
 * at multiples of pi; st, ct: sin and cos of theta. */
static double anomaly(double eps, double s, double theta, double st, double ct)
{
    double g0 = atan2(s * st, eps + ct);
    return theta + remainder(g0 - theta, 2.0 * M_PI);
}

/* The antiderivatives at gamma = g, with sg, cg its sine and cosine (from theta's:
 * cos gamma = (eps + cos theta) / h, sin gamma = s sin theta / h, h = 1 + eps cos theta,
 * so that one sine and cosine of theta serve an end of the film). */
static void antiderivatives(double eps, double s, double g, double sg, double cg, double out[3])
{
    double s2g = 2.0 * sg * cg;
    double s3 = s * s * s, s4 = s3 * s, s5 = s4 * s;
    out[0] = ((0.5 + eps * eps) * g + 0.25 * s2g - 2.0 * eps * sg) / s5;
    out[1] = (0.5 * sg * sg + eps * cg) / s4;
    out[2] = (0.5 * g - 0.25 * s2g) / s3;
}

/* dF/deps along theta fixed of the antiderivatives above at gamma = g, theta = t (st, ct):
 * dF/deps|gamma + (dF/dgamma) dgamma/deps|theta with dF/dgamma = f(theta) h / s and
 * dgamma/deps|theta = -sin(theta) / (s h) (from cos gamma = (eps + cos theta) / h,
 * h = 1 + eps cos theta), f the integrands cos^2, sin cos, sin^2 over h^3. */
static void antiderivatives_deps(double eps, double s, double g, double sg, double cg, double st,
                                 double ct, double out[3])
{
    double s2g = 2.0 * sg * cg;
    double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
    double a0 = (0.5 + eps * eps) * g + 0.25 * s2g - 2.0 * eps * sg;
    double a1 = 0.5 * sg * sg + eps * cg, a2 = 0.5 * g - 0.25 * s2g;
    double h = 1.0 + eps * ct, b = st / (s2 * h * h * h);
    out[0] = (2.0 * eps * g - 2.0 * sg) / s5 + 5.0 * eps * a0 / (s5 * s2) - ct * ct * b;
    out[1] = cg / s4 + 4.0 * eps * a1 / (s4 * s2) - st * ct * b;
    out[2] = 3.0 * eps * a2 / (s3 * s2) - st * st * b;
}

/* J over [t1, t2] and, if dj, dJ/deps (theta's limits fixed). */
static void integrals(double eps, double t1, double t2, double j[3], double dj[3])
{
    double s = sqrt((1.0 - eps) * (1.0 + eps));
    double a[3], b[3];
    /* keep gamma continuous over the interval: add whole turns of theta to gamma */
    double turns = floor((t2 - t1) / (2.0 * M_PI));
    double t2r = t2 - turns * 2.0 * M_PI;
    double st1 = sin(t1), ct1 = cos(t1), st2 = sin(t2r), ct2 = cos(t2r);
    double h1 = 1.0 + eps * ct1, h2 = 1.0 + eps * ct2;
    double sg1 = s * st1 / h1, cg1 = (eps + ct1) / h1, sg2 = s * st2 / h2, cg2 = (eps + ct2) / h2;
    double g2 = anomaly(eps, s, t2r, st2, ct2);
    double g1 = anomaly(eps, s, t1, st1, ct1);
    antiderivatives(eps, s, g1, sg1, cg1, a);
    /* gamma(t2r) must not be below gamma(t1) when t2r >= t1 */
    while (g2 < g1 - 1e-15)
        g2 += 2.0 * M_PI;
    g2 += turns * 2.0 * M_PI;
    antiderivatives(eps, s, g2, sg2, cg2, b);
    for (int k = 0; k < 3; k++)
        j[k] = b[k] - a[k];
    if (!dj) return;
    antiderivatives_deps(eps, s, g1, sg1, cg1, st1, ct1, a);
    antiderivatives_deps(eps, s, g2, sg2, cg2, st2, ct2, b);
    for (int k = 0; k < 3; k++)
        dj[k] = b[k] - a[k];
}

void gd_sfd_integrals(double eps, double t1, double t2, double j[3])
{
    integrals(eps, t1, t2, j, NULL);
}

void gd_sfd_force_polar(const gd_sfd_params *p, double e, double edot, double phidot, double *fr,
                        double *ft)
{
    double c = p->clearance;
    double emax = p->max_eccentricity > 0 ? p->max_eccentricity : 0.995;
    double eps = e / c;
    if (eps > emax) eps = emax;
    if (eps < 0) eps = 0;
    double epsd = edot / c, wv = eps * phidot; /* eps', eps phi' */
    double eta = p->correction > 0   ? p->correction
                 : p->correction < 0 ? 1.0
                                     : gd_sfd_correction_factor(p->length / (2.0 * p->radius));
    double scale = p->viscosity * p->radius * p->length * p->length * p->length / (c * c) * eta;
    double j[3];
    if (p->film == GD_SFD_2PI_FILM) {
        gd_sfd_integrals(eps, 0.0, 2.0 * M_PI, j);
    } else {
        if (epsd == 0.0 && wv == 0.0) {
            *fr = *ft = 0.0;
            return;
        }
        double psi0 = atan2(wv, epsd);
        gd_sfd_integrals(eps, psi0 + 0.5 * M_PI, psi0 + 1.5 * M_PI, j);
    }
    *fr = -scale * (epsd * j[0] + wv * j[1]);
    *ft = -scale * (epsd * j[1] + wv * j[2]);
}

void gd_sfd_force(const gd_sfd_params *p, double x, double y, double vx, double vy, double *fx,
                  double *fy)
{
    double e = hypot(x, y);
    double cphi, sphi;
    if (e > 1e-12 * p->clearance) {
        cphi = x / e;
        sphi = y / e;
    } else {
        /* centred: the forces are isotropic, any direction serves; take the velocity's */
        double v = hypot(vx, vy);
        cphi = v > 0 ? vx / v : 1.0;
        sphi = v > 0 ? vy / v : 0.0;
        e = 0.0;
    }
    double edot = vx * cphi + vy * sphi;   /* radial velocity */
    double ephid = -vx * sphi + vy * cphi; /* tangential velocity e phi' */
    double phidot = e > 0 ? ephid / e : 0.0;
    double fr, ft;
    if (e > 0) {
        gd_sfd_force_polar(p, e, edot, phidot, &fr, &ft);
    } else {
        /* eps phi' = ephid / c is finite as e -> 0: evaluate with a tiny eccentricity */
        double et = 1e-9 * p->clearance;
        gd_sfd_force_polar(p, et, edot, ephid / et, &fr, &ft);
    }
    *fx = fr * cphi - ft * sphi;
    *fy = fr * sphi + ft * cphi;
}

/* Central differences of gd_sfd_force (steps 1e-6 of the clearance and of the velocity
 * scale): the Jacobian where the closed form below has no direction to work in. */
static void jacobian_differences(const gd_sfd_params *p, double x, double y, double vx, double vy,
                                 double *fx, double *fy, double jq[4], double jv[4])
{
    double u[4] = {x, y, vx, vy};
    double c = p->clearance, vs = hypot(vx, vy);
    double h[4] = {1e-6 * c, 1e-6 * c, 1e-6 * (vs > 0 ? vs : c), 1e-6 * (vs > 0 ? vs : c)};
    gd_sfd_force(p, x, y, vx, vy, fx, fy);
    for (int j = 0; j < 4; j++) {
        double up[4], um[4], fp[2], fm[2];
        for (int k = 0; k < 4; k++)
            up[k] = um[k] = u[k];
        up[j] += h[j];
        um[j] -= h[j];
        gd_sfd_force(p, up[0], up[1], up[2], up[3], &fp[0], &fp[1]);
        gd_sfd_force(p, um[0], um[1], um[2], um[3], &fm[0], &fm[1]);
        double *J = j < 2 ? jq : jv;
        int col = j & 1;
        for (int i = 0; i < 2; i++)
            J[2 * i + col] = (fp[i] - fm[i]) / (2.0 * h[j]);
    }
}

/* The Jacobian in closed form. In the polar frame of the journal (e, phi) the force is
 * F_r = -S (u J1 + w J2), F_t = -S (u J2 + w J3) with u = eps', w = eps phi' (velocities
 * over c) and J(eps, psi0) over the squeezed half of the film. psi0 moves the film's
 * ends, where the pressure u cos + w sin over h^3 vanishes: Leibniz's boundary terms are
 * zero and J depends on the state through eps alone, dJ/deps from the antiderivatives
 * (integrals()). The chain rule then runs through e, phi (the frame turning with phi:
 * dF/dphi gains (-F_t, F_r)) and through u, w as the velocity components in that frame.
 * At the eccentricity cap eps stops moving with e and w = eps_max ephi' / e. Centred
 * (e below 1e-9 c) or at rest in the pi film (no squeezed half): central differences. */
void gd_sfd_force_jacobian(const gd_sfd_params *p, double x, double y, double vx, double vy,
                           double *fx, double *fy, double jq[4], double jv[4])
{
    const double c = p->clearance, e = hypot(x, y);
    double emax = p->max_eccentricity > 0 ? p->max_eccentricity : 0.995;
    if (!(e > 1e-9 * c)) {
        jacobian_differences(p, x, y, vx, vy, fx, fy, jq, jv);
        return;
    }
    double cp = x / e, sp = y / e;
    double edot = vx * cp + vy * sp, ephid = -vx * sp + vy * cp;
    int capped = e / c > emax;
    double eps = capped ? emax : e / c, k = eps / e; /* w = k ephid */
    double u = edot / c, w = eps * (ephid / e);      /* as gd_sfd_force_polar rounds it */
    double eta = p->correction > 0   ? p->correction
                 : p->correction < 0 ? 1.0
                                     : gd_sfd_correction_factor(p->length / (2.0 * p->radius));
    double S = p->viscosity * p->radius * p->length * p->length * p->length / (c * c) * eta;
    double j[3], dj[3];
    if (p->film == GD_SFD_2PI_FILM) {
        integrals(eps, 0.0, 2.0 * M_PI, j, dj);
    } else {
        if (u == 0.0 && w == 0.0) {
            jacobian_differences(p, x, y, vx, vy, fx, fy, jq, jv);
            return;
        }
        double psi0 = atan2(w, u);
        integrals(eps, psi0 + 0.5 * M_PI, psi0 + 1.5 * M_PI, j, dj);
    }
    double fr = -S * (u * j[0] + w * j[1]), ft = -S * (u * j[1] + w * j[2]);
    *fx = fr * cp - ft * sp;
    *fy = fr * sp + ft * cp;
    /* polar partials in (eps, u, w) */
    double fr_u = -S * j[0], fr_w = -S * j[1], ft_u = -S * j[1], ft_w = -S * j[2];
    double fr_eps = -S * (u * dj[0] + w * dj[1]), ft_eps = -S * (u * dj[1] + w * dj[2]);
    /* along e (phi, v fixed) and along phi (e, v fixed) */
    double deps_de = capped ? 0.0 : 1.0 / c, dw_de = capped ? -w / e : 0.0;
    double du_dphi = ephid / c, dw_dphi = -k * edot;
    double Fr_e = fr_eps * deps_de + fr_w * dw_de, Ft_e = ft_eps * deps_de + ft_w * dw_de;
    double Fr_p = fr_u * du_dphi + fr_w * dw_dphi, Ft_p = ft_u * du_dphi + ft_w * dw_dphi;
    double fx_e = Fr_e * cp - Ft_e * sp, fy_e = Fr_e * sp + Ft_e * cp;
    double fx_p = Fr_p * cp - Ft_p * sp - *fy, fy_p = Fr_p * sp + Ft_p * cp + *fx;
    jq[0] = fx_e * cp - fx_p * sp / e;
    jq[1] = fx_e * sp + fx_p * cp / e;
    jq[2] = fy_e * cp - fy_p * sp / e;
    jq[3] = fy_e * sp + fy_p * cp / e;
    /* velocities: u = (vx cp + vy sp) / c, w = k (-vx sp + vy cp) */
    double du[2] = {cp / c, sp / c}, dw[2] = {-k * sp, k * cp};
    for (int m = 0; m < 2; m++) {
        double Fr_v = fr_u * du[m] + fr_w * dw[m], Ft_v = ft_u * du[m] + ft_w * dw[m];
        jv[m] = Fr_v * cp - Ft_v * sp;
        jv[2 + m] = Fr_v * sp + Ft_v * cp;
    }
}

/* ---- the squeeze film damper as a law (include/geardyn/law_type.h) ----
 * Local DOFs [x, y] of the journal node, then [x, y] of the housing node (absent:
 * ground). value[]: viscosity, diameter, length, clearance, film (0 pi, 1 2pi),
 * correction (0 auto, < 0 none, > 0 factor), max_eccentricity (0: 0.995). */

#include "geardyn/law_type.h"
#include "laws/laws_impl.h"

enum { SFD_MU, SFD_D, SFD_L, SFD_C, SFD_FILM, SFD_CORR, SFD_EMAX, SFD_NPARAMS };

static const gd_law_param sfd_params[SFD_NPARAMS] = {
    {"viscosity", GD_QTY_VISCOSITY, NAN, GD_LAW_POSITIVE, "the oil's dynamic viscosity, Pa s"},
    {"diameter", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the journal diameter D"},
    {"length", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the land length L"},
    {"clearance", GD_QTY_LENGTH, NAN, GD_LAW_POSITIVE, "the radial clearance c"},
    {"film", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG, "0: pi (cavitated) film, 1: 2pi film"},
    {"correction", GD_QTY_DIMLESS, 0.0, GD_LAW_ANY,
     "finite-length factor: 0 auto, negative none, positive this factor"},
    {"max_eccentricity", GD_QTY_DIMLESS, 0.0, GD_LAW_NONNEG,
     "cap of the eccentricity ratio, below 1 (0: 0.995)"},
};

void gd_sfd_params_of_law(const gd_law *law, gd_sfd_params *p)
{
    const double *v = law->value;
    p->viscosity = v[SFD_MU];
    p->radius = 0.5 * v[SFD_D];
    p->length = v[SFD_L];
    p->clearance = v[SFD_C];
    p->film = v[SFD_FILM] != 0.0 ? GD_SFD_2PI_FILM : GD_SFD_PI_FILM;
    p->correction = v[SFD_CORR];
    p->max_eccentricity = v[SFD_EMAX];
}

void gd_sfd_law_values(const gd_sfd_params *p, gd_law *law)
{
    double *v = law->value;
    v[SFD_MU] = p->viscosity;
    v[SFD_D] = 2.0 * p->radius;
    v[SFD_L] = p->length;
    v[SFD_C] = p->clearance;
    v[SFD_FILM] = p->film == GD_SFD_2PI_FILM ? 1.0 : 0.0;
    v[SFD_CORR] = p->correction;
    v[SFD_EMAX] = p->max_eccentricity;
}

static int sfd_check(const gd_law *law, const char **field, char *msg, size_t cap)
{
    return gd_law_check_film(law->value[SFD_FILM], law->value[SFD_EMAX], field, msg, cap);
}

static void sfd_relative(const gd_law_point *x, double rel[4])
{
    rel[0] = x->q[0] - x->q[2];
    rel[1] = x->q[1] - x->q[3];
    rel[2] = x->v[0] - x->v[2];
    rel[3] = x->v[1] - x->v[3];
}

static void sfd_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    gd_sfd_params p;
    gd_sfd_params_of_law(law, &p);
    double r[4], fx, fy;
    sfd_relative(x, r);
    if (jq || jv) {
        double a[4], b[4];
        gd_sfd_force_jacobian(&p, r[0], r[1], r[2], r[3], &fx, &fy, a, b);
        for (int k = 0; k < 4; k++) {
            if (jq) jq[k] = a[k];
            if (jv) jv[k] = b[k];
        }
    } else {
        gd_sfd_force(&p, r[0], r[1], r[2], r[3], &fx, &fy);
    }
    f[0] += fx;
    f[1] += fy;
    f[2] -= fx;
    f[3] -= fy;
}

static const gd_law_record sfd_records[] = {{"fx", "N"}, {"fy", "N"}, {"ecc", "-"}};

static double sfd_record(const gd_law *law, int k, const gd_law_point *x)
{
    gd_sfd_params p;
    gd_sfd_params_of_law(law, &p);
    double r[4], fx, fy;
    sfd_relative(x, r);
    if (k == 2) return hypot(r[0], r[1]) / p.clearance;
    gd_sfd_force(&p, r[0], r[1], r[2], r[3], &fx, &fy);
    return k == 0 ? fx : fy;
}

const gd_law_type gd_law_sfd = {
    .name = "sfd",
    .summary = "squeeze film damper, short-bearing theory with a finite-length correction",
    .flags = GD_LAW_SMOOTH,
    .params = sfd_params,
    .nparams = SFD_NPARAMS,
    .dirs = gd_law_xy_dirs,
    .ndirs = 2,
    .two_nodes = 1,
    .check = sfd_check,
    .nterms = 4,
    .term = gd_law_xy_term,
    .force = sfd_force,
    .records = sfd_records,
    .nrecords = 3,
    .record = sfd_record,
    .linearize = gd_law_linearize_terms,
};
