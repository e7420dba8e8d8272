/* A tooth as a non-uniform cantilever along its centre line (the potential energy
 * method of [YangLin1987] / [Tian2004], [JMSTHelical] Eqs. 7-9), written for any tooth
 * whose flank is one involute from the contact to the root circle, and integrated over
 * the pressure angle a of the flank point (r = r_b / cos a, smooth at the base circle):
 *   half tooth angle psi(a) = alpha2 - inv a (external) or alpha2 + inv a (a ring's
 *   tooth, which widens outward), centre-line height y = r cos psi, half thickness
 *   h = r sin psi, dy/da = r tan a (cos psi -+ sin psi tan a);
 *   the load along the line of action makes the angle a1 = a_c -+ psi_c with the normal
 *   to the centre line (external -, ring +: the ring's concave flank tilts the load
 *   further), and with d = |y - y_c| the moment is F (d cos a1 - h_c sin a1), so per unit
 *   face width
 *   1/k_b = int 3 (d cos a1 - h_c sin a1)^2 / (2 E h^3) dy,
 *   1/k_s = int 1.2 (1 + nu) cos^2 a1 / (E h) dy,  1/k_a = int sin^2 a1 / (2 E h) dy.
 * For an external tooth with its root above the base circle this is the same integral
 * as tooth_energy.c's (there over the tangent-point angle), which the tests check.
 * The ring tooth's foundation ([Sainsot2004] with the ring's root thickness and load
 * height) needs a body ratio h = r_f / r_int: a rim of thickness r_o - r_f is mapped to
 * the hub of the same relative thickness, h = 1 / (2 - r_o / r_f), kept inside the
 * fitted range 1.4 .. 7 of the formula (docs/mesh-stiffness.md, "Internal pairs"). */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

typedef struct radial_ctx {
    const gd_ms_tooth *t;
    double sgn;            /* -1 external, +1 ring */
    double yc, hc, ca, sa; /* contact point, cos/sin of a1 */
    int term;
} radial_ctx;

static double psi_of(const gd_ms_tooth *t, double sgn, double a)
{
    return t->alpha2 + sgn * (tan(a) - a);
}

static double integrand(double a, void *vp)
{
    const radial_ctx *c = vp;
    const gd_ms_tooth *t = c->t;
    double r = t->rb / cos(a), ta = tan(a);
    double psi = psi_of(t, c->sgn, a);
    double y = r * cos(psi), h = r * sin(psi);
    double dyda = fabs(r * ta * (cos(psi) - c->sgn * sin(psi) * ta));
    double dist = fabs(y - c->yc);
    double m = dist * c->ca - c->hc * c->sa;
    double E = t->E;
    switch (c->term) {
    case 0:
        return 3 * m * m / (2 * E * h * h * h) * dyda;
    case 1:
        return 1.2 * (1 + t->nu) * c->ca * c->ca / (E * h) * dyda;
    default:
        return c->sa * c->sa / (2 * E * h) * dyda;
    }
}

void gd_ms_radial_beam_terms(const gd_ms_tooth *t, double tc, double rtol, double out[3])
{
    double sgn = t->internal ? 1 : -1;
    double ac = atan(tc), rc = t->rb / cos(ac);
    double psic = psi_of(t, sgn, ac);
    double a1 = ac + sgn * psic;
    radial_ctx c = {t, sgn, rc * cos(psic), rc * sin(psic), cos(a1), sin(a1), 0};
    double af = t->rf > t->rb ? acos(t->rb / t->rf) : 0;
    for (int k = 0; k < 3; k++) {
        c.term = k;
        /* over y from the contact to the root: a decreases on an external tooth */
        double v = gd_ms_integrate(integrand, &c, ac < af ? ac : af, ac < af ? af : ac, rtol, NULL);
        out[k] = v;
    }
}

double gd_ms_ring_fillet_compliance(const gd_ms_tooth *t, double tc)
{
    double ac = atan(tc);
    double psic = psi_of(t, 1, ac);
    double a1 = ac + psic;
    double thf = psi_of(t, 1, acos(t->rb / t->rf)); /* half tooth angle at the root circle */
    double ratio = t->rbore / t->rf;                /* rim outer / root, > 1 */
    double h = ratio < 2 ? 1 / (2 - ratio) : 7;
    if (h < 1.4) h = 1.4;
    if (h > 7) h = 7;
    /* the load line crosses the centre line r_b / cos(a1) from the ring's centre, inside
     * the root circle */
    double uf = t->rf - t->rb / cos(a1);
    return gd_ms_foundation_formula(a1, uf, 2 * t->rf * thf, thf, h, t->E);
}
