/* Harmonic balance's row of the method table (method.h): its context (continuation_impl.h)
 * for the run, the first H and its cap from the workspace's memory, the sampling its laws
 * need (backlash 128, a kink 1024 samples and corners), both directions by
 * gd_per_run_branch (continuation.c), which hands its context and operations (the row's
 * ops) to the shared drivers (driver/). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/transient_model.h"
#include "periodic/continuation_impl.h"
#include "periodic/method.h"
#include "periodic/periodic_impl.h"

/* The method table's row for harmonic balance (method.h): the workspace, the first H and
 * its cap from memory, the sampling the laws need, both directions by gd_per_run_branch. */
gd_status gd_per_hb_run(const gd_per_arc_ops *ops, const gd_system *sys,
                        const gd_transient_spec *spec, const gd_periodic_param *param,
                        const double *values, int nvalues, const gd_periodic_options *opt,
                        const gd_tr_record *records, int nrecords, gd_periodic_result *res,
                        gd_error *err)
{
    ctx c;
    memset(&c, 0, sizeof c);
    c.sys = sys;
    c.spec = spec;
    c.param = param;
    c.opt = opt;
    c.rec = records;
    c.nrec = nrecords;
    c.H = opt->harmonics;
    c.shoot_stab = opt->shoot_stability == 2 && opt->stability;
    c.res = res;
    int mnf = 0, mnt = 0, mng = 0, mem_ok = 0; /* what the workspace's memory depends on */
    long mknz = 0;
    /* the number of free DOFs, from a problem at the first value */
    {
        gd_transient *tr = NULL;
        gd_status st;
        if (param) {
            stage s = {0};
            c.opt = opt;
            if (gd_per_make_stage(&c, &s, values[0]) && !s.tr) {
                gd_error_set(err, GD_EINPUT, "", 0, 0, param->name ? param->name : "param", "",
                             "%s", s.msg);
                gd_per_stage_clear(&s);
                return GD_EINPUT;
            }
            c.nf = gd_transient_nstates(s.tr) / 2;
            gd_per_stage_clear(&s);
        } else {
            if ((st = gd_transient_new(sys, spec, values[0], &tr, err))) {
                return st;
            }
            int nt = gd_transient_terms(tr, NULL);
            c.nf = gd_transient_nstates(tr) / 2;
            gd_hb_memory_params_tr(tr, &mnf, &mnt, &mng, &mknz); /* the H cap, below */
            mem_ok = 1;
            gd_transient_free(tr);
            if (nt < 0) {
                return gd_error_set(err, GD_EINPUT, "", 0, 0, "cam_torques",
                                    "solve by shooting (--method shooting, or auto), which "
                                    "integrates them, or set include_acceleration: false",
                                    "cam torques with include_acceleration are not supported by "
                                    "harmonic balance");
            }
        }
    }
    /* the harmonic count: the first H (adaptive: the least that holds every excitation's
     * fundamental) and the cap from the workspace's memory */
    int H0 = opt->harmonics;
    {
        const gd_system *s0 = sys;
        const gd_transient_spec *sp0 = spec;
        double sp = param ? param->speed : values[0], w0;
        stage st0 = {0};
        int order = 0;
        c.H = 1 << 30; /* the stage's own check of H is not wanted here */
        if (param && !gd_per_make_stage(&c, &st0, values[0])) {
            s0 = st0.sys;
            sp0 = st0.spec;
        } else if (param) {
            s0 = NULL;
        }
        gd_error e2;
        if (opt->adaptive && s0 && !gd_periodic_fundamental(s0, sp0, sp, &w0, &order, &e2))
            H0 = order * opt->subharmonic > 0 ? order * opt->subharmonic : 1;
        double lim = gd_hb_memory_limit(opt), need = 0.0;
        c.Hcap = opt->max_harmonics > 0 ? opt->max_harmonics : 1 << 20;
        if (!mem_ok && s0) mem_ok = !gd_hb_memory_params(s0, sp0, sp, &mnf, &mnt, &mng, &mknz);
        if (mem_ok) {
#define MEM(H) gd_hb_memory(mnf, (H), gd_hb_samples_for(H), mnt, mng, mknz)
            if (opt->max_harmonics <= 0) {
                /* doubling up to the limit, then bisection: H whose workspace fits */
                int lo = 1, hi = 2;
                while (hi < (1 << 20) && MEM(hi) <= lim) {
                    lo = hi;
                    hi *= 2;
                }
                while (hi - lo > 1) {
                    int mid = lo + (hi - lo) / 2;
                    if (MEM(mid) <= lim)
                        lo = mid;
                    else
                        hi = mid;
                }
                c.Hcap = lo;
            }
            need = MEM(H0);
#undef MEM
        }
        /* the laws, asked (gd_transient_spec_laws): a law with switches (a backlash mesh)
         * makes the sampled residual piecewise smooth: with few samples Newton cycles near
         * grazing and the arclength chatters (the backlash test with auto H = 7 at 32
         * samples: 1500 steps stuck at the 555 rad/s fold; at 128: the whole branch, four
         * folds). One that is not smooth and has no switches (a unilateral spring: a kink
         * at contact): 1024 samples, as NLvib's example 03 takes (at 128, H = 21, Newton
         * stalls at a relative residual of 1.5e-7 near grazing; at 1024 the whole branch
         * converges), and corners of the sampled branch taken as corners
         * (continuation.c) */
        const gd_transient_spec *spc = param ? st0.spec : spec;
        gd_law *laws = NULL;
        int nlaws = 0;
        gd_error e3;
        if (s0 && spc && !gd_transient_spec_laws(s0, spc, sp, &laws, &nlaws, &e3)) {
            for (int i = 0; i < nlaws; i++) {
                if (gd_law_nswitches(&laws[i]) > 0 || !(gd_law_flags(&laws[i]) & GD_LAW_SMOOTH))
                    c.shoot_stab |= opt->shoot_stability == 1 && opt->stability;
                if (gd_law_nswitches(&laws[i]) > 0) {
                    c.min_samples = c.min_samples > 128 ? c.min_samples : 128;
                } else if (!(gd_law_flags(&laws[i]) & GD_LAW_SMOOTH)) {
                    c.min_samples = c.min_samples > 1024 ? c.min_samples : 1024;
                    c.corners = 1;
                }
            }
            free(laws);
        }
        /* a one-sided contact (a backlash mesh without a coast flank): when the teeth part
         * the force drops to the free damping with nothing to meet on the far side, a kink
         * like the unilateral spring's rather than a second flank's switch: the same 1024
         * samples and corners (issue 33: such a pair failed 16 of 36 points at 128 that
         * --samples 1024 solved) */
        for (int i = 0; spc && i < spc->nmeshes; i++)
            if (spc->meshes[i].backlash && spc->meshes[i].coast_scale == 0.0) {
                c.min_samples = c.min_samples > 1024 ? c.min_samples : 1024;
                c.corners = 1;
            }
        gd_per_stage_clear(&st0);
        if (H0 > c.Hcap) {
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "harmonics",
                                "give fewer harmonics (or raise memory_limit)",
                                "H = %d needs about %.2g GB for its workspace, more than the "
                                "limit of %.2g GB (largest H: %d)",
                                H0, need / 1e9, lim / 1e9, c.Hcap);
        }
        c.H = H0;
    }
    c.ndir = opt->both_directions ? 2 : 1;
    int rc = gd_per_hb_setup(&c, H0) || gd_per_run_branch(&c, ops, values, nvalues, H0);
    gd_per_stage_clear(&c.st[0]);
    gd_per_stage_clear(&c.st[1]);
    gd_hb_free(&c.h);
    gd_hb_free(&c.hr);
    res->steps = c.steps;
    if (c.chb_tried) { /* the choice stated (issue 33 item 3) */
        size_t len = strlen(res->method_note);
        snprintf(res->method_note + len, sizeof res->method_note - len,
                 "%sharmonic balance condensed onto %d law coordinates: %ld of %ld fixed-value "
                 "solves (the rest by the full Newton)",
                 len ? "; " : "", c.chb_nc, c.chb_solves, c.chb_tried);
    }
    if (rc) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    return GD_OK;
}
