/* ISO 6336-1:2006 Method B tooth stiffness (clause 9), per unit face width:
 *   q' = C1 + C2/zn1 + C3/zn2 + C4 x1 + C5 x1/zn1 + C6 x2 + C7 x2/zn2 + C8 x1^2 + C9 x2^2
 *   c'_th = 1/q' [N/(mm um)],  c' = c'_th C_M C_R C_B cos(beta) (E / E_steel),
 *   c_gamma_alpha = c' (0.75 eps_alpha + 0.25),  c_gamma_beta = 0.85 c_gamma_alpha,
 * with zn = z / (cos^2(beta_b) cos(beta)), C_M = 0.8, C_R the gear blank factor
 * 1 + ln(b_s/b) / (5 exp(s_R / (5 m_n))) for webbed bodies, and the basic rack factor
 * C_B = [1 + 0.5 (1.2 - h_fP/m_n)] [1 - 0.02 (20 deg - alpha_n)]. Valid for steel pairs,
 * x1 >= x2, -0.5 <= x1 + x2 <= 2 and a line load of at least 100 N/mm (assumed).
 * ISO refers c_gamma to the transverse plane (as used with the reduced mass of its
 * dynamic factor); 1 N/(mm um) = 1e9 N/m^2. */
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const double C[10] = {0,        0.04723,  0.15551,  0.25791, -0.00635,
                             -0.11654, -0.00193, -0.24188, 0.00529, 0.00182};

void gd_ms_iso6336(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d, gd_ms_iso *iso)
{
    double cb = cos(d->base_helix_angle), beta = g->helix_angle;
    double zn1 = g->gear[0].teeth / (cb * cb * cos(beta));
    /* internal pairs: zn2 -> infinity (ISO 6336-1:2006, 9.3.2.1: the ring as a rack) */
    double zn2 = d->internal ? HUGE_VAL : g->gear[1].teeth / (cb * cb * cos(beta));
    double x1 = g->gear[0].profile_shift, x2 = g->gear[1].profile_shift;
    double q = C[1] + C[2] / zn1 + C[3] / zn2 + C[4] * x1 + C[5] * x1 / zn1 + C[6] * x2 +
               C[7] * x2 / zn2 + C[8] * x1 * x1 + C[9] * x2 * x2;
    iso->c_th = 1.0 / q;
    iso->C_M = 0.8;
    double cr = 0, cbr = 0;
    for (int i = 0; i < 2; i++) {
        const gd_gear_geometry *w = &g->gear[i];
        double ri = 1;
        if (w->web_thickness > 0) {
            double ro = w->web_outer_radius > 0 ? w->web_outer_radius
                                                : d->root_radius[i] - 2 * g->normal_module;
            double sR = d->root_radius[i] - ro; /* rim thickness */
            double bs = w->web_thickness / g->face_width;
            if (bs < 0.2) bs = 0.2; /* ISO range 0.2 <= b_s/b <= 1.2 */
            if (bs > 1.2) bs = 1.2;
            if (sR < g->normal_module) sR = g->normal_module;
            ri = 1 + log(bs) / (5 * exp(sR / (5 * g->normal_module)));
        }
        cr += 0.5 * ri;
        double hfp = w->dedendum_coef;
        double an_deg = g->normal_pressure_angle * 180 / GD_MS_PI;
        cbr += 0.5 * (1 + 0.5 * (1.2 - hfp)) * (1 - 0.02 * (20 - an_deg));
    }
    iso->C_R = cr;
    iso->C_B = cbr;
    double E1 = g->gear[0].E, E2 = g->gear[1].E;
    iso->E_factor = (2 * E1 * E2 / (E1 + E2)) / 2.06e11;
    double cs = iso->c_th * iso->C_M * iso->C_R * iso->C_B * cos(beta) * iso->E_factor;
    iso->c_single = cs * 1e9;
    iso->c_gamma_alpha = iso->c_single * (0.75 * d->contact_ratio_transverse + 0.25);
    iso->c_gamma_beta = 0.85 * iso->c_gamma_alpha;
}
