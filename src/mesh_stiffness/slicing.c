/* Which tooth pairs and face-width slices are in contact at a driver angle, and their
 * summed stiffness (002_... Sec. 2.1 and Eq. 1: K = sum k_i, Lsf_i = k_i / K).
 *
 * Pair m touches, on the front face, at s_m = s_A + (theta/T + m) p_bt along the
 * transverse line of action (T = 2 pi / z1, p_bt the transverse base pitch); at axial
 * position y the helix shifts it to s_m - y tan(beta_b). A point is in contact when
 * s_A <= s < s_E. The face width is cut into thin spur slices; a slice only partly in
 * contact counts with its active width, evaluated at the middle of that width, so the
 * stiffness grows continuously as a contact line enters (no jump of one slice). */
#include <math.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

double gd_ms_slicing_eval(const gd_ms_slicing *sl, double theta, double *pair_k, int *npairs)
{
    const gd_gear_pair_derived *d = sl->d;
    const double p = d->base_pitch_transverse, sA = d->contact_start, sE = d->contact_end;
    const double b = sl->face_width, gb = d->overlap_length, tb = gb / b;
    const double eps_g = (d->contact_length + gb) / p;
    const double phase = theta / d->mesh_period;
    const int N = sl->slices > 0 ? sl->slices : 1;
    const double db = b / N;
    if (pair_k) memset(pair_k, 0, (size_t)sl->nslots * sizeof *pair_k);
    double total = 0;
    int count = 0;
    long mlo = (long)ceil(-phase - 1e-12), mhi = (long)floor(eps_g - phase) + 1;
    for (long m = mlo; m <= mhi; m++) {
        double q = phase + (double)m;           /* pitches since the front face entered */
        if (q < -1e-12 || q >= eps_g) continue; /* tolerance: rounding of theta/T */
        if (q < 0) q = 0;
        double sm = sA + q * p, km = 0, width = 0;
        if (gb <= 0) {
            if (sm < sE) km = b * sl->law(sm, sl->law_ctx), width = b;
        } else {
            double ylo = (sm - sE) / tb, yhi = (sm - sA) / tb;
            if (ylo < 0) ylo = 0;
            if (yhi > b) yhi = b;
            if (yhi > ylo) {
                int i0 = (int)floor(ylo / db), i1 = (int)ceil(yhi / db);
                if (i0 < 0) i0 = 0;
                if (i1 > N) i1 = N;
                for (int i = i0; i < i1; i++) {
                    double ya = i * db, yb = (i + 1) * db;
                    if (ya < ylo) ya = ylo;
                    if (yb > yhi) yb = yhi;
                    if (yb > ya) {
                        km += (yb - ya) * sl->law(sm - 0.5 * (ya + yb) * tb, sl->law_ctx);
                        width += yb - ya;
                    }
                }
            }
        }
        /* a contact line shorter than 1e-9 b is rounding, not contact */
        if (km > 0 && width > 1e-9 * b) {
            count++;
            total += km;
            if (pair_k) {
                int slot = (int)floor(q + 1e-9);
                if (slot >= sl->nslots) slot = sl->nslots - 1;
                pair_k[slot] += km;
            }
        }
    }
    if (npairs) *npairs = count;
    return total;
}
