/* Harmonic truncation: the error estimate of a point (the change of its records between H
 * and 2 H) and the memory one harmonic balance workspace needs, which caps H.
 *
 * Why the change of the records and not the residual's truncated harmonics: with a TVMS
 * from the tooth geometry the force carries mesh harmonics up to ~25 times the mesh
 * frequency, the response's high harmonics feed back into the low ones through the
 * stiffness modulation, and the aliasing of the AFT samples (4 (H + 1)) moves with H;
 * only a solution at a refined H sees all three. If the error falls as H^-p, the change
 * from H to 2 H is (1 - 2^-p) times the error at H and 2^p - 1 times the error at 2 H:
 * an estimate of the first and, for p >= 1, a bound of the second. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "periodic/periodic_impl.h"

static double rel_change(double a, double b)
{
    if (a == b) return 0.0;
    double d = fabs(a - b), m = fabs(b);
    return m > 0 ? d / m : INFINITY;
}

/* The largest magnitude in a record's statistics: |mean| + peak-to-peak bounds |value|. */
static double record_size(const gd_per_record_stats *s)
{
    return fabs(s->mean) + s->peak_to_peak;
}

void gd_hb_truncation(const gd_per_record_stats *coarse, int Hc, gd_per_record_stats *fine, int Hf,
                      int nrec, const double *zero, double *p2p, double *amp)
{
    *p2p = *amp = 0.0;
    for (int r = 0; r < nrec; r++) {
        const gd_per_record_stats *a = &coarse[r];
        gd_per_record_stats *b = &fine[r];
        /* a record that is zero to rounding at both H (the tilt of a spur gear: 1e-20 rad
         * against 5e-5 rad of torsion) has nothing to converge: its relative changes are
         * noise of order 1 and drove --harmonics auto on [JMSTHelical] at 0 deg to
         * H = 18943 */
        if (zero && record_size(a) <= zero[r] && record_size(b) <= zero[r]) {
            b->p2p_error = b->amp_error = 0.0;
            continue;
        }
        double e = rel_change(a->peak_to_peak, b->peak_to_peak);
        /* a record that does not move (a constant force, a contact state that never
         * changes) has no peak-to-peak to be relative to: its change is absolute */
        if (!(b->peak_to_peak > 1e-12 * fabs(b->mean)) && b->peak_to_peak <= 1e-300)
            e = fabs(a->peak_to_peak - b->peak_to_peak);
        double m = 0.0, d = 0.0;
        if (a->amplitude && b->amplitude) {
            for (int k = 1; k <= Hf; k++)
                m = b->amplitude[k] > m ? b->amplitude[k] : m;
            for (int k = 1; k <= Hc && k <= Hf; k++) {
                double x = fabs(a->amplitude[k] - b->amplitude[k]);
                d = x > d ? x : d;
            }
        }
        double ea = m > 0 ? d / m : 0.0;
        b->p2p_error = e;
        b->amp_error = ea;
        *p2p = e > *p2p ? e : *p2p;
        *amp = ea > *amp ? ea : *amp;
    }
}

void gd_hb_record_zero(const gd_tr_record *rec, int nrec, const double *X, int n, int H, double w,
                       double *zero)
{
    double xmax = 0.0;
    for (int i = 0; i < n; i++)
        xmax = fabs(X[i]) > xmax ? fabs(X[i]) : xmax;
    for (int r = 0; r < nrec; r++)
        zero[r] = rec[r].kind == GD_REC_DISP  ? 1e-12 * xmax
                  : rec[r].kind == GD_REC_VEL ? 1e-12 * xmax * H * fabs(w)
                                              : 0.0;
}

double gd_hb_coef_change(const double *Xc, int nc, const double *Xf, int nfine)
{
    double d = 0.0, s = 0.0;
    for (int i = 0; i < nfine; i++) {
        double x = i < nc ? Xc[i] - Xf[i] : Xf[i];
        d += x * x;
        s += Xf[i] * Xf[i];
    }
    return s > 0 ? sqrt(d / s) : sqrt(d);
}

double gd_hb_memory(int nf, int H, int N, int nterm, int ngroup, long knz)
{
    const double nh = 2.0 * H + 1, n = nf * nh;
    /* samples and spectra (tq, tv, tf, the term derivatives, gd_hb_samples' buffers) */
    double b = 8.0 * ((double)nf * N * 4 + 2.0 * nterm * N);
    b += 8.0 * n * 12; /* the Newton and continuation vectors */
    double r = (double)ngroup * nh;
    if (n >= 2000 && r <= n / 4) {
        /* low rank: L^-1 U (r x 2 nf), the complex block factors (KLU fill of the union
         * pattern, ~4x its entries) and the capacitance: dense, r^2 and every term's
         * harmonic coupling Gall; iterative (capacitance.c), the GMRES basis (61 + 3
         * vectors of r), the samples again and the transfer scalars */
        b += 8.0 * r * 2 * nf + 16.0 * (H + 1) * 4.0 * (double)(knz + nf);
        if (r >= GD_HB_CAP_CROSSOVER)
            b += 8.0 * r * 64 + 16.0 * nterm * N + 16.0 * (H + 1) * nterm * (ngroup + 1);
        else
            b += 8.0 * r * r + 8.0 * nterm * nh * nh;
    } else {
        /* the whole sparse LU: the linear part per harmonic plus every term's dense
         * coupling over the harmonics on its DOFs (Gall); fill ~3x */
        b += 8.0 * nterm * nh * nh;
        b += 3.0 * 12.0 * (4.0 * (double)knz * nh + (double)nterm * 4 * nh * nh);
    }
    return b;
}

double gd_hb_memory_limit(const gd_periodic_options *opt)
{
    if (opt->memory_limit > 0) return opt->memory_limit;
    long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
    if (pages <= 0 || psize <= 0) return 4e9;
    return 0.5 * (double)pages * (double)psize;
}

void gd_hb_memory_params_tr(gd_transient *tr, int *nf, int *nterm, int *ngroup, long *knz)
{
    const gd_tr_term *term = NULL;
    int nt = gd_transient_terms(tr, &term);
    *nf = gd_transient_nstates(tr) / 2;
    hb h;
    memset(&h, 0, sizeof h);
    h.nterm = nt > 0 ? nt : 0;
    h.term = term;
    *nterm = h.nterm;
    *ngroup = gd_hb_term_groups(&h, NULL, NULL);
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    *knz = (long)K.colptr[K.n] + M.colptr[M.n] + D.colptr[D.n];
}

int gd_hb_memory_params(const gd_system *sys, const gd_transient_spec *spec, double speed, int *nf,
                        int *nterm, int *ngroup, long *knz)
{
    gd_transient *tr = NULL;
    gd_error err;
    if (gd_transient_new(sys, spec, speed, &tr, &err)) return 1;
    gd_hb_memory_params_tr(tr, nf, nterm, ngroup, knz);
    gd_transient_free(tr);
    return 0;
}

int gd_hb_samples_for(int H)
{
    int N = 16;
    while (N < 4 * (H + 1))
        N *= 2;
    return N;
}

double gd_periodic_memory(const gd_system *sys, const gd_transient_spec *spec, double speed, int H)
{
    int nf, nt, ng;
    long knz;
    if (H < 1 || gd_hb_memory_params(sys, spec, speed, &nf, &nt, &ng, &knz)) return NAN;
    return gd_hb_memory(nf, H, gd_hb_samples_for(H), nt, ng, knz);
}
