/* Bending, shear and axial compressive compliance of one involute tooth, modelled as a
 * non-uniform cantilever clamped at the root circle ([JMSTHelical] Eqs. 7-9; Yang & Lin 1987
 * for bending and axial energy, Tian 2004 for shear; Chen & Shao 2011 for the straight
 * part between base and root circle when the root circle is the smaller).
 *
 * gamma is the polar angle, from the tooth centre line, of the point where the line
 * generating the involute touches the base circle; the profile point is then at
 * half-thickness h = rb (sin g + (a2 - g) cos g) and height y = rb (cos g - (a2 - g) sin g),
 * with a2 the half tooth angle on the base circle. The load acts at gamma = -a1, where
 * a1 = tc - a2 is the angle between the load and the normal to the centre line and tc
 * the roll angle of the contact point. Per unit face width, plane stress. */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

typedef struct beam_ctx {
    const gd_ms_tooth *t;
    double ca, sa; /* cos, sin of a1 */
    int term;      /* 0 bending, 1 shear, 2 axial, 3 all */
} beam_ctx;

static double integrand(double g, void *vp)
{
    const beam_ctx *c = vp;
    const double a2 = c->t->alpha2, E = c->t->E;
    double sg = sin(g), cg = cos(g);
    double lever = (a2 - g) * cg;                /* dy / (rb dg) */
    double D = sg + lever;                       /* h / rb */
    double m = 1 + c->ca * ((a2 - g) * sg - cg); /* bending moment / (F rb) */
    double vb = 3 * m * m * lever / (2 * E * D * D * D);
    double vs = 1.2 * (1 + c->t->nu) * lever * c->ca * c->ca / (E * D);
    double va = lever * c->sa * c->sa / (2 * E * D);
    switch (c->term) {
    case 0:
        return vb;
    case 1:
        return vs;
    case 2:
        return va;
    default:
        return vb + vs + va;
    }
}

double gd_ms_tooth_root_half_angle(const gd_ms_tooth *t)
{
    if (t->rf < t->rb) return asin(t->rb * sin(t->alpha2) / t->rf);
    double af = acos(t->rb / t->rf);
    return t->alpha2 - (tan(af) - af);
}

/* Upper limit of the involute integral and length of the straight part below it. */
static void clamp(const gd_ms_tooth *t, double *gend, double *d1, double *hb)
{
    *hb = t->rb * sin(t->alpha2);
    if (t->rf < t->rb) {
        *gend = t->alpha2;
        double yb = t->rb * cos(t->alpha2);
        double yr = *hb < t->rf ? sqrt(t->rf * t->rf - *hb * *hb) : 0;
        *d1 = yb > yr ? yb - yr : 0;
    } else {
        *gend = t->alpha2 - sqrt((t->rf / t->rb) * (t->rf / t->rb) - 1);
        *d1 = 0;
    }
}

/* Closed-form terms of the straight segment (constant half-thickness hb, length d1). */
static void straight_terms(const gd_ms_tooth *t, double a1, double d1, double hb, double out[3])
{
    double ca = cos(a1), sa = sin(a1), E = t->E, rb = t->rb, a2 = t->alpha2;
    double yc = rb * (ca + (a1 + a2) * sa), hc = rb * ((a1 + a2) * ca - sa);
    double dc = yc - rb * cos(a2);
    double m0 = ca * dc - sa * hc, m1 = ca * (dc + d1) - sa * hc;
    out[0] = 3.0 / (2 * E * hb * hb * hb) * (m1 * m1 * m1 - m0 * m0 * m0) / (3 * ca);
    out[1] = 1.2 * (1 + t->nu) * ca * ca * d1 / (E * hb);
    out[2] = sa * sa * d1 / (2 * E * hb);
}

void gd_ms_tooth_beam_terms(const gd_ms_tooth *t, double tc, double rtol, int n, double out[3])
{
    double a1 = tc - t->alpha2, gend, d1, hb;
    clamp(t, &gend, &d1, &hb);
    beam_ctx c = {t, cos(a1), sin(a1), 0};
    for (int k = 0; k < 3; k++) {
        c.term = k;
        out[k] = n > 0 ? gd_ms_gauss_legendre(integrand, &c, -a1, gend, n)
                       : gd_ms_integrate(integrand, &c, -a1, gend, rtol, NULL);
    }
    if (d1 > 0) {
        double s[3];
        straight_terms(t, a1, d1, hb, s);
        for (int k = 0; k < 3; k++)
            out[k] += s[k];
    }
}

double gd_ms_tooth_beam_compliance(const gd_ms_tooth *t, double tc, double rtol, int *neval)
{
    double a1 = tc - t->alpha2, gend, d1, hb;
    clamp(t, &gend, &d1, &hb);
    beam_ctx c = {t, cos(a1), sin(a1), 3};
    double v = gd_ms_integrate(integrand, &c, -a1, gend, rtol, neval);
    if (d1 > 0) {
        double s[3];
        straight_terms(t, a1, d1, hb, s);
        v += s[0] + s[1] + s[2];
    }
    return v;
}
