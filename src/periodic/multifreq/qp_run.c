/* The branch over speed by multi-frequency harmonic balance (qphb_impl.h): one problem per
 * speed, its base frequencies, Newton on the torus from the last point's coefficients,
 * the order H raised until two orders' records agree (the truncation estimate of the
 * single-frequency solver, truncation.c), and the records' statistics over the torus. */
#include <complex.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/multifreq/qphb_impl.h"
#include "transient/transient_impl.h"

/* The order of the first torus with --harmonics auto, and the largest tried (on the
 * co-prime gearbox, examples/gearbox_coprime.yaml, order 48 puts the dynamic mesh forces
 * within 2 % of a long transient: docs/periodic.md, "Several base frequencies"). */
#define QP_H_FIRST 32
#define QP_H_MAX 48
/* --harmonics auto raises the order by half (32, 48): at 900 rpm the mesh forces' standard
 * deviation at H = 24 is 9 % (p2p 15 %) off a long transient, at 32 and 48 within 1.6 %
 * (p2p 1.2 %), so an estimate between 24 and 48 measured H = 24's error (16 % on the
 * peak-to-peak), not that of the order reported */
#define NEXT_ORDER(H, adaptive) ((adaptive) ? (H) + (H) / 2 : 2 * (H))
/* --harmonics auto takes the next order (72) where QP_H_MAX harmonics of the highest base
 * stay below QP_W_REACH times the highest natural frequency (estimated by the largest
 * K_ii / M_ii): on the co-prime gearbox (mesh modes at 8.2 kHz) order 48 is 7 % (600 rpm)
 * and 4.6 % (700 rpm) off a long transient's peak-to-peak, 72 within 1.5 %; at 800 rpm
 * (48 harmonics reach 1.8 times the estimate) 48 is within 1.9 % */
#define QP_W_REACH 1.7

/* sqrt(max_i K_ii / M_ii) over the free DOFs: about the highest natural frequency */
static double top_frequency(const gd_transient *tr)
{
    gd_csc M, D, K;
    gd_transient_matrices(tr, &M, &D, &K);
    double w2 = 0.0;
    for (int j = 0; j < M.n; j++) {
        double m = 0.0, k = 0.0;
        for (int p = M.colptr[j]; p < M.colptr[j + 1]; p++)
            if (M.rowind[p] == j) m = M.values[p];
        for (int p = K.colptr[j]; p < K.colptr[j + 1]; p++)
            if (K.rowind[p] == j) k = K.values[p];
        if (m > 0.0) w2 = fmax(w2, k / m);
    }
    return sqrt(w2);
}

static void free_stats(gd_per_record_stats *s, int nrec)
{
    if (!s) return;
    for (int k = 0; k < nrec; k++) {
        free(s[k].amplitude);
        free(s[k].phase_deg);
    }
    free(s);
}

/* Statistics of record r (values v over Nt samples): mean, rms, peak-to-peak. */
static void basic_stats(const double *v, long Nt, gd_per_record_stats *s)
{
    double mean = 0.0, sq = 0.0, lo = INFINITY, hi = -INFINITY;
    for (long p = 0; p < Nt; p++) {
        mean += v[p];
        sq += v[p] * v[p];
        lo = fmin(lo, v[p]);
        hi = fmax(hi, v[p]);
    }
    s->mean = mean / Nt;
    s->rms = sqrt(sq / Nt);
    s->peak_to_peak = hi - lo;
    s->p2p_error = s->amp_error = NAN;
}

/* Samples per cycle of the highest base on the slice: a mesh force whose stiffness steps
 * at the contact-ratio changes (a spline through the computed table rings there) has
 * narrow peaks; its peak-to-peak is that of a transient's output at the same sampling
 * (the co-prime gearbox at 1700 rpm: 426.7 N at 512 per cycle, 397.1 N at 128) */
#define SLICE_PER_CYCLE 512

/* The records on the physical slice theta = W t over one common period (bases of common
 * fundamental w0 = common, each harmonic k at the whole order n = k . W / w0): the
 * coefficients gathered by order into one spectrum, q(t) and q'(t) by one inverse FFT of
 * Ns samples, the records evaluated by the problem's own laws at each t. vals: nrec x Ns
 * (the caller frees). 0 ok, 1 no memory or orders too high. */
static int slice_values(gd_qp *q, const double *X, const gd_tr_record *rec, int nrec, double **vals,
                        long *Ns_out, double *w0_out)
{
    const int nf = q->nf;
    const double w0 = q->b->common;
    long top = 0;
    long *ord = malloc((size_t)q->T.nk * sizeof *ord);
    if (!ord) return 1;
    for (int j = 0; j < q->T.nk; j++) {
        double w = 0.0;
        for (int g = 0; g < q->T.d; g++)
            w += q->T.k[j * q->T.d + g] * q->T.W[g];
        ord[j] = lround(w / w0);
        if (labs(ord[j]) > top) top = labs(ord[j]);
    }
    long Ns = 64;
    while (Ns < 4 * top + 4 || Ns < SLICE_PER_CYCLE * q->b->order)
        Ns *= 2;
    if (Ns > (1L << 24)) {
        free(ord);
        return 1;
    }
    fftw_complex *sp = fftw_malloc((size_t)Ns * 2 * sizeof *sp);
    double *qs = malloc((size_t)Ns * 2 * nf * sizeof *qs), *y = q->y;
    double *v = malloc((size_t)(nrec > 0 ? nrec : 1) * Ns * sizeof *v),
           *out = malloc((size_t)(nrec > 0 ? nrec : 1) * sizeof *out);
    fftw_plan pl = sp ? fftw_plan_dft_1d((int)Ns, sp, sp, FFTW_BACKWARD, FFTW_ESTIMATE) : NULL;
    int rc = 1;
    if (!sp || !qs || !v || !out || !pl) goto done;
    for (int i = 0; i < nf; i++)
        for (int deriv = 0; deriv < 2; deriv++) {
            memset(sp, 0, (size_t)Ns * sizeof *sp);
            if (!deriv) sp[0] = X[i];
            for (int j = 1; j < q->T.nk; j++) {
                double c = X[(size_t)(2 * j - 1) * nf + i], s = X[(size_t)2 * j * nf + i];
                double complex z = 0.5 * (c - I * s); /* at +n; its conjugate at -n */
                long n = ord[j];
                if (deriv) z *= I * (double)n * w0;
                sp[((n % Ns) + Ns) % Ns] += z;
                sp[((-n % Ns) + Ns) % Ns] += conj(z);
            }
            fftw_execute(pl);
            for (long p = 0; p < Ns; p++)
                qs[(size_t)p * 2 * nf + deriv * nf + i] = creal(sp[p]);
        }
    q->tr->law_time = NULL; /* on the slice every law is read at the physical time */
    for (long p = 0; p < Ns; p++) {
        const double t = 6.28318530717958647692 / w0 * (double)p / (double)Ns;
        memcpy(y, qs + (size_t)p * 2 * nf, 2 * (size_t)nf * sizeof *y);
        gd_transient_record_values(q->tr, rec, nrec, t, y, out);
        for (int r = 0; r < nrec; r++)
            v[(size_t)r * Ns + p] = out[r];
    }
    *vals = v;
    v = NULL;
    *Ns_out = Ns;
    *w0_out = w0;
    rc = 0;
done:
    if (pl) fftw_destroy_plan(pl);
    fftw_free(sp);
    free(qs);
    free(v);
    free(out);
    free(ord);
    return rc;
}

/* The records' statistics: on the physical slice over one common period where the bases
 * have one (slice_values), else over the grid of the torus (the time average of a
 * quasi-periodic response is its torus mean; its extremes those of the torus); and the
 * amplitudes and phases of the harmonics m W_1 (m = 0..2 H: the point reports 0..H, the
 * truncation estimate compares the next order's range) of the first base. 0 ok. */
static int record_stats(gd_qp *q, const double *X, const gd_tr_record *rec, int nrec,
                        gd_per_record_stats **out)
{
    const int nf = q->nf, H = q->T.H;
    gd_per_record_stats *s = calloc((size_t)(nrec > 0 ? nrec : 1), sizeof *s);
    if (!s) return 1;
    double *val = NULL, w0 = 0.0;
    /* the phase of base 1 at sample p, in cycles: n0 p / cyc (slice: n0 cycles of it in
     * the Nt samples; grid: row p / stride of N_1) */
    long Nt = 0, stride = 1, cyc = 0, n0 = 1;
    if (q->b->common > 0 && !slice_values(q, X, rec, nrec, &val, &Nt, &w0)) {
        n0 = lround(q->T.W[0] / w0);
        cyc = Nt;
    } else {
        Nt = q->T.Ntot;
        val = malloc((size_t)(nrec > 0 ? nrec : 1) * Nt * sizeof *val);
        double *v1 = malloc((size_t)(nrec > 0 ? nrec : 1) * sizeof *v1);
        if (!val || !v1) {
            free(s);
            free(val);
            free(v1);
            return 1;
        }
        if (gd_qp_samples(q, X)) {
            free(s);
            free(val);
            free(v1);
            return 1;
        }
        for (long p = 0; p < Nt; p++) {
            const double t = gd_qp_point_times(q, p);
            memcpy(q->y, q->qs + (size_t)p * nf, (size_t)nf * sizeof *q->y);
            memcpy(q->y + nf, q->vs + (size_t)p * nf, (size_t)nf * sizeof *q->y);
            gd_transient_record_values(q->tr, rec, nrec, t, q->y, v1);
            for (int r = 0; r < nrec; r++)
                val[(size_t)r * Nt + p] = v1[r];
        }
        q->tr->law_time = NULL;
        free(v1);
        stride = Nt / q->T.N[0]; /* row-major: the first base varies slowest */
        cyc = q->T.N[0];
    }
    /* the amplitudes up to 2 H (the next order's, for the truncation estimate) by one
     * real FFT per record of the samples folded by the phase of base 1: L phases (the
     * slice: every sample, base 1 at bin n0 m; the grid: the rows of N_1) */
    const int M = 2 * H;
    const long L = cyc;
    double *fold = fftw_malloc((size_t)L * sizeof *fold);
    fftw_complex *spec = fftw_malloc((size_t)(L / 2 + 1) * sizeof *spec);
    fftw_plan pl = fold && spec ? fftw_plan_dft_r2c_1d((int)L, fold, spec, FFTW_ESTIMATE) : NULL;
    int bad = !pl;
    for (int r = 0; r < nrec && !bad; r++) {
        const double *v = val + (size_t)r * Nt;
        basic_stats(v, Nt, &s[r]);
        s[r].amplitude = calloc((size_t)M + 1, sizeof(double));
        s[r].phase_deg = calloc((size_t)M + 1, sizeof(double));
        if (!s[r].amplitude || !s[r].phase_deg) {
            bad = 1;
            break;
        }
        memset(fold, 0, (size_t)L * sizeof *fold);
        for (long p = 0; p < Nt; p++)
            fold[p / stride] += v[p];
        fftw_execute(pl);
        for (int m = 0; m <= M && 2 * m * n0 < L; m++) {
            const double complex z = spec[m * n0] / (double)Nt;
            const double re = creal(z), im = cimag(z);
            /* x = A cos(m theta + phi): coefficient of e^{i m theta} is A e^{i phi} / 2 */
            s[r].amplitude[m] = m ? 2.0 * hypot(re, im) : fabs(re);
            s[r].phase_deg[m] = m ? atan2(im, re) * 57.29577951308232 : 0.0;
        }
    }
    if (pl) fftw_destroy_plan(pl);
    fftw_free(fold);
    fftw_free(spec);
    free(val);
    if (bad) {
        free_stats(s, nrec);
        return 1;
    }
    *out = s;
    return 0;
}

/* Xc (harmonics kc, nkc of them, d entries each) onto the set of T (Xf zeroed first):
 * each harmonic by value (another order, or the last speed's solution). */
static void pad(const double *Xc, const int *kc, int nkc, int nf, const gd_qp_torus *T, double *Xf)
{
    memset(Xf, 0, (size_t)gd_qp_unknowns(T, nf) * sizeof *Xf);
    memcpy(Xf, Xc, (size_t)nf * sizeof *Xf);
    for (int j = 1; j < nkc; j++) {
        int f = gd_qp_torus_find(T, kc + (size_t)j * T->d);
        if (f <= 0) continue;
        memcpy(Xf + (size_t)(2 * f - 1) * nf, Xc + (size_t)(2 * j - 1) * nf,
               2 * (size_t)nf * sizeof *Xf);
    }
}

/* Per record the change of the peak-to-peak (relative to it) and of the amplitudes
 * (relative to their largest, k >= 1) from the coarse order to the fine one, kept in
 * the fine statistics; the largest over the records in *p2p, *amp (the rule of the
 * single-frequency estimate, truncation.c). Without records: the change of the
 * coefficients, relative to their norm. */
struct qp_sol;
static void truncation(const struct qp_sol *c, struct qp_sol *f, int nrec, double *p2p,
                       double *amp);

typedef struct qp_sol {
    int H;
    long n;
    double *X;
    int *k, nk, d; /* its harmonics (nk x d) */
    gd_per_record_stats *st;
    int ok, iters, condensed;
    long matvecs;
    double resid;
    char msg[200];
} qp_sol;

static void truncation(const qp_sol *c, qp_sol *f, int nrec, double *p2p, double *amp)
{
    *p2p = *amp = 0.0;
    for (int r = 0; r < nrec; r++) {
        const gd_per_record_stats *a = &c->st[r];
        gd_per_record_stats *b = &f->st[r];
        double dp = b->peak_to_peak > 0 ? fabs(b->peak_to_peak - a->peak_to_peak) / b->peak_to_peak
                    : fabs(b->peak_to_peak - a->peak_to_peak) > 0 ? 1.0
                                                                  : 0.0;
        double top = 0.0, da = 0.0;
        for (int k = 1; k <= f->H; k++)
            top = fmax(top, b->amplitude[k]);
        for (int k = 1; k <= f->H; k++) {
            /* the coarse statistics hold the amplitudes up to 2 H (record_stats): its set
             * holds these harmonics too, they were only not reported */
            double ak = k <= 2 * c->H ? a->amplitude[k] : 0.0;
            da = fmax(da, fabs(b->amplitude[k] - ak));
        }
        da = top > 0 ? da / top : 0.0;
        b->p2p_error = dp;
        b->amp_error = da;
        *p2p = fmax(*p2p, dp);
        *amp = fmax(*amp, da);
    }
    if (nrec) return;
    /* the coefficients by harmonic value (the fine set holds the coarse one) */
    const int nf = (int)(f->n / (2L * f->nk - 1)), d = f->d;
    double num = 0.0, den = 0.0;
    for (long i = 0; i < f->n; i++)
        den += f->X[i] * f->X[i];
    for (int j = 0; j < f->nk; j++) {
        int jc = -1;
        for (int m = 0; m < c->nk && jc < 0; m++)
            if (!memcmp(c->k + (size_t)m * d, f->k + (size_t)j * d, (size_t)d * sizeof *c->k))
                jc = m;
        const int rows = j ? 2 : 1;
        for (int r = 0; r < rows; r++)
            for (int i = 0; i < nf; i++) {
                const long o = (long)(j ? 2 * j - 1 + r : 0) * nf + i;
                const double xc = jc < 0 ? 0.0 : c->X[(long)(jc ? 2 * jc - 1 + r : 0) * nf + i];
                num += (f->X[o] - xc) * (f->X[o] - xc);
            }
    }
    *p2p = *amp = den > 0 ? sqrt(num / den) : 0.0;
}

static void sol_clear(qp_sol *s, int nrec)
{
    free(s->X);
    free(s->k);
    free_stats(s->st, nrec);
    memset(s, 0, sizeof *s);
}

/* Solves the problem on the torus of order H from x0 (another order's or speed's
 * solution, may be NULL). 0 done (s->ok says whether it converged), 1 no memory, 2 too
 * large. */
static int solve_at(gd_transient *tr, const gd_qp_bases *b, int H, const qp_sol *x0,
                    const gd_periodic_options *opt, const gd_tr_record *rec, int nrec, qp_sol *s)
{
    gd_qp q;
    memset(s, 0, sizeof *s);
    s->H = H;
    if (opt->condensed >= 0 && gd_qpc_applies(tr)) {
        gd_qpc *c = gd_qpc_new(tr, b, H, s->msg, sizeof s->msg);
        if (c) {
            int rc = 0;
            gd_qpc_view(c, &q);
            s->condensed = 1;
            s->n = q.n;
            s->nk = q.T.nk;
            s->d = q.T.d;
            s->X = calloc((size_t)q.n, sizeof *s->X);
            s->k = malloc((size_t)q.T.nk * q.T.d * sizeof *s->k);
            if (!s->X || !s->k) rc = 1;
            if (!rc) {
                memcpy(s->k, q.T.k, (size_t)q.T.nk * q.T.d * sizeof *s->k);
                if (x0 && x0->X) pad(x0->X, x0->k, x0->nk, q.nf, &q.T, s->X);
                s->ok = !gd_qpc_newton(c, s->X, opt->tol, opt->max_iter, &s->resid, &s->iters,
                                       s->msg, sizeof s->msg);
                s->matvecs = gd_qpc_matvecs(c);
                if (s->ok && record_stats(&q, s->X, rec, nrec, &s->st)) rc = 1;
            }
            gd_qp_view_release(&q);
            gd_qpc_free(c);
            return rc;
        }
        s->msg[0] = '\0'; /* the full torus below */
    }
    int rc = gd_qp_init(&q, tr, b, H, s->msg, sizeof s->msg);
    if (rc) {
        gd_qp_free(&q);
        return rc;
    }
    s->n = q.n;
    s->nk = q.T.nk;
    s->d = q.T.d;
    s->X = calloc((size_t)q.n, sizeof *s->X);
    s->k = malloc((size_t)q.T.nk * q.T.d * sizeof *s->k);
    if (!s->X || !s->k) {
        gd_qp_free(&q);
        return 1;
    }
    memcpy(s->k, q.T.k, (size_t)q.T.nk * q.T.d * sizeof *s->k);
    if (x0 && x0->X) pad(x0->X, x0->k, x0->nk, q.nf, &q.T, s->X);
    s->ok = !gd_qp_newton(&q, s->X, opt->tol, opt->max_iter, &s->resid, &s->iters, s->msg,
                          sizeof s->msg);
    s->matvecs = q.matvecs;
    if (s->ok && record_stats(&q, s->X, rec, nrec, &s->st)) rc = 1;
    gd_qp_free(&q);
    return rc;
}

/* The fine solution f projected onto the set of order H (its harmonics outside that set
 * dropped) and that projection's records into c: the truncation estimate of f's order
 * without solving the coarse order (the change the harmonics between H and f's order make
 * to the records; between two solved orders it also holds their feedback through the
 * laws, measured on the co-prime gearbox: docs/periodic.md, "Order"). 0 ok, 1 no memory. */
static int project_to(gd_transient *tr, const gd_qp_bases *b, int H, const qp_sol *f,
                      const gd_tr_record *rec, int nrec, qp_sol *c)
{
    gd_qp q;
    memset(&q, 0, sizeof q);
    memset(c, 0, sizeof *c);
    c->H = H;
    const int nf = (int)(f->n / (2L * f->nk - 1));
    if (gd_qp_torus_init(&q.T, b, H)) return 1;
    q.tr = tr;
    q.b = b;
    q.nf = nf;
    q.n = gd_qp_unknowns(&q.T, nf);
    q.ltime = malloc((size_t)(tr->nlaw > 0 ? tr->nlaw : 1) * sizeof *q.ltime);
    q.y = calloc(2 * (size_t)nf, sizeof *q.y);
    c->X = calloc((size_t)q.n, sizeof *c->X);
    c->k = malloc((size_t)q.T.nk * q.T.d * sizeof *c->k);
    int rc = !q.ltime || !q.y || !c->X || !c->k;
    if (!rc) {
        c->n = q.n;
        c->nk = q.T.nk;
        c->d = q.T.d;
        c->ok = 1;
        memcpy(c->k, q.T.k, (size_t)q.T.nk * q.T.d * sizeof *c->k);
        pad(f->X, f->k, f->nk, nf, &q.T, c->X);
        rc = record_stats(&q, c->X, rec, nrec, &c->st);
    }
    free(q.ltime);
    free(q.y);
    q.ltime = q.y = NULL;
    gd_qp_view_release(&q);
    gd_qp_torus_free(&q.T);
    return rc;
}

int gd_per_qp_probe(const gd_system *sys, const gd_transient_spec *spec, double speed,
                    double W[GD_QP_MAXD], long *order, int *nf, char *msg, size_t cap)
{
    gd_transient *tr = NULL;
    gd_error err;
    *order = 0;
    if (gd_transient_new(sys, spec, speed, &tr, &err)) {
        snprintf(msg, cap, "%s", err.message);
        return 0;
    }
    gd_qp_bases b;
    memset(&b, 0, sizeof b);
    int d = 0;
    *nf = gd_transient_nstates(tr) / 2;
    const int nc = gd_qpc_applies(tr); /* the condensed torus solves for the coordinates */
    if (nc > 0) *nf = nc;
    if (gd_transient_terms(tr, NULL) >= 0 &&
        !gd_qp_find_bases(tr, sys, spec, speed, &b, msg, cap)) {
        d = b.d;
        memcpy(W, b.W, sizeof b.W);
        *order = b.order;
    }
    gd_qp_bases_free(&b);
    gd_transient_free(tr);
    return d;
}

int gd_per_qp_run(const gd_system *sys, const gd_transient_spec *spec, const double *values,
                  int nvalues, const gd_periodic_options *opt, const gd_tr_record *records,
                  int nrecords, gd_periodic_result *res)
{
    res->points = calloc((size_t)nvalues, sizeof *res->points);
    if (!res->points) return 1;
    qp_sol prev = {0}; /* the last converged point's solution (its X and harmonics) */
    int rc = 0;
    for (int i = 0; i < nvalues && !rc; i++) {
        gd_periodic_point *p = &res->points[res->npoints++];
        p->speed = values[i];
        p->parameter = NAN;
        p->direction = 1;
        p->stable = -1;
        p->mu_max = NAN;
        p->harmonic_ok = -1;
        p->harmonic_error_p2p = p->harmonic_error_amp = NAN;
        p->method = GD_PER_MULTIFREQ;
        p->stability_method = -1;
        gd_transient *tr = NULL;
        gd_error err;
        gd_qp_bases b;
        memset(&b, 0, sizeof b);
        if (gd_transient_new(sys, spec, values[i], &tr, &err)) {
            snprintf(p->reason, sizeof p->reason, "%.255s", err.message);
            goto emit;
        }
        char why[200] = "";
        if (gd_transient_terms(tr, NULL) < 0 ||
            gd_qp_find_bases(tr, sys, spec, values[i], &b, why, sizeof why)) {
            snprintf(p->reason, sizeof p->reason, "multi-frequency harmonic balance: %.200s",
                     why[0] ? why : "cam torques with include_acceleration are not represented");
            goto emit;
        }
        if (b.d == 0) {
            snprintf(p->reason, sizeof p->reason,
                     "the period is undefined: the model has no periodic excitation");
            goto emit;
        }
        p->omega = b.W[0];
        {
            /* the order: given, or QP_H_MAX estimated against its projection onto the
             * order QP_H_FIRST, then raised by half until two orders agree */
            const int adaptive = opt->adaptive;
            int H = adaptive ? QP_H_MAX : opt->harmonics;
            const double wtop = b.W[b.d - 1], reach = QP_W_REACH * top_frequency(tr);
            const int Hauto = QP_H_MAX * wtop < reach ? NEXT_ORDER(QP_H_MAX, 1) : QP_H_MAX;
            if (adaptive && opt->max_harmonics <= 0) H = Hauto;
            const int Hcap = opt->max_harmonics > 0 ? opt->max_harmonics
                             : adaptive             ? Hauto
                                                    : 1 << 20;
            if (H > Hcap) H = Hcap;
            qp_sol a = {0}, f = {0};
            int r1 = solve_at(tr, &b, H, &prev, opt, records, nrecords, &a);
            if (r1 == 1) rc = 1;
            if (r1 || !a.ok) {
                snprintf(p->reason, sizeof p->reason, "%.255s", a.msg);
                p->harmonics = H;
                sol_clear(&a, nrecords);
                goto emit;
            }
            const int estimate = adaptive || opt->estimate;
            double ep = NAN, ea = NAN;
            int good = 0;
            if (adaptive) { /* the first estimate: the projection onto the coarse order */
                const int Hc = H * QP_H_FIRST / QP_H_MAX;
                if (Hc >= 1) {
                    if (project_to(tr, &b, Hc, &a, records, nrecords, &f)) {
                        rc = 1;
                        sol_clear(&f, nrecords);
                        sol_clear(&a, nrecords);
                        goto emit;
                    }
                    truncation(&f, &a, nrecords, &ep, &ea);
                    good = ep <= opt->harmonic_tol && ea <= opt->harmonic_tol;
                    p->harmonics_ref = Hc;
                    sol_clear(&f, nrecords);
                }
            }
            while (estimate && !good && NEXT_ORDER(a.H, adaptive) <= (adaptive ? Hcap : 2 * a.H)) {
                int r2 =
                    solve_at(tr, &b, NEXT_ORDER(a.H, adaptive), &a, opt, records, nrecords, &f);
                if (r2 == 1) rc = 1;
                if (r2 || !f.ok) {
                    char m2[120];
                    snprintf(m2, sizeof m2, "%.110s", f.msg);
                    sol_clear(&f, nrecords);
                    snprintf(p->reason, sizeof p->reason,
                             "no truncation estimate: order %d failed (%.110s)",
                             NEXT_ORDER(a.H, adaptive), m2);
                    break;
                }
                truncation(&a, &f, nrecords, &ep, &ea);
                good = ep <= opt->harmonic_tol && ea <= opt->harmonic_tol;
                p->harmonics_ref = a.H;
                if (!adaptive) { /* the fine solution only for the estimate */
                    for (int r = 0; r < nrecords; r++) {
                        a.st[r].p2p_error = f.st[r].p2p_error;
                        a.st[r].amp_error = f.st[r].amp_error;
                    }
                    p->harmonics_ref = f.H;
                    sol_clear(&f, nrecords);
                    break;
                }
                sol_clear(&a, nrecords);
                a = f;
                memset(&f, 0, sizeof f);
            }
            if (estimate && isfinite(ep)) {
                p->harmonic_error_p2p = ep;
                p->harmonic_error_amp = ea;
                p->harmonic_ok = ep <= opt->harmonic_tol && ea <= opt->harmonic_tol;
                if (!p->harmonic_ok)
                    snprintf(p->reason, sizeof p->reason,
                             "truncation estimate %.2g (peak-to-peak) and %.2g (amplitudes) "
                             "between orders %d and %d, over the tolerance %g",
                             ep, ea, p->harmonics_ref < a.H ? p->harmonics_ref : a.H,
                             p->harmonics_ref < a.H ? a.H : p->harmonics_ref, opt->harmonic_tol);
            }
            p->converged = 1;
            p->harmonics = a.H;
            p->residual = a.resid;
            p->iterations = a.iters;
            p->records = a.st;
            a.st = NULL;
            if (opt->stability) {
                char note[200] = "";
                const int nf = (int)(a.n / (2L * a.nk - 1));
                if (gd_qp_stability(tr, &b, a.X, a.k, a.nk, nf, opt, p, note, sizeof note)) rc = 1;
                if (note[0] && !p->reason[0]) snprintf(p->reason, sizeof p->reason, "%s", note);
            }
            sol_clear(&prev, nrecords);
            prev = a; /* its statistics moved to the point above */
            memset(&a, 0, sizeof a);
        }
    emit:
        gd_qp_bases_free(&b);
        gd_transient_free(tr);
        if (!p->records && nrecords) { /* a failed point: empty statistics */
            p->records = calloc((size_t)nrecords, sizeof *p->records);
            if (!p->records) rc = 1;
            for (int r = 0; p->records && r < nrecords; r++) {
                gd_per_record_stats *s = &p->records[r];
                s->mean = s->rms = s->peak_to_peak = s->p2p_error = s->amp_error = NAN;
                s->amplitude = calloc((size_t)p->harmonics + 1, sizeof(double));
                s->phase_deg = calloc((size_t)p->harmonics + 1, sizeof(double));
                if (!s->amplitude || !s->phase_deg) rc = 1;
            }
        }
        if (!p->converged) { /* the next point starts afresh */
            sol_clear(&prev, nrecords);
        }
        if (opt->on_point) opt->on_point(p, i, (double)(i + 1) / nvalues, opt->user);
    }
    sol_clear(&prev, nrecords);
    return rc;
}
