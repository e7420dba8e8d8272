/* Campbell diagram: the damped modes at every speed (in parallel over speeds, one
 * result slot per speed, so the numbers do not depend on the number of threads), then
 * tracking, orders, critical speeds and stability. The sparse path builds the pattern
 * and its symbolic factorisation once and factors P(sigma) per speed. */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "campbell/campbell_impl.h"
#include "modal/modal_impl.h"

/* Speeds per chain without the continuation (see gd_campbell_run). */
#define GD_CAMPBELL_CHAIN 8
/* Modes solved above the window when speeds are continued (a guard band: a pair the
 * window's edge cuts is tracked whole, and gd_sparse_track drops what fails above the
 * window instead of handing the speed to Krylov-Schur). Measured on the 5-planet set of
 * bench/bench_planetary.sh, whose window of 12 cuts a translational pair at rest. */
#define GD_CAMPBELL_GUARD 1

void gd_campbell_options_init(gd_campbell_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->nmodes = 12;
    opt->kind = GD_MODAL_AUTO;
    opt->method = GD_EIG_AUTO;
    opt->shaft_orders = 1;
    opt->mesh_orders = 1;
    opt->mac_min = 0.1;
}

void gd_campbell_free(gd_campbell_result *r)
{
    if (!r) return;
    free(r->speeds);
    free(r->tracks);
    free(r->modes);
    free(r->orders);
    free(r->critical);
    free(r->no_equilibrium);
    free(r);
}

/* The laws' operating state at speed s of the sweep (NULL: none kept, solved where used). */
static const double *state_at(const gd_system *sys, const double *states, int s)
{
    return states ? states + (size_t)s * sys->ndof : NULL;
}

/* The operating states of the laws at every speed, in speed order, each Newton
 * iteration started from the previous speed's state (gd_system_law_state_from): a
 * journal bearing's eccentricity moves little between neighbouring speeds, so a few
 * steps replace the climb from rest. Solved once, before the threads, so the states do
 * not depend on their number. NULL with no laws to linearise, or out of memory. found (nspeeds)
 * flags the speeds that have an equilibrium: the result reports the others, so nobody solves them
 * again to find out. */
static double *operating_states(const gd_system *sys, const gd_campbell_options *opt, int *flag)
{
    if (!sys->nlaws || sys->op_kind == GD_OPERATING_ZERO) return NULL;
    const size_t n = (size_t)sys->ndof, n1 = n > 0 ? n : 1;
    double *q = malloc(((size_t)opt->nspeeds + 1) * n1 * sizeof *q);
    if (!q) return NULL;
    double *start = q + (size_t)opt->nspeeds * n1; /* the predicted state */
    const double *W = opt->speeds;
    int found = 0, found2 = 0; /* at the previous speed, and at the one before */
    for (int s = 0; s < opt->nspeeds; s++) {
        const double *q0 = NULL;
        if (found && found2) {
            /* the secant through the two previous states: about one Newton step less */
            double a = (W[s] - W[s - 1]) / (W[s - 1] - W[s - 2]);
            for (size_t i = 0; i < n; i++)
                start[i] = q[(s - 1) * n + i] + a * (q[(s - 1) * n + i] - q[(s - 2) * n + i]);
            q0 = start;
        } else if (found) {
            q0 = q + (s - 1) * n;
        }
        found2 = found;
        found = gd_system_law_state_from(sys, W[s], q0, q + s * n);
        flag[s] = found;
    }
    return q;
}

static gd_status solve_one(const gd_system *sys, const gd_dynmat *a, const gd_splu_symbolic *sym,
                           const gd_campbell_options *opt, int nreq, double speed,
                           const double *state, gd_sparse_ws *ws, gd_modal_result **out,
                           gd_error *err)
{
    gd_modal_options o;
    gd_modal_options_init(&o);
    o.speed = speed;
    o.law_state = state;
    o.nmodes = nreq;
    o.kind = opt->kind;
    o.want_left = 0;
    o.method = GD_EIG_DENSE;
    if (a) return gd_sparse_modes(a, sym, &o, opt->shift, ws, out, err);
    return gd_modal_solve(sys, &o, out, err);
}

/* The cost model of gd_modal_solve (src/modal/method.c) per speed, judged at the
 * highest speed, where gyroscopic terms make the problem damped if any speed does. */
static int sparse_cheaper(const gd_system *sys, const gd_dynmat *a, const gd_splu_symbolic *sym,
                          const gd_campbell_options *opt, const double *state)
{
    size_t nz = (size_t)(a->pat.nnz > 0 ? a->pat.nnz : 1);
    double *k = malloc(nz * sizeof *k), *d = malloc(nz * sizeof *d);
    int cheaper = 1;
    if (k && d) {
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.speed = opt->speeds[opt->nspeeds - 1];
        o.law_state = state;
        o.kind = opt->kind;
        int damped = gd_modal_damped_at(a, &o, k, d);
        cheaper = gd_cost_sparse(&a->pat, sym, opt->nmodes) <
                  gd_cost_dense(sys->ndof, damped, opt->nmodes);
    }
    free(k);
    free(d);
    return cheaper;
}

/* Releases the mode shapes of a result whose modes have been tracked. */
static void drop_shapes(gd_modal_result *r)
{
    free(r->shape_re);
    free(r->shape_im);
    r->shape_re = r->shape_im = NULL;
}

static gd_whirl majority_whirl(const gd_mode *md, const double *speeds, int ns)
{
    int cnt[4] = {0};
    for (int s = 0; s < ns; s++)
        if (md[s].rigid_body >= 0 && speeds[s] != 0) cnt[md[s].whirl]++;
    static const gd_whirl pref[3] = {GD_WHIRL_FORWARD, GD_WHIRL_BACKWARD, GD_WHIRL_MIXED};
    gd_whirl best = GD_WHIRL_NONE;
    int bc = 0;
    for (int i = 0; i < 3; i++)
        if (cnt[pref[i]] > bc) {
            bc = cnt[pref[i]];
            best = pref[i];
        }
    return bc >= cnt[GD_WHIRL_NONE] ? best : GD_WHIRL_NONE;
}

static gd_motion majority_motion(const gd_mode *md, int ns)
{
    int cnt[GD_NMOTIONS] = {0}, best = 0;
    for (int s = 0; s < ns; s++)
        if (md[s].rigid_body >= 0) cnt[md[s].dominant_motion]++;
    for (int k = 1; k < GD_NMOTIONS; k++)
        if (cnt[k] > cnt[best]) best = k;
    return (gd_motion)best;
}

gd_status gd_campbell(const gd_system *sys, const gd_campbell_options *opt,
                      gd_campbell_result **out, gd_error *err)
{
    return gd_campbell_run(sys, opt, 1, NULL, out, err);
}

gd_status gd_campbell_run(const gd_system *sys, const gd_campbell_options *opt, int continuation,
                          gd_campbell_stats *stats, gd_campbell_result **out, gd_error *err)
{
    *out = NULL;
    if (stats) memset(stats, 0, sizeof *stats);
    const gd_model *m = sys->model;
    int ns = opt->nspeeds;
    if (ns < 1 || !opt->speeds)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "speeds", "give at least one speed",
                            "no speeds to compute");
    for (int s = 0; s < ns; s++)
        if (!isfinite(opt->speeds[s]) || (s > 0 && !(opt->speeds[s] > opt->speeds[s - 1])))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "speeds",
                                "give finite speeds in increasing order",
                                "speed %d (%g rad/s) is not finite or not above the previous",
                                s + 1, opt->speeds[s]);
    if (opt->nmodes < 0)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "modes", "give a positive number of modes",
                            "negative number of modes");
    int sparse = opt->method == GD_EIG_SPARSE ||
                 (opt->method == GD_EIG_AUTO && gd_sparse_applicable(sys, opt->nmodes));
    if (sparse && (opt->nmodes == 0 || sys->nmassless > 0))
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "method",
                            "use the dense method (it condenses massless DOFs and gives all modes)",
                            opt->nmodes == 0 ? "the sparse eigensolver computes the lowest modes, "
                                               "not all of them"
                                             : "the sparse eigensolver needs mass on every DOF");
    gd_status st = GD_OK;
    gd_dynmat a = {0};
    gd_splu_symbolic sym = {0};
    gd_modal_result **res = calloc((size_t)ns, sizeof *res);
    gd_error *errs = calloc((size_t)ns, sizeof *errs);
    gd_status *sts = calloc((size_t)ns, sizeof *sts);
    int **elastic = calloc((size_t)ns, sizeof *elastic),
        **track = calloc((size_t)ns, sizeof *track);
    int *nel = calloc((size_t)ns, sizeof *nel), *nfb = calloc((size_t)ns, sizeof *nfb),
        *ncont = calloc((size_t)ns, sizeof *ncont);
    gd_campbell_result *r = calloc(1, sizeof *r);
    gd_sparse_ws *wss = NULL;
    int nt = 1;
    double *states = NULL;
    if (!res || !errs || !sts || !elastic || !track || !nel || !nfb || !ncont || !r) goto nomem;
    if (sys->nlaws && sys->op_kind != GD_OPERATING_ZERO) {
        /* every speed has an equilibrium until operating_states says otherwise */
        if (!(r->no_equilibrium = malloc((size_t)ns * sizeof *r->no_equilibrium))) goto nomem;
        for (int s = 0; s < ns; s++)
            r->no_equilibrium[s] = 1;
        if (!(states = operating_states(sys, opt, r->no_equilibrium))) goto nomem;
        for (int s = 0; s < ns; s++)
            r->no_equilibrium[s] = !r->no_equilibrium[s];
    }
    if (sparse) {
        if ((st = gd_dynmat_build(sys, &a, err))) goto done;
        if ((st = gd_splu_analyze(&a.pat, &sym, err))) goto done;
        if (opt->method == GD_EIG_AUTO &&
            !sparse_cheaper(sys, &a, &sym, opt, state_at(sys, states, ns - 1))) {
            gd_splu_symbolic_free(&sym);
            gd_dynmat_free(&a);
            memset(&a, 0, sizeof a);
            memset(&sym, 0, sizeof sym);
            sparse = 0;
        }
    }
    /* rigid-body modes are not tracked: count them once at the first speed (they sort
     * first, so a probe that is not all rigid has found them all), then ask for that
     * many more; with none, the probe is the first speed's result */
    int nreq = 0, nrigid = 0, nsolve = 0;
    /* with the continuation, the sparse solves give the guard band too (the window's
     * modes are the lowest nreq whatever the band) */
    /* (not on a system so small that the band crowds Krylov-Schur's basis) */
    int guard =
        sparse && continuation && ns > 1 && sys->ndof >= 4 * (opt->nmodes + GD_CAMPBELL_GUARD) + 12
            ? GD_CAMPBELL_GUARD
            : 0;
    if (opt->nmodes > 0) {
        for (int probe = opt->nmodes + guard;; probe *= 2) {
            if (probe > sys->ndof) probe = sys->ndof;
            gd_modal_result *r0 = NULL;
            if ((st = solve_one(sys, sparse ? &a : NULL, &sym, opt, probe, opt->speeds[0],
                                state_at(sys, states, 0), NULL, &r0, err)))
                goto done;
            nrigid = 0;
            for (int j = 0; j < r0->nmodes; j++)
                nrigid += r0->modes[j].rigid_body;
            if (nrigid < r0->nmodes || probe == sys->ndof) {
                nreq = opt->nmodes + nrigid;
                if (nreq > sys->ndof) nreq = sys->ndof;
                nsolve = nreq + guard < sys->ndof ? nreq + guard : sys->ndof;
                if (nsolve == probe)
                    res[0] = r0;
                else
                    gd_modal_free(r0);
                break;
            }
            gd_modal_free(r0);
        }
    }
    nt = opt->nthreads > 0 ? opt->nthreads : omp_get_max_threads();
    /* one workspace per thread, reused over its speeds; one result slot per speed. The
     * speeds go in blocks: each block is solved in parallel, then tracked, and the
     * mode shapes that tracking no longer needs are released, so the next block reuses
     * their memory (fresh pages cost more than the tracking itself). Blocks change
     * nothing in the numbers. */
    wss = calloc((size_t)nt, sizeof *wss);
    if (!wss) goto nomem;
    for (int t = 0; t < nt && sparse; t++)
        if (gd_sparse_ws_init(&wss[t], &a, nsolve)) memset(&wss[t], 0, sizeof wss[t]);
    /* A trial before the sweep: the second speed continued from the first. Where that
     * is hard (gd_sparse_track: near-double modes cut by the window's edge, as on a
     * finely meshed, weakly gyroscopic shaft), every speed goes to Krylov-Schur instead
     * of each chain finding it out at its own cost. Done once, before the threads, so
     * the numbers do not depend on their count. */
    if (sparse && continuation && ns > 1 && wss[0].k) {
        gd_sparse_ws *w0 = &wss[0];
        if (gd_sparse_ws_chain(w0, a.pat.n)) goto nomem;
        w0->warm_ok = 0;
        gd_sparse_track_reset(w0);
        if (!res[0] && (st = solve_one(sys, &a, &sym, opt, nsolve, opt->speeds[0],
                                       state_at(sys, states, 0), w0, &res[0], err)))
            goto done;
        gd_modal_options o;
        gd_modal_options_init(&o);
        o.speed = opt->speeds[1];
        o.law_state = state_at(sys, states, 1);
        o.nmodes = nreq;
        o.kind = opt->kind;
        o.want_left = 0;
        int hard = 0;
        if ((st = gd_sparse_track(&a, &sym, &o, res[0], NULL, w0, &res[1], &hard, err))) goto done;
        if (hard) {
            gd_modal_free(res[1]);
            res[1] = NULL;
            continuation = 0;
            nsolve = nreq;            /* Krylov-Schur needs no guard band */
            gd_sparse_track_free(w0); /* its buffers and factorisations */
        } else {
            ncont[1] = 1;
        }
    }
    /* Sparse: the speeds go in chains (GD_CAMPBELL_CHAIN speeds, or a quarter of them
     * with the continuation), each solved in order by one thread and its first speed
     * cold, so the chains, and the numbers, are the same whatever the number of threads.
     * Every later speed of a chain is continued from the previous ones (gd_sparse_track:
     * each mode refined from its previous eigenpair, then a completeness check) or, when
     * the continuation declines, solved by Krylov-Schur started from the previous
     * speed's modes (gd_sparse_ws warm start: 15-20 % fewer operator steps on the
     * 10k-DOF shaft). */
    int nt_tracks = 0, chain = sparse ? GD_CAMPBELL_CHAIN : 1, block = 8 * nt;
    /* with the continuation each chain's cold first speed costs a few continued ones:
     * four chains (a parallel sweep on up to four threads) when the speeds are many */
    if (sparse && continuation && (ns + 3) / 4 > chain) chain = (ns + 3) / 4;
    if (sparse) block = chain * nt;
    for (int t = 0; t < nt && sparse; t++)
        if (wss[t].k && gd_sparse_ws_chain(&wss[t], a.pat.n)) goto nomem;
    for (int b0 = 0; b0 < ns; b0 += block) {
        int b1 = b0 + block < ns ? b0 + block : ns, nch = (b1 - b0 + chain - 1) / chain;
#pragma omp parallel for num_threads(nt) schedule(dynamic, 1)
        for (int c = 0; c < nch; c++) {
            gd_sparse_ws *ws = sparse ? &wss[omp_get_thread_num()] : NULL;
            if (ws && !ws->k) ws = NULL;
            if (ws) {
                ws->warm_ok = 0;
                gd_sparse_track_reset(ws);
            }
            int c1 = b0 + (c + 1) * chain < b1 ? b0 + (c + 1) * chain : b1, easy = 1;
            for (int s = b0 + c * chain; s < c1; s++) {
                if (s == b0 + c * chain) easy = 1;
                if (!res[s] && ws && continuation && easy && s > b0 + c * chain) {
                    /* continued from the previous speed of the chain; NULL: Krylov-Schur */
                    gd_modal_options o;
                    gd_modal_options_init(&o);
                    o.speed = opt->speeds[s];
                    o.law_state = state_at(sys, states, s);
                    o.nmodes = nreq;
                    o.kind = opt->kind;
                    o.want_left = 0;
                    const gd_modal_result *p2 = s - 1 > b0 + c * chain ? res[s - 2] : NULL;
                    int hard = 0;
                    sts[s] =
                        gd_sparse_track(&a, &sym, &o, res[s - 1], p2, ws, &res[s], &hard, &errs[s]);
                    easy = !hard;
                    if (!sts[s] && res[s]) {
                        ncont[s] = 1;
                        gd_sparse_ws_remember(ws, res[s]);
                        continue;
                    }
                    if (!sts[s]) nfb[s] = 1;
                }
                if (sts[s]) break;
                if (!res[s])
                    sts[s] = solve_one(sys, sparse ? &a : NULL, &sym, opt, nsolve, opt->speeds[s],
                                       state_at(sys, states, s), ws, &res[s], &errs[s]);
                else if (ws) /* the first speed's probe, solved cold */
                    gd_sparse_ws_remember(ws, res[s]);
                if (sts[s]) break;
            }
        }
        for (int s = b0; s < b1; s++)
            if (sts[s]) {
                if (err) *err = errs[s];
                st = sts[s];
                goto done;
            }
        /* the sparse solves label their modes without the laws' strain energy: finished
           here with the same stiffness blocks as `geardyn modal` at that speed (the dense
           path, gd_modal_solve, already did), so a bearing-dominated mode carries the same
           component label in both. Shapes, hence tracking, are untouched. */
        for (int s = b0; s < b1 && sparse; s++)
            if (gd_modal_energies_laws(sys, res[s], state_at(sys, states, s))) goto nomem;
        for (int s = b0; s < b1; s++) {
            int cap = res[s]->nmodes > 0 ? res[s]->nmodes : 1;
            elastic[s] = malloc((size_t)cap * sizeof **elastic);
            track[s] = malloc((size_t)cap * sizeof **track);
            if (!elastic[s] || !track[s]) goto nomem;
            int lim = opt->nmodes > 0 ? opt->nmodes : res[s]->nmodes;
            for (int j = 0; j < res[s]->nmodes && nel[s] < lim; j++)
                if (!res[s]->modes[j].rigid_body) elastic[s][nel[s]++] = j;
            if (res[s]->nmodes - nel[s] > nrigid && opt->nmodes == 0)
                nrigid = res[s]->nmodes - nel[s];
            if (gd_campbell_track_step(s > 0 ? res[s - 1] : NULL, s > 0 ? elastic[s - 1] : NULL,
                                       s > 0 ? nel[s - 1] : 0, s > 0 ? track[s - 1] : NULL, res[s],
                                       elastic[s], nel[s], opt->mac_min, track[s], &nt_tracks))
                goto nomem;
            if (s > 0) drop_shapes(res[s - 1]);
        }
    }
    if (stats)
        for (int s = 0; s < ns; s++) {
            stats->continued += ncont[s];
            stats->fallbacks += nfb[s];
        }
    r->nspeeds = ns;
    r->ntracks = nt_tracks;
    r->ndof = sys->ndof;
    r->nrigid = nrigid;
    r->sparse = sparse;
    r->speeds = malloc((size_t)ns * sizeof *r->speeds);
    r->tracks = calloc((size_t)(nt_tracks > 0 ? nt_tracks : 1), sizeof *r->tracks);
    r->modes = malloc((size_t)(nt_tracks > 0 ? nt_tracks : 1) * (size_t)ns * sizeof *r->modes);
    if (!r->speeds || !r->tracks || !r->modes) goto nomem;
    memcpy(r->speeds, opt->speeds, (size_t)ns * sizeof *r->speeds);
    for (size_t i = 0; i < (size_t)nt_tracks * ns; i++) {
        gd_mode *md = &r->modes[i];
        memset(md, 0, sizeof *md);
        md->lambda_re = md->lambda_im = md->omega_n = md->omega_d = NAN;
        md->frequency_hz = md->damping_ratio = md->log_decrement = NAN;
        md->rigid_body = -1;
        md->dominant_component = -1;
    }
    for (int s = 0; s < ns; s++)
        for (int j = 0; j < nel[s]; j++)
            r->modes[(size_t)track[s][j] * ns + s] = res[s]->modes[elastic[s][j]];
    for (int t = 0; t < nt_tracks; t++) {
        r->tracks[t].id = t + 1;
        r->tracks[t].whirl = majority_whirl(r->modes + (size_t)t * ns, r->speeds, ns);
        r->tracks[t].dominant_motion = majority_motion(r->modes + (size_t)t * ns, ns);
    }
    r->norders = gd_campbell_orders(m, opt, &r->orders);
    if (r->norders < 0 || gd_campbell_crossings(r)) goto nomem;
    *out = r;
    r = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the Campbell sweep");
done:
    for (int t = 0; wss && t < nt; t++)
        gd_sparse_ws_free(&wss[t]);
    free(wss);
    free(states);
    if (sparse) {
        gd_splu_symbolic_free(&sym);
        gd_dynmat_free(&a);
    }
    for (int s = 0; s < ns && res; s++) {
        gd_modal_free(res[s]);
        if (elastic) free(elastic[s]);
        if (track) free(track[s]);
    }
    free(res);
    free(errs);
    free(sts);
    free(elastic);
    free(track);
    free(nel);
    free(nfb);
    free(ncont);
    gd_campbell_free(r);
    return st;
}
