/* Fillet-foundation compliance of a tooth on a ring-shaped body (Sainsot, Velex &
 * Duverger, J. Mech. Des. 126, 2004; [JMSTHelical] Eq. 10), per unit face width:
 *   1/k_f = cos^2(a1)/E { L*(u_f/S_f)^2 + M*(u_f/S_f) + P*(1 + Q* tan^2 a1) }
 * with u_f the distance from the root circle to where the load line crosses the tooth
 * centre line (rb/cos a1 - rf), S_f = 2 rf theta_f the root thickness, and
 * X* = A/theta_f^2 + B h^2 + C h/theta_f + D/theta_f + E h + F, h = rf/r_bore. */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const double COEF[4][6] = {
    /*        A            B            C            D          E        F */
    {-5.574e-5, -1.9986e-3, -2.3015e-4, 4.7702e-3, 0.0271, 6.8045},  /* L* */
    {60.111e-5, 28.100e-3, -83.431e-4, -9.9256e-3, 0.1624, 0.9086},  /* M* */
    {-50.952e-5, 185.50e-3, 0.0538e-4, 53.300e-3, 0.2895, 0.9236},   /* P* */
    {-6.2042e-5, 9.0889e-3, -4.0964e-4, 7.8297e-3, -0.1472, 0.6904}, /* Q* */
};

double gd_ms_foundation_formula(double a1, double uf, double Sf, double thf, double h, double E)
{
    double X[4];
    for (int i = 0; i < 4; i++) {
        const double *c = COEF[i];
        X[i] = c[0] / (thf * thf) + c[1] * h * h + c[2] * h / thf + c[3] / thf + c[4] * h + c[5];
    }
    double q = uf / Sf, ta = tan(a1), ca = cos(a1);
    return ca * ca / E * (X[0] * q * q + X[1] * q + X[2] * (1 + X[3] * ta * ta));
}

double gd_ms_fillet_compliance(const gd_ms_tooth *t, double tc)
{
    double a1 = tc - t->alpha2;
    double thf = gd_ms_tooth_root_half_angle(t);
    double uf = t->rb / cos(a1) - t->rf;
    return gd_ms_foundation_formula(a1, uf, 2 * t->rf * thf, thf, t->rf / t->rbore, t->E);
}
