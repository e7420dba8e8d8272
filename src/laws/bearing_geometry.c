/* Rolling bearings from their geometry: the load and 5 x 5 stiffness of a ball or roller
 * bearing from the Hertz contact of every element (geardyn/bearing_geometry.h;
 * [LimSingh1990]; [HarrisKotzalas2006] ch. 6-7; Hamrock & Brewe 1983 for the point
 * contact's ellipticity and elliptic integrals). */
#include "geardyn/bearing_geometry.h"

#include <lapacke.h>
#include <math.h>
#include <string.h>

#define TWO_PI 6.283185307179586

void gd_bearing_geometry_init(gd_bearing_geometry *g)
{
    memset(g, 0, sizeof *g);
    g->kind = GD_BEARING_BALL;
    g->inner_curvature = 0.52;
    g->outer_curvature = 0.52;
    g->modulus = 206e9;
    g->poisson = 0.3;
}

static gd_status bad(gd_error *err, const char *field, const char *hint, const char *what)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, "%s", what);
}

gd_status gd_bearing_geometry_check(const gd_bearing_geometry *g, gd_error *err)
{
    if (g->kind != GD_BEARING_BALL && g->kind != GD_BEARING_ROLLER)
        return bad(err, "type", "ball or roller", "unknown bearing type");
    if (g->elements < 3 || g->elements > 1000)
        return bad(err, "elements", "give 3 to 1000 balls or rollers",
                   "the number of elements is out of range");
    if (!(g->element_diameter > 0) || !isfinite(g->element_diameter))
        return bad(err, "element_diameter", "give the ball or roller diameter, > 0",
                   "the element diameter must be positive");
    if (!(g->pitch_diameter > g->element_diameter) || !isfinite(g->pitch_diameter))
        return bad(err, "pitch_diameter", "give a pitch diameter above the element diameter",
                   "the pitch diameter must be larger than the element diameter");
    if (!(g->contact_angle >= 0 && g->contact_angle < 1.5707963267948966))
        return bad(err, "contact_angle", "give 0 to below 90 deg",
                   "the contact angle is out of range");
    if (!isfinite(g->clearance) || !(fabs(g->clearance) < 0.1 * g->element_diameter))
        return bad(err, "clearance", "a radial clearance (or, negative, a preload) of a few um",
                   "the clearance must be finite and below a tenth of the element diameter");
    if (!(g->contact_stiffness >= 0) || !isfinite(g->contact_stiffness))
        return bad(err, "contact_stiffness", "give K_n > 0 in N/m^n, or 0 for the geometry's",
                   "the contact stiffness must be finite and not negative");
    if (!(g->modulus > 0) || !isfinite(g->modulus) || !(g->poisson >= 0 && g->poisson < 0.5))
        return bad(err, "modulus", "steel: 206 GPa and Poisson's ratio 0.3",
                   "the elastic modulus must be positive and Poisson's ratio in [0, 0.5)");
    if (!isfinite(g->phase)) return bad(err, "phase", "give a finite angle", "phase not finite");
    if (g->kind == GD_BEARING_BALL) {
        if (!(g->inner_curvature > 0.5 && g->inner_curvature < 1) ||
            !(g->outer_curvature > 0.5 && g->outer_curvature < 1))
            return bad(err, "inner_curvature", "groove radius over ball diameter, e.g. 0.52",
                       "the groove curvatures f_i and f_o must lie in (0.5, 1)");
    } else if (g->contact_stiffness == 0 &&
               (!(g->roller_length > 0) || !isfinite(g->roller_length))) {
        return bad(err, "roller_length", "give the rollers' effective length",
                   "a roller bearing without a contact stiffness needs its roller length");
    }
    return GD_OK;
}

/* Hertz point contact of a ball on a raceway: K of Q = K delta^(3/2), from the principal
 * radii rx (rolling direction) and ry (across the groove) of the contact: Hamrock & Brewe's
 * ellipticity k = 1.0339 (Ry/Rx)^0.636, E = 1.0003 + 0.5968 Rx/Ry, F = 1.5277 + 0.6023
 * ln(Ry/Rx), and delta = F [9 / (2 E R) (Q / (pi k E'))^2]^(1/3), R the effective radius. */
static double point_contact(double rx, double ry, double e_red)
{
    double lo = fmin(rx, ry), hi = fmax(rx, ry), ar = hi / lo;
    double k = 1.0339 * pow(ar, 0.636), E = 1.0003 + 0.5968 / ar, F = 1.5277 + 0.6023 * log(ar);
    double R = rx * ry / (rx + ry);
    return M_PI * k * e_red * sqrt(2 * E * R / 9) / pow(F, 1.5);
}

gd_status gd_bearing_contact_constant(const gd_bearing_geometry *g, double *kn, double *n,
                                      gd_error *err)
{
    gd_status st = gd_bearing_geometry_check(g, err);
    if (st) return st;
    const double d = g->element_diameter;
    const double e_red = g->modulus / (1 - g->poisson * g->poisson); /* both bodies alike */
    *n = g->kind == GD_BEARING_BALL ? 1.5 : 10.0 / 9.0;
    if (g->contact_stiffness > 0) {
        *kn = g->contact_stiffness;
        return GD_OK;
    }
    if (g->kind == GD_BEARING_BALL) {
        double gam = d * cos(g->contact_angle) / g->pitch_diameter;
        double fi = g->inner_curvature, fo = g->outer_curvature;
        double ki = point_contact(0.5 * d * (1 - gam), fi * d / (2 * fi - 1), e_red);
        double ko = point_contact(0.5 * d * (1 + gam), fo * d / (2 * fo - 1), e_red);
        /* in series: delta = (Q / ki)^(2/3) + (Q / ko)^(2/3) */
        *kn = pow(pow(ki, -2.0 / 3) + pow(ko, -2.0 / 3), -1.5);
    } else {
        /* Palmgren, steel: delta_mm = 3.84e-5 Q^0.9 / l_mm^0.8 per contact, so Q = K1
           delta^(10/9), K1 = (1e3 (1e3 l)^0.8 / 3.84e-5)^(10/9) N/m^(10/9); two equal
           contacts in series halve the approach; K scales with E' from steel's */
        double k1 = pow(1e3 * pow(1e3 * g->roller_length, 0.8) / 3.84e-5, 10.0 / 9.0);
        double steel = 206e9 / (1 - 0.09);
        *kn = k1 * pow(2.0, -10.0 / 9.0) * e_red / steel;
    }
    return GD_OK;
}

/* radius of the inner raceway's groove-curvature centre: the tilt's lever arm */
static double lever(const gd_bearing_geometry *g)
{
    double R = 0.5 * g->pitch_diameter;
    if (g->kind == GD_BEARING_BALL)
        R += (g->inner_curvature - 0.5) * g->element_diameter * cos(g->contact_angle);
    return R;
}

/* F(d) and K (may be NULL), K_n and n given. */
static void forces(const gd_bearing_geometry *g, double kn, double n, const double *d, double *F,
                   double *K, int *loaded)
{
    const int Z = g->elements;
    const double R = lever(g), a0 = g->contact_angle;
    const double A0 = (g->inner_curvature + g->outer_curvature - 1) * g->element_diameter;
    memset(F, 0, 5 * sizeof *F);
    if (K) memset(K, 0, 25 * sizeof *K);
    int nl = 0;
    for (int j = 0; j < Z; j++) {
        double psi = g->phase + TWO_PI * j / Z, cp = cos(psi), sp = sin(psi);
        double dr = d[0] * cp + d[1] * sp - g->clearance;
        double dz = d[2] + R * (d[3] * sp - d[4] * cp);
        double fr, fa, krr, krz, kzz;
        if (g->kind == GD_BEARING_BALL) {
            double u = A0 * sin(a0) + dz, v = A0 * cos(a0) + dr, A = hypot(u, v);
            double del = A - A0;
            if (!(del > 0)) continue;
            double Q = kn * pow(del, n), dQ = n * kn * pow(del, n - 1), c = v / A, s = u / A;
            fr = Q * c;
            fa = Q * s;
            /* d(Q v/A)/dv, d(Q v/A)/du = d(Q u/A)/dv, d(Q u/A)/du */
            krr = dQ * c * c + Q * s * s / A;
            krz = (dQ - Q / A) * s * c;
            kzz = dQ * s * s + Q * c * c / A;
        } else {
            double ca = cos(a0), sa = sin(a0), del = dr * ca + dz * sa;
            if (!(del > 0)) continue;
            double Q = kn * pow(del, n), dQ = n * kn * pow(del, n - 1);
            fr = Q * ca;
            fa = Q * sa;
            krr = dQ * ca * ca;
            krz = dQ * ca * sa;
            kzz = dQ * sa * sa;
        }
        nl++;
        double er[5] = {cp, sp, 0, 0, 0}, ez[5] = {0, 0, 1, R * sp, -R * cp};
        for (int a = 0; a < 5; a++)
            F[a] += fr * er[a] + fa * ez[a];
        if (K)
            for (int b = 0; b < 5; b++)
                for (int a = 0; a < 5; a++)
                    K[a + 5 * b] += krr * er[a] * er[b] + krz * (er[a] * ez[b] + ez[a] * er[b]) +
                                    kzz * ez[a] * ez[b];
    }
    if (loaded) *loaded = nl;
}

gd_status gd_bearing_forces(const gd_bearing_geometry *g, const double d[5], double F[5],
                            double K[25], int *loaded, gd_error *err)
{
    double kn, n;
    gd_status st = gd_bearing_contact_constant(g, &kn, &n, err);
    if (st) return st;
    for (int a = 0; a < 5; a++)
        if (!isfinite(d[a])) return bad(err, "displacement", "give finite values", "not finite");
    forces(g, kn, n, d, F, K, loaded);
    return GD_OK;
}

/* The solve in scaled coordinates y = (dx, dy, dz, R bx, R by), loads (Fx, Fy, Fz, Mx / R,
 * My / R), so metres and radians, newtons and newton-metres weigh alike. */
typedef struct solver {
    const gd_bearing_geometry *g;
    double kn, n, R, L[5];
    int act[5], na; /* the directions the bearing holds */
} solver;

static void unscale(const solver *s, const double *y, double *d)
{
    for (int a = 0; a < 5; a++)
        d[a] = a < 3 ? y[a] : y[a] / s->R;
}

/* r = F_s(y) - L_s over the active directions; J (na x na, may be NULL) = dF_s/dy */
static double resid(const solver *s, const double *y, double *r, double *J)
{
    double d[5], F[5], K[25];
    unscale(s, y, d);
    forces(s->g, s->kn, s->n, d, F, J ? K : NULL, NULL);
    double sc[5] = {1, 1, 1, 1 / s->R, 1 / s->R}, nr = 0;
    for (int i = 0; i < s->na; i++) {
        int a = s->act[i];
        r[i] = sc[a] * F[a] - s->L[a];
        nr += r[i] * r[i];
        if (J)
            for (int k = 0; k < s->na; k++)
                J[i + s->na * k] = sc[a] * K[a + 5 * s->act[k]] * sc[s->act[k]];
    }
    return sqrt(nr);
}

static double slope_at(const solver *s, const double *y, const double *dy, double a)
{
    double yt[5] = {0}, r[5];
    for (int i = 0; i < 5; i++)
        yt[i] = y[i];
    for (int i = 0; i < s->na; i++)
        yt[s->act[i]] += a * dy[i];
    resid(s, yt, r, NULL);
    double g = 0;
    for (int i = 0; i < s->na; i++)
        g += dy[i] * r[i];
    return g;
}

/* the step along dy (slope < 0 at 0) to the potential's minimum, at most amax when the
 * slope there is still negative; 0 when none */
static double min_along(const solver *s, const double *y, const double *dy, double amax)
{
    if (!(slope_at(s, y, dy, 0) < 0)) return 0;
    double lo = 0, hi = amax > 0 ? amax : 1e-15;
    if (amax > 0) {
        if (slope_at(s, y, dy, amax) <= 0) return amax;
    } else {
        int up = 0;
        for (int k = 0; k < 300 && !up; k++) {
            if (slope_at(s, y, dy, hi) > 0)
                up = 1;
            else
                lo = hi, hi *= 2;
        }
        if (!up) return 0;
    }
    for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; k++) {
        double mid = 0.5 * (lo + hi);
        if (slope_at(s, y, dy, mid) > 0)
            hi = mid;
        else
            lo = mid;
    }
    return lo;
}

gd_status gd_bearing_at_load(const gd_bearing_geometry *g, const double L[5], double d[5],
                             double K[25], gd_error *err)
{
    solver s = {.g = g};
    gd_status st = gd_bearing_contact_constant(g, &s.kn, &s.n, err);
    if (st) return st;
    memset(d, 0, 5 * sizeof *d);
    s.R = lever(g);
    double sc[5] = {1, 1, 1, 1 / s.R, 1 / s.R}, lnorm = 0;
    for (int a = 0; a < 5; a++) {
        if (!isfinite(L[a])) return bad(err, "load", "give finite loads", "the load is not finite");
        s.L[a] = sc[a] * L[a];
        lnorm += s.L[a] * s.L[a];
    }
    lnorm = sqrt(lnorm);
    /* A roller's point contacts at the pitch radius and a fixed angle tie its moment to
       its forces (Mx = R tan(alpha) Fy, My = -R tan(alpha) Fx): its tilt is held at 0 and
       the moment it reacts follows; at contact angle 0 it holds no axial motion either */
    int roller = g->kind == GD_BEARING_ROLLER, radial = roller && g->contact_angle == 0;
    for (int a = 0; a < 5; a++)
        if (!roller || a < (radial ? 2 : 3)) s.act[s.na++] = a;
    if (radial && L[2] != 0)
        return bad(err, "load",
                   "a roller bearing at contact angle 0 carries radial load only: give a "
                   "contact angle (tapered rollers) or put the axial load on another bearing",
                   "the bearing cannot carry an axial load");
    if (roller && (L[3] != 0 || L[4] != 0))
        return bad(err, "load",
                   "a roller bearing's moment follows from its forces (Mx = R tan(alpha) Fy, "
                   "My = -R tan(alpha) Fx, R the pitch radius): give Mx = My = 0; its tilt is "
                   "held at 0",
                   "the moments of a roller bearing are not free");
    double y[5] = {0}, r[5], J[25], dy[5], sv[5];
    int found = 0;
    for (int it = 0; it < 300 && !found; it++) {
        double rn = resid(&s, y, r, J);
        if (rn <= 1e-11 * lnorm || lnorm == 0) {
            found = 1;
            break;
        }
        for (int i = 0; i < s.na; i++)
            dy[i] = -r[i];
        lapack_int rank;
        double a = 0;
        if (LAPACKE_dgelsd(LAPACK_COL_MAJOR, s.na, s.na, 1, J, s.na, dy, s.na, sv, 1e-12, &rank) ==
            0)
            a = min_along(&s, y, dy, 1.0);
        if (!(a > 0)) { /* no stiffness yet (inside the clearance): along the load */
            for (int i = 0; i < s.na; i++)
                dy[i] = -r[i];
            a = min_along(&s, y, dy, 0);
        }
        if (!(a > 0)) break;
        for (int i = 0; i < s.na; i++)
            y[s.act[i]] += a * dy[i];
    }
    if (!found)
        return bad(err, "load",
                   g->kind == GD_BEARING_ROLLER
                       ? "a tapered roller bearing carries axial load in one direction only "
                         "(+z pushes the inner ring into its cone): check the sign of Fz"
                       : "check the load against the geometry: a ball bearing carries axial "
                         "load and moments through its contact angle and groove conformity",
                   "the bearing finds no position that carries the load");
    unscale(&s, y, d);
    double F[5], Kd[25];
    forces(g, s.kn, s.n, d, F, Kd, NULL);
    if (K) memcpy(K, Kd, sizeof Kd);
    return GD_OK;
}
