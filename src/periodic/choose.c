/* The method of `--method auto` (periodic.h, gd_periodic_choose): shooting where harmonic
 * balance cannot represent a law, else the cheaper of the two for the model by a measured
 * cost rule. Both costs are measured on the problem at the first value (one integrated
 * period; one harmonic balance residual and factorisation) and scaled by the work a point
 * needs (docs/periodic.md, "Choosing the method"). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/transient_model.h"
#include "periodic/condensed/chb.h"
#include "periodic/method.h"
#include "periodic/multifreq/qphb_impl.h"
#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692

const char *gd_per_kind_name(gd_per_kind k)
{
    /* the rows' names (method_table.c); auto is no row */
    if (k == GD_PER_AUTO) return "auto";
    const gd_per_method_row *row = gd_per_method_find(k);
    return (row ? row : gd_per_method_find(GD_PER_HB))->name;
}

/* The time one integration reached (its progress report). */
static void reached(double t, double t0, double t1, void *data)
{
    (void)t0;
    (void)t1;
    *(double *)data = t;
}

/* One integration from rest (the static equilibrium under loads) over [0, t_end] at the
 * shooting tolerance, at most max_steps steps: its right-hand sides, -1 when it failed
 * (*t_reached: how far it got). */
static long integrate(gd_transient *tr, const gd_transient_spec *spec, double t_end, double rtol,
                      long max_steps, double *t_reached)
{
    gd_transient_options o;
    gd_transient_options_init(&o);
    o.rtol = rtol;
    o.atol_q *= rtol / 1e-6;
    o.atol_v *= rtol / 1e-6;
    o.t_end = t_end;
    /* output samples (no records) only for the progress report of the time reached */
    o.output_interval = t_end / 4096;
    o.max_steps = max_steps;
    o.init = spec->nloads ? GD_TR_INIT_STATIC : GD_TR_INIT_REST;
    *t_reached = 0.0;
    o.progress = reached;
    o.progress_data = t_reached;
    gd_transient_result *r = NULL;
    gd_error err;
    gd_status st = gd_transient_run(tr, &o, NULL, 0, &r, &err);
    const long n = st ? -1 : r->rhs_evals;
    if (!st) *t_reached = t_end;
    gd_transient_result_free(r);
    return n;
}

/* Seconds of counted work (work.c) of one period T integrated from rest at the shooting
 * tolerance: the integrator's right-hand sides, counted, times their flops; NAN when it
 * fails. At most max_steps steps are taken (the cap that keeps the measurement cheap:
 * shooting could not win above it): a period that needs more is extrapolated from the
 * stretch the cap reached (*part: its fraction of T, 1 when the whole period ran),
 * integrated again to its last report so that its right-hand sides are counted, where
 * that stretch is 1/64 of the period at least (the start from rest, small steps, is in
 * it, so the extrapolation errs on the long side); NAN below that (*part 1: the cap is
 * then the bound).
 * The integrator's step sequence is deterministic, so is the count. */
static double period_cost(gd_transient *tr, const gd_transient_spec *spec, double T, double rtol,
                          long max_steps, double *part)
{
    const double rhs = gd_per_work_seconds(gd_per_rhs_flops(tr, spec));
    double t = 0.0;
    *part = 1.0;
    long n = integrate(tr, spec, T, rtol, max_steps, &t);
    if (n >= 0) return (double)n * rhs;
    /* too short a stretch is mostly the start's small steps: only a lower bound then */
    if (!(t >= T / 64) || !(t < T)) return NAN;
    double t2 = 0.0; /* its start step differs (CVODE's first step follows t_end) */
    n = integrate(tr, spec, t, rtol, 2 * max_steps, &t2);
    if (n < 0) return NAN;
    *part = t / T;
    return (double)n * rhs / *part;
}

/* 1 when a law of the problem is not smooth (a switch: backlash, contact; or a kink: a
 * unilateral spring): harmonic balance's truncated orbit is not a solution of the
 * time-domain equations there, and the multipliers taken along it are not to be trusted
 * near grazing (issue 33: |mu| 0.89 against 2.99 on NLvib's example 03). */
int gd_per_nonsmooth(const gd_system *sys, const gd_transient_spec *spec, double speed)
{
    gd_law *laws = NULL;
    int nlaws = 0, ns = 0;
    gd_error e;
    if (gd_transient_spec_laws(sys, spec, speed, &laws, &nlaws, &e)) return 0;
    for (int i = 0; i < nlaws; i++)
        if (gd_law_nswitches(&laws[i]) > 0 || !(gd_law_flags(&laws[i]) & GD_LAW_SMOOTH)) ns = 1;
    free(laws);
    return ns;
}

/* Newton steps per point in harmonic balance's estimate; on the arclength also the
 * bordered solves per point counted for shooting (correctors and tangents together): both
 * follow the same branch with the same step control (the Chen pair, 400-1500 rad/s, 12
 * speeds: 112 steps by harmonic balance, 118 by shooting), so both count the same solves. */
#define NEWTON_PER_POINT 8.0

/* A non-smooth law takes shooting up to this multiple of harmonic balance's cost: its
 * orbits solve the time-domain equations, so the multipliers and bifurcations are those
 * shooting's oracle finds (issue 33 item 1); above it, harmonic balance. */
#define NONSMOOTH_RATIO 20.0
/* ... or, whatever the ratio, up to this many seconds of counted work per point: the
 * rattling idler of examples/rattle_pair.yaml (shooting 0.55 s against 0.0017 s, 330x)
 * has unstable orbits that shooting's branch follows at every speed, where harmonic
 * balance fails two of three and a failed point handed to shooting alone, from rest,
 * finds no orbit (bench/periodic_examples.sh) */
#define NONSMOOTH_FLOOR 1.0

/* Shooting's cost per point in integrated periods (n states; dense: the monodromy up to
 * --shoot-dense-max). A dense monodromy of n + 1 columns costs 2 n + 1 periods (its
 * right-hand side is 2 n + 1 evaluations); on the Newton-Krylov path a GMRES solve costs
 * min(n + 1, 40) + 1 monodromy-vector products of one period each (one Krylov cycle and the
 * true residual; 60 where restarts are needed, above 40 unknowns) and the multipliers 81
 * at most (Arnoldi's steps, min(n, 40), by central differences of two periods each, and
 * one period about the point).
 *  - natural (--sequential): five Newton iterations, each a monodromy or a GMRES solve,
 *    and the multipliers;
 *  - pseudo-arclength: NEWTON_PER_POINT bordered solves, each with its point's P(y) (or
 *    its monodromy) and dF/dlambda by one more period, and the Krylov multipliers at every
 *    step (three solves a step: measured 3.05 on the Chen pair, 2.05 corrector iterations
 *    and the tangent); at the requested value the fixed-value Newton from the step's
 *    interpolate (two iterations) and the period of its records. */
static double shoot_periods(int n, int dense, const gd_periodic_options *opt)
{
    const double gm = n + 1 <= 40 ? n + 2.0 : 60.0,
                 mult = opt->stability ? 2.0 * fmin(n, 40.0) + 1 : 0;
    if (opt->method != GD_PER_ARCLENGTH) return dense ? 5.0 * (2.0 * n + 1.0) : 5.0 * 60.0 + 80.0;
    if (dense) return NEWTON_PER_POINT * (2.0 * n + 2.0) + 2.0 * (2.0 * n + 1.0) + 1.0;
    return NEWTON_PER_POINT * (gm + 2.0 + mult / 3.0) + 2.0 * (gm + 1.0) + 1.0 + mult;
}

/* One complex sparse LU of a harmonic block Z_k = K - (k w)^2 M + i k w D (KLU on the
 * union pattern of K, M, D) and one solve with it, in flops: the fill taken as 4 (knz + nf)
 * entries (the memory estimate's, truncation.c), a refactorization 24 flops per entry of
 * the fill, a solve (forward and back) 4 per entry and right-hand side: on seed 002 (377
 * DOFs, 5404 pattern entries) 0.555 M and 0.093 M, calibrated to the 0.54 M instructions
 * per refactorization and 0.57 M per solve with 6 right-hand sides callgrind measured
 * (docs/periodic.md, "Why not a modal sum"). */
static double block_lu_flops(long knz, int nf)
{
    return 24.0 * 4.0 * ((double)knz + nf);
}

static double block_solve_flops(long knz, int nf)
{
    return 4.0 * 4.0 * ((double)knz + nf);
}

/* GMRES products of the iterative capacitance per Newton step (capacitance.c: its
 * preconditioner holds the laws' means, so it iterates on the TVMS' variation only) */
#define CAP_PRODUCTS 30.0

/* One Newton step of the full harmonic balance at H harmonics and N samples: the whole
 * sparse LU on small models (gd_per_hb_step_flops, work.c); on the low-rank path
 * (gd_hb_use_lowrank: from 2000 unknowns with the laws' rank r = ngroup (2 H + 1) at most
 * a quarter of them, or solver 2-4) the residual, H + 1 block LUs, L^-1 U (ngroup solves
 * per block), the transfer scalars w^T Z_k^-1 u, and the capacitance: dense (2/3 r^3)
 * below GD_HB_CAP_CROSSOVER, else CAP_PRODUCTS GMRES products of one AFT per term. Not
 * the dense 2/3 r^3 at every rank: that put seed 002's point at 361 s, 1000x its cost. */
static double full_step_flops(gd_transient *tr, int H, int N, int solver)
{
    int nf, nterm, ngroup;
    long knz;
    gd_hb_memory_params_tr(tr, &nf, &nterm, &ngroup, &knz);
    const double nh = 2.0 * H + 1.0, r = (double)ngroup * nh, n = (double)nf * nh,
                 fft = 2.5 * N * log2((double)N);
    const int lowrank = solver == 1 ? 0 : solver >= 2 ? 1 : n >= 2000 && 4.0 * r <= n;
    if (!lowrank) return gd_per_hb_step_flops(tr, H, N);
    const int iterative = solver == 3 || (solver != 4 && r >= GD_HB_CAP_CROSSOVER);
    const double resid = 2.0 * nf * fft + (double)N * GD_PER_TERM_FLOPS * nterm + 20.0 * nh * knz,
                 blocks = (H + 1.0) *
                          (block_lu_flops(knz, nf) + (ngroup + 1.0) * block_solve_flops(knz, nf)),
                 transfer = (H + 1.0) * 8.0 * nterm * ngroup * nf,
                 cap = iterative ? CAP_PRODUCTS * (nterm * (2.0 * fft + 4.0 * N) +
                                                   8.0 * (H + 1.0) * nterm * ngroup)
                                 : 2.0 * nterm * nh * nh + 2.0 / 3.0 * r * r * r;
    return resid + blocks + transfer + cap;
}

/* Newton iterations and GMRES products of one condensed fixed-value solve (condensed/
 * chb.c; measured on seed 002 at H = 591, sequential, from the previous speed's orbit:
 * see docs/periodic.md, "Choosing the method") */
#define CHB_NEWTON 4.0
#define CHB_PRODUCTS 25.0

/* One fixed-value solve by the condensed harmonic balance on nc coordinates at H
 * harmonics and N samples (condensed/chb.h), lent of its H + 1 block LUs borrowed
 * (the truncation estimate's solve at 2 H + 1 takes the point's): the receptances (H + 1
 * block LUs and nc + 1 solves each), CHB_NEWTON residuals (the coordinates' AFT, the laws
 * at N samples reading q = C (C^T C)^-1 y, Y - H_k G_k), CHB_PRODUCTS GMRES products (the
 * AFT of the samples' nc x nc Jacobians), the recovery X_k = Z_k^-1 r_k + Z_k^-1 C G_k and
 * the full residual it is checked by. */
static double chb_solve_flops(gd_transient *tr, int H, int N, int nc, int lent)
{
    int nf, nterm, ngroup;
    long knz;
    gd_hb_memory_params_tr(tr, &nf, &nterm, &ngroup, &knz);
    const double nh = 2.0 * H + 1.0, fft = 2.5 * N * log2((double)N), h1 = H + 1.0;
    const double rec = (h1 - lent) * block_lu_flops(knz, nf) +
                       h1 * (nc + 1.0) * block_solve_flops(knz, nf) + h1 * 8.0 * nf * nc * nc,
                 resid = 3.0 * nc * fft + (double)N * (GD_PER_TERM_FLOPS * nterm + 2.0 * nf * nc) +
                         8.0 * h1 * nc * nc,
                 product = 3.0 * nc * fft + 4.0 * (double)N * nc * nc + 8.0 * h1 * nc * nc,
                 recover = h1 * 8.0 * nf * nc,
                 check = 2.0 * nf * fft + (double)N * GD_PER_TERM_FLOPS * nterm + 20.0 * nh * knz;
    return rec + CHB_NEWTON * resid + CHB_PRODUCTS * product + recover + check;
}

/* The condensed solve's coordinate count where it will be used for the fixed-value
 * solves of problem tr (the corrector's test, gd_chb_applies: coordinates at most a
 * quarter of the free DOFs; forced by condensed 1), 0 where the full Newton runs. */
static int chb_coords(gd_transient *tr, int H, int N, const gd_periodic_options *opt)
{
    if (opt->condensed < 0) return 0;
    int nf, nterm, ngroup;
    long knz;
    gd_hb_memory_params_tr(tr, &nf, &nterm, &ngroup, &knz);
    gd_chb *c = gd_chb_new(nf, H, N);
    if (!c) return 0;
    const int ap = gd_chb_applies(c, tr), nc = gd_chb_ncoords(c);
    gd_chb_free(c);
    return ap > 0 || (ap == 0 && opt->condensed > 0) ? nc : 0;
}

/* Several base frequencies whose common period holds more than this many periods of the
 * highest (or none at all): ordinary harmonic balance would need H of at least this
 * times the harmonics one mesh cycle needs (issue 33: a gearbox with a common fundamental
 * of 1/34 of the input speed walked to H = 850), the torus keeps each base's own. */
#define QP_AUTO_ORDER 16
/* ... on up to this many free DOFs (its preconditioner holds a dense nf x nf block per
 * harmonic: 64 DOFs at order 16, 545 harmonics, 36 MB) */
#define QP_AUTO_NF 64

/* 1 when the torus is the better choice for a long common period of `order` periods of
 * the highest: on up to QP_AUTO_NF free DOFs (its Floquet multipliers are computed there),
 * or where ordinary harmonic balance of the common period would need more than QP_HB_MAX_H
 * harmonics (QP_H_PER_CYCLE per period of the highest: a mesh's TVMS from geometry) or
 * more memory than allowed. Larger models whose common period harmonic balance holds
 * (seed 002's two-stage helical train, order 36: H = 864; its Figs. 11-13 at H = 591 cost
 * 0.375 s CPU a point) keep it and its multipliers at every point; the co-prime gearbox
 * on FE shafts (order 67: H = 1608) goes to the torus. */
#define QP_H_PER_CYCLE 24
#define QP_HB_MAX_H 1000
static int small_or_hb_too_large(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                 long order, const gd_periodic_options *opt)
{
    gd_transient *tr = NULL;
    gd_error err;
    if (gd_transient_new(sys, spec, speed, &tr, &err)) return 0;
    int mnf, mnt, mng;
    long mknz;
    gd_hb_memory_params_tr(tr, &mnf, &mnt, &mng, &mknz);
    gd_transient_free(tr);
    if (mnf <= QP_AUTO_NF) return 1;
    const long Hn = order * QP_H_PER_CYCLE;
    if (Hn > QP_HB_MAX_H) return 1;
    const int Hc = Hn > 1000000 ? 1000000 : (int)Hn;
    return gd_hb_memory(mnf, Hc, gd_hb_samples_for(Hc), mnt, mng, mknz) > gd_hb_memory_limit(opt);
}

/* 1 (with note) when the multi-frequency harmonic balance is the method for the problem:
 * smooth laws, two or more base frequencies, and a common period of more than
 * QP_AUTO_ORDER periods of the highest or none. */
static int multifreq_fits(const gd_system *sys, const gd_transient_spec *spec, double speed,
                          const gd_periodic_options *opt, char *note)
{
    double W[GD_QP_MAXD];
    long order = 0;
    char why[200] = "";
    /* a given --harmonics H counts harmonics of the common period: ordinary HB */
    if (opt->subharmonic > 1 || !opt->adaptive) return 0;
    int nf = 0, d = gd_per_qp_probe(sys, spec, speed, W, &order, &nf, why, sizeof why);
    if (d < 2 || (order > 0 && order <= QP_AUTO_ORDER)) return 0;
    if (gd_per_nonsmooth(sys, spec, speed)) return 0; /* shooting's orbits: the rule below */
    if (nf > QP_AUTO_NF) return 0;
    if (order > 0 && !small_or_hb_too_large(sys, spec, speed, order, opt)) return 0;
    if (order > 0)
        snprintf(note, 256,
                 "multi-frequency harmonic balance: %d base frequencies (%.5g, %.5g rad/s%s) "
                 "with a common period of %ld periods of the highest: one period would need "
                 "H >= %ld (limit %d)",
                 d, W[0], W[1], d > 2 ? ", ..." : "", order, order, QP_AUTO_ORDER);
    else
        snprintf(note, 256,
                 "multi-frequency harmonic balance: %d base frequencies (%.6g and %.6g rad/s%s) "
                 "with no common period",
                 d, W[0], W[1], d > 2 ? ", ..." : "");
    return 1;
}

/* Reduced shooting (rshoot/) instead of harmonic balance where the laws qualify (linear in
 * the state at fixed time, constant loads) and harmonic balance's own truncation estimate
 * at its default H is over harmonic_tol: the point at the first value solved at H and 2 H
 * + 1, every mesh force recorded (with a stepping TVMS their peak-to-peaks converge
 * slowest in H). Only with --harmonics auto (a given H asks for harmonic balance at it);
 * the default H: the automatic ladder from the excitations' order (H -> 2 H + 1) to
 * RS_PROBE_H at least (591 on [JMSTHelical], where
 * `--harmonics auto` settles at 1817 and 3000 rpm; docs/periodic.md, "Reduced shooting at
 * low speed": 100-1000 rpm 17-83 % there). 1 (note) to take it. */
#define RS_PROBE_H 512
static int reduced_fits(const gd_system *sys, const gd_transient_spec *spec, double speed,
                        int order, const gd_periodic_options *opt, char *note)
{
    char why[256];
    /* a given --harmonics H asks for harmonic balance at that H */
    if (!opt->adaptive || speed == 0.0 || gd_per_rs_refusal(sys, spec, speed, opt, why, sizeof why))
        return 0;
    gd_periodic_options o = *opt;
    o.kind = GD_PER_HB;
    o.method = GD_PER_SEQUENTIAL;
    o.both_directions = 0;
    o.stability = 0;
    o.estimate = 1;
    o.on_point = NULL;
    o.on_step = NULL;
    o.user = NULL;
    if (o.adaptive) {
        long H = (long)order * opt->subharmonic;
        while (H < RS_PROBE_H)
            H = 2 * H + 1;
        o.harmonics = (int)H;
        o.adaptive = 0;
    }
    const int nr = spec->nmeshes;
    gd_tr_record *rec = calloc((size_t)nr + 1, sizeof *rec);
    if (!rec) return 0;
    for (int k = 0; k < nr; k++)
        rec[k] = (gd_tr_record){GD_REC_MESH_FORCE, k, 0};
    gd_periodic_result *r = NULL;
    gd_error err;
    int take = 0;
    if (gd_per_run_kind(sys, spec, NULL, &speed, 1, &o, rec, nr, &r, &err)) {
        snprintf(note, 256,
                 "reduced shooting: the laws are linear in the state at fixed time and harmonic "
                 "balance at H = %d failed (%.120s)",
                 o.harmonics, err.message);
        take = 1;
    } else if (r->npoints < 1 || !r->points[0].converged) {
        snprintf(note, 256,
                 "reduced shooting: the laws are linear in the state at fixed time and harmonic "
                 "balance at H = %d did not converge",
                 o.harmonics);
        take = 1;
    } else {
        const gd_periodic_point *p = &r->points[0];
        const double e = fmax(p->harmonic_error_p2p, p->harmonic_error_amp);
        if (!(e <= opt->harmonic_tol)) {
            snprintf(note, 256,
                     "reduced shooting: laws linear in the state at fixed time; harmonic "
                     "balance's truncation estimate at H = %d is %.3g (against %d, mesh forces), "
                     "over %g",
                     o.harmonics, e, p->harmonics_ref, opt->harmonic_tol);
            take = 1;
        }
    }
    gd_periodic_result_free(r);
    free(rec);
    return take;
}

gd_per_kind gd_periodic_choose(const gd_system *sys, const gd_transient_spec *spec,
                               const gd_periodic_param *param, double value,
                               const gd_periodic_options *opt, char *note)
{
    char buf[256];
    if (!note) note = buf;
    note[0] = '\0';
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_error err;
    gd_per_kind k = GD_PER_HB;
    double speed = value;
    gd_tr_load *floads = NULL;
    gd_transient_spec fspec;
    if (param && param->load_frequency) {
        char msg[200];
        if (gd_per_frequency_spec(spec, value, &floads, &fspec, msg, sizeof msg)) {
            snprintf(note, 256, "harmonic balance (the default: %.200s)", msg);
            return GD_PER_HB;
        }
        spec = &fspec;
        speed = param->speed;
    } else if (param) {
        if (!param->rebuild || param->rebuild(value, param->data, &m, &s, &tm, &err)) {
            snprintf(note, 256,
                     "harmonic balance (the default: the problem at the first value "
                     "could not be made to measure)");
            return GD_PER_HB;
        }
        sys = s;
        spec = &tm->spec;
        speed = param->speed;
    }
    if (!param && multifreq_fits(sys, spec, speed, opt, note)) return GD_PER_MULTIFREQ;
    double w0;
    int order = 1;
    if (gd_periodic_fundamental(sys, spec, speed, &w0, &order, &err) ||
        gd_transient_new(sys, spec, speed, &tr, &err)) {
        snprintf(note, 256, "harmonic balance (the default: %.200s)", err.message);
        goto done;
    }
    if (gd_transient_terms(tr, NULL) < 0) {
        k = GD_PER_SHOOTING;
        snprintf(note, 256,
                 "shooting: harmonic balance cannot represent cam torques with "
                 "include_acceleration");
        goto done;
    }
    {
        const double w = w0 / opt->subharmonic;
        const int n = gd_transient_nstates(tr), nf = n / 2;
        int H = opt->harmonics;
        if (opt->adaptive && (long)order * opt->subharmonic > H) H = order * opt->subharmonic;
        int backlash = gd_transient_nswitches(tr) > 0; /* contact laws */
        const int dense = n <= (opt->shoot_dense_max > 0 ? opt->shoot_dense_max : 64);
        const double per_period = shoot_periods(n, dense, opt);
        {
            /* a workspace over the memory limit: a fixed H is the user's to change (harmonic
             * balance refuses it, naming the limit); an automatic one leaves shooting */
            int mnf, mnt, mng;
            long mknz;
            gd_hb_memory_params_tr(tr, &mnf, &mnt, &mng, &mknz);
            const double need = gd_hb_memory(mnf, H, gd_hb_samples_for(H), mnt, mng, mknz);
            if (need > gd_hb_memory_limit(opt)) {
                k = opt->adaptive ? GD_PER_SHOOTING : GD_PER_HB;
                snprintf(note, 256,
                         "%s: harmonic balance's workspace at H = %d needs about %.2g GB, over "
                         "the limit",
                         opt->adaptive ? "shooting" : "harmonic balance", H, need / 1e9);
                goto done;
            }
        }
        double Ns = opt->samples > 0 ? opt->samples : gd_hb_samples_for(H);
        if (backlash && Ns < 128) Ns = 128;
        if (Ns < 2 * H + 2) Ns = 2 * H + 2;
        const double th = gd_per_work_seconds(full_step_flops(tr, H, (int)Ns, opt->solver));
        /* harmonic balance: eight Newton steps (NEWTON_PER_POINT), three times that with the
         * solution at 2 H + 1 of the truncation estimate; where the condensed solve takes
         * the fixed-value solves (every point with --sequential, the crossing of each
         * requested value on the arclength, the estimate's solve at 2 H + 1 with the
         * point's H + 1 receptances borrowed), those at its own counts */
        const int nc = chb_coords(tr, H, (int)Ns, opt);
        const int est = opt->estimate || opt->adaptive;
        double ch = NEWTON_PER_POINT * th * (est ? 3.0 : 1.0);
        if (nc > 0) {
            const int H2 = 2 * H + 1;
            double N2 = opt->samples > 0 ? 2.0 * opt->samples : gd_hb_samples_for(H2);
            if (backlash && N2 < 128) N2 = 128;
            if (N2 < 2 * H2 + 2) N2 = 2 * H2 + 2;
            ch = gd_per_work_seconds(chb_solve_flops(tr, H, (int)Ns, nc, 0));
            if (est) ch += gd_per_work_seconds(chb_solve_flops(tr, H2, (int)N2, nc, H + 1));
            if (opt->method == GD_PER_ARCLENGTH) ch += NEWTON_PER_POINT * th;
        }
        double N = opt->samples > 0 ? opt->samples : gd_hb_samples_for(H);
        double steps = opt->monodromy_steps > 0 ? opt->monodromy_steps : fmax(256.0, 4.0 * N);
        /* the reduced basis (floquet_reduced.c, auto above floquet_dmax states): every mode
         * of (K, M) once, then per step about 8 nterm (2 r)^2 flops, r about 64 (48 on
         * the [JMSTHelical] model, 22 on the two-stage gearbox: docs/periodic.md) */
        const int dmax = opt->floquet_dmax > 0 ? opt->floquet_dmax : 300;
        const double fdense = steps * 30.0 * pow(2.0 * nf, 3) / 2e9;
        /* auto also where the dense one is over the budget (points.c) */
        const int reduced =
            opt->floquet == GD_FLOQUET_REDUCED ||
            (opt->floquet == GD_FLOQUET_AUTO &&
             (n > dmax || (opt->floquet_budget > 0 && fdense > opt->floquet_budget)));
        const double rb = fmin(nf, 64.0), nterm = fmax(1.0, gd_transient_terms(tr, NULL));
        /* the reduced basis picks its own steps: s0 = 8 per period of the top order (a power
         * of 2, at least 256), then 2 s0 to compare, so about 3 s0 steps in all */
        const double rsteps =
            opt->monodromy_steps > 0
                ? steps
                : 3.0 * gd_floquet_reduced_first_steps((long)order * opt->subharmonic);
        const double fq =
            reduced ? (10.0 * pow(nf, 3) + rsteps * 8.0 * nterm * 4.0 * rb * rb) / 2e9 : fdense;
        if (opt->stability) /* no more than the multipliers' budget: over it they are left out */
            ch += fmin(fq, opt->floquet_budget > 0 ? opt->floquet_budget : INFINITY);
        /* a non-smooth law: shooting, whose orbits solve the time-domain equations (their
         * multipliers and bifurcations are those of the dynamics), unless it would cost more
         * than NONSMOOTH_RATIO times harmonic balance */
        const int nonsmooth = gd_per_nonsmooth(sys, spec, speed);
        const double ratio =
            nonsmooth ? fmax(NONSMOOTH_RATIO, ch > 0 ? NONSMOOTH_FLOOR / ch : NONSMOOTH_RATIO)
                      : 1.0;
        /* the period is integrated only as far as shooting could still win: at most the
         * steps (one right-hand side each, at least) that fit in ratio ch / per_period */
        double tr1 = gd_per_work_seconds(gd_per_rhs_flops(tr, spec)), cs = NAN, tp = NAN;
        long cap =
            isfinite(th) && tr1 > 0 ? (long)fmin(2e6, ratio * ch / per_period / tr1) + 100 : 0;
        double part = 1.0;
        tp = period_cost(tr, spec, TWO_PI / w, opt->shoot_rtol > 0 ? opt->shoot_rtol : 1e-9, cap,
                         &part);
        cs = per_period * tp;
        char msg[512];
        if (part < 1.0 && isfinite(th)) {
            /* the cap was reached: shooting cannot win (its steps alone exceed what would),
             * the estimate extrapolated from the stretch integrated says by how much */
            snprintf(msg, sizeof msg,
                     "harmonic balance%s: estimated %.3g s per point (H = %d%s) against about "
                     "%.3g s by shooting (%d states; one period extrapolated from %.2g %% of "
                     "it, %ld steps; counted work)",
                     nonsmooth ? " (a non-smooth law, shooting over 20x and 1 s)" : "", ch, H,
                     nc > 0 ? ", condensed" : "", cs, n, 100.0 * part, cap);
            snprintf(note, 256, "%.255s", msg);
            goto done;
        }
        if (!isfinite(cs) && isfinite(th)) {
            snprintf(msg, sizeof msg,
                     "harmonic balance: estimated %.3g s per point (H = %d%s), and one period "
                     "of shooting's integration (%d states) needs more than %ld steps: shooting "
                     "could not be %s",
                     ch, H, nc > 0 ? ", condensed" : "", n, cap,
                     nonsmooth
                         ? "within 20 times of it or 1 s (non-smooth law: stability by harmonic "
                           "balance)"
                         : "cheaper");
            snprintf(note, 256, "%.255s", msg);
            goto done;
        }
        if (!isfinite(cs)) {
            snprintf(note, 256, "harmonic balance: the period could not be integrated");
        } else if (!isfinite(th)) {
            k = GD_PER_SHOOTING;
            snprintf(note, 256, "shooting: the harmonic balance workspace at H = %d failed", H);
        } else {
            k = cs < ratio * ch ? GD_PER_SHOOTING : GD_PER_HB;
            snprintf(note, 256,
                     "%s%s: estimated %.3g s per point by shooting (%s%s, %d states) against "
                     "%.3g s by harmonic balance (H = %d%s; counted work)",
                     k == GD_PER_SHOOTING ? "shooting" : "harmonic balance",
                     nonsmooth
                         ? (k == GD_PER_SHOOTING ? " (a non-smooth law)"
                                                 : " (a non-smooth law, shooting over 20x and 1 s)")
                         : "",
                     cs, opt->method == GD_PER_ARCLENGTH ? "arclength, " : "",
                     dense ? "dense" : "matrix-free", n, ch, H, nc > 0 ? ", condensed" : "");
        }
    }
done:
    if (k == GD_PER_HB && tr && !(param && param->load_frequency) &&
        reduced_fits(sys, spec, speed, order, opt, note))
        k = GD_PER_REDUCED_SHOOTING;
    gd_transient_free(tr);
    free(floads);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    return k;
}
