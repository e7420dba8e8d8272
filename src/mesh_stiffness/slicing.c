/* Which tooth pairs and face-width slices are in contact at a driver angle, and their
 * summed stiffness ([JMSTHelical] Sec. 2.1 and Eq. 1: K = sum k_i, Lsf_i = k_i / K).
 *
 * Pair m touches, on the front face, at s_m = s_A + (theta/T + m) p_bt along the
 * transverse line of action (T = 2 pi / z1, p_bt the transverse base pitch); at axial
 * position y the helix shifts it to s_m - y tan(beta_b). A point is in contact when
 * s_A <= s < s_E. The face width is cut into thin spur slices; a slice only partly in
 * contact counts with its active width, evaluated at the middle of that width, so the
 * stiffness grows continuously as a contact line enters (no jump of one slice). The
 * contact analysis lists the slices (with their face position) instead of summing them. */
#include <math.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static double eps_gamma(const gd_ms_slicing *sl)
{
    const gd_gear_pair_derived *d = sl->d;
    return (d->contact_length + d->overlap_length) / d->base_pitch_transverse;
}

int gd_ms_slicing_capacity(const gd_ms_slicing *sl)
{
    int N = sl->slices > 0 ? sl->slices : 1;
    return ((int)ceil(eps_gamma(sl)) + 3) * (N + 1);
}

/* Records one slice (when listing) and returns its stiffness. */
static double add(gd_ms_contact *out, int *n, double s, double y, double w, double k, int slice)
{
    if (out) out[*n] = (gd_ms_contact){s, y, w, k, 0, slice};
    (*n)++;
    return k;
}

double gd_ms_slicing_contacts(const gd_ms_slicing *sl, double theta, gd_ms_contact *out, int *nout,
                              double *pair_k, int *npairs)
{
    const gd_gear_pair_derived *d = sl->d;
    const double p = d->base_pitch_transverse, sA = d->contact_start, sE = d->contact_end;
    const double b = sl->face_width, gb = d->overlap_length, tb = gb / b;
    const double eps_g = eps_gamma(sl);
    const double phase = theta / d->mesh_period;
    const int N = sl->slices > 0 ? sl->slices : 1;
    const double db = b / N;
    if (pair_k) memset(pair_k, 0, (size_t)sl->nslots * sizeof *pair_k);
    double total = 0;
    int count = 0, n = 0;
    long mlo = (long)ceil(-phase - 1e-12), mhi = (long)floor(eps_g - phase) + 1;
    for (long m = mlo; m <= mhi; m++) {
        double q = phase + (double)m;           /* pitches since the front face entered */
        if (q < -1e-12 || q >= eps_g) continue; /* tolerance: rounding of theta/T */
        if (q < 0) q = 0;
        double sm = sA + q * p, km = 0, width = 0;
        int n0 = n;
        if (gb <= 0) {
            if (sm < sE) {
                double kl = sl->law(sm, sl->law_ctx);
                if (N == 1)
                    km = add(out, &n, sm, 0.5 * b, b, b * kl, 0);
                else
                    for (int i = 0; i < N; i++)
                        km += add(out, &n, sm, (i + 0.5) * db, db, db * kl, i);
                width = b;
            }
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
                        double y = 0.5 * (ya + yb);
                        km += add(out, &n, sm - y * tb, y, yb - ya,
                                  (yb - ya) * sl->law(sm - y * tb, sl->law_ctx), i);
                        width += yb - ya;
                    }
                }
            }
        }
        /* a contact line shorter than 1e-9 b is rounding, not contact */
        if (km > 0 && width > 1e-9 * b) {
            count++;
            total += km;
            int slot = (int)floor(q + 1e-9);
            if (slot >= sl->nslots) slot = sl->nslots - 1;
            if (pair_k) pair_k[slot] += km;
            if (out)
                for (int j = n0; j < n; j++)
                    out[j].slot = slot;
        } else {
            n = n0;
        }
    }
    if (npairs) *npairs = count;
    if (nout) *nout = n;
    return total;
}

double gd_ms_slicing_eval(const gd_ms_slicing *sl, double theta, double *pair_k, int *npairs)
{
    return gd_ms_slicing_contacts(sl, theta, NULL, NULL, pair_k, npairs);
}
