/* The study report: every analysis of a model run with report defaults and its figure
 * appended to one document (geardyn/report.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/report.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "geardyn/waterfall.h"

#define PI 3.14159265358979323846
enum { MAX_PROBES = 32 };

void gd_report_options_init(gd_report_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->speed = -1;
    opt->nmodes = 8;
    opt->nfreq = 400;
    opt->runup_revolutions = 200;
}

static int add_probe(gd_probe *pr, int *n, int index, gd_dof dir, const char *name,
                     const char *suffix)
{
    if (*n == MAX_PROBES) return 0;
    pr[*n] = (gd_probe){.element = NULL, .index = index, .dir = dir};
    snprintf(pr[*n].name, sizeof pr[*n].name, "%s%s", name, suffix);
    (*n)++;
    return 1;
}

/* Mesh forces and the lateral forces of every bearing (gd_probe_defaults). */
static void force_probes(const gd_system *sys, gd_probe *pr, int *n)
{
    *n += gd_probe_defaults(sys, pr + *n, MAX_PROBES - *n);
}

/* The FRF input: the torque on the first mesh's driver, else a lateral force on the
 * first disk, else the first DOF. */
static int frf_input(const gd_system *sys)
{
    const gd_model *m = sys->model;
    int i = m->nmeshes ? gd_system_dof(sys, m->meshes[0].driver, GD_RZ) : -1;
    if (i < 0 && m->ndisks) i = gd_system_dof(sys, m->disks[0].node, GD_X);
    return i < 0 ? 0 : i;
}

static gd_status add_modes(gd_plot *doc, const gd_system *sys, double speed, double *wtop,
                           gd_error *err)
{
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.speed = speed;
    mo.nmodes = sys->ndof <= 30 ? 0 : 12;
    mo.want_left = 0;
    gd_modal_result *r;
    gd_status st = gd_modal_solve(sys, &mo, &r, err);
    if (st) return st;
    *wtop = 0;
    for (int j = 0; j < r->nmodes; j++)
        if (isfinite(r->modes[j].omega_n)) *wtop = fmax(*wtop, r->modes[j].omega_n);
    gd_plot *p;
    st = gd_plot_modal(sys, r, &p, err);
    gd_modal_free(r);
    if (!st) st = gd_plot_append(doc, p, err);
    if (!st && speed == 0)
        st = gd_plot_add_note(
            doc, "Modes at rest",
            "The model gives no operating speed (`speed:` in the model file), so the modes "
            "above are at 0 rpm, where no gyroscopic term acts and every whirl is none. Give "
            "`speed:` in the model or `geardyn report --speed 3000rpm` for the modes and whirl "
            "at the operating speed; the Campbell diagram below shows them over speed.",
            err);
    return st;
}

static gd_status add_campbell(gd_plot *doc, const gd_system *sys, const gd_report_options *opt,
                              const double *speeds, int ns, gd_error *err)
{
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.speeds = speeds;
    co.nspeeds = ns;
    co.nmodes = opt->nmodes;
    co.nthreads = opt->nthreads;
    gd_campbell_result *r;
    gd_status st = gd_campbell(sys, &co, &r, err);
    if (st) return st;
    gd_plot *p;
    st = gd_plot_campbell(r, &p, err);
    gd_campbell_free(r);
    return st ? st : gd_plot_append(doc, p, err);
}

static gd_status add_frf(gd_plot *doc, const gd_system *sys, const gd_report_options *opt,
                         double speed, double wmax, gd_error *err)
{
    gd_probe pr[MAX_PROBES];
    int np = 0;
    force_probes(sys, pr, &np);
    if (!np) return GD_OK;
    int nf = opt->nfreq > 1 ? opt->nfreq : 400, in = frf_input(sys);
    double *w = malloc((size_t)nf * sizeof *w);
    if (!w) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (!(wmax > 0)) wmax = 2 * PI * 1000;
    for (int k = 0; k < nf; k++) /* from one step above 0: rigid-body modes are singular there */
        w[k] = 1.3 * wmax * (k + 1) / nf;
    gd_frf_options fo;
    gd_frf_options_init(&fo);
    fo.freqs = w;
    fo.nfreq = nf;
    fo.speed = speed;
    fo.inputs = &in;
    fo.ninputs = 1;
    fo.outputs = pr;
    fo.noutputs = np;
    fo.nthreads = opt->nthreads;
    gd_frf_result *r;
    gd_status st = gd_frf(sys, &fo, &r, err);
    if (!st) {
        gd_plot *p;
        st = gd_plot_frf(sys, &fo, r, &p, err);
        if (!st) st = gd_plot_append(doc, p, err);
        gd_frf_free(r);
    }
    free(w);
    return st;
}

static gd_status add_unbalance(gd_plot *doc, const gd_system *sys, const gd_report_options *opt,
                               const double *speeds, int ns, gd_error *err)
{
    const gd_model *m = sys->model;
    gd_probe pr[MAX_PROBES];
    int orb[MAX_PROBES], np = 0, nb = 0;
    for (int u = 0; u < m->nunbalances; u++) {
        int node = m->unbalances[u].node, x = gd_system_dof(sys, node, GD_X),
            y = gd_system_dof(sys, node, GD_Y), seen = 0;
        for (int k = 0; k < nb; k++)
            seen |= orb[k] == node;
        if (seen || x < 0 || y < 0 || nb == MAX_PROBES) continue;
        orb[nb++] = node;
        add_probe(pr, &np, x, GD_X, m->nodes[node].name, ".x");
        add_probe(pr, &np, y, GD_Y, m->nodes[node].name, ".y");
    }
    force_probes(sys, pr, &np);
    gd_unbalance_options uo;
    gd_unbalance_options_init(&uo);
    uo.speeds = speeds;
    uo.nspeeds = ns;
    uo.outputs = pr;
    uo.noutputs = np;
    uo.orbit_nodes = orb;
    uo.norbits = nb;
    uo.nthreads = opt->nthreads;
    gd_unbalance_result *r;
    gd_status st = gd_unbalance_response(sys, &uo, &r, err);
    if (st) return st;
    gd_plot *p;
    st = gd_plot_unbalance(sys, &uo, r, 0, &p, err);
    gd_unbalance_free(r);
    return st ? st : gd_plot_append(doc, p, err);
}

/* What excites a run-up of the model, named in buf (empty when nothing does). */
static const char *runup_forcing(const gd_model *m, const gd_transient_model *tm, char *buf,
                                 size_t len)
{
    int mesh = 0,
        other = tm->spec.nloads || tm->spec.ncams || tm->spec.nlaws || tm->spec.nprescribed;
    for (int i = 0; i < tm->spec.nmeshes; i++)
        mesh |= tm->meshes[i].tvms || tm->meshes[i].ste || tm->meshes[i].backlash;
    const char *part[3] = {m->nunbalances ? "the model's unbalances" : NULL,
                           mesh ? "the meshes' time-varying laws" : NULL,
                           other ? "the model's loads, cams and laws" : NULL};
    buf[0] = 0;
    for (int k = 0; k < 3; k++)
        if (part[k])
            snprintf(buf + strlen(buf), len - strlen(buf), "%s%s", buf[0] ? " and " : "", part[k]);
    return buf;
}

/* The run-up waterfall (gd_report_options.runup_*): one transient through the ramp,
 * order-tracked (geardyn/waterfall.h). */
static gd_status add_runup(gd_plot *doc, const gd_system *sys, const gd_report_options *opt,
                           gd_error *err)
{
    const gd_model *m = sys->model;
    const double w0 = opt->runup_from, w1 = opt->runup_to;
    if (!(w0 * w1 >= 0) || !isfinite(w0) || !isfinite(w1))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--run-up", "give FROM:TO of one sign",
                            "run-up speeds %g -> %g rad/s", w0, w1);
    const double revs = opt->runup_revolutions > 0 ? opt->runup_revolutions : 200;
    gd_transient_model *tm = NULL;
    gd_status st = gd_transient_model_build(sys, &tm, err);
    if (st) return st;
    char fbuf[160];
    const char *forcing = runup_forcing(m, tm, fbuf, sizeof fbuf);
    gd_tr_record rec = {GD_REC_DISP, -1, 0};
    if (m->nunbalances) rec.index = gd_system_dof(sys, m->unbalances[0].node, GD_X);
    if (rec.index < 0 && m->nmeshes) rec = (gd_tr_record){GD_REC_MESH_FORCE, 0, 0};
    if (rec.index < 0 && m->ndisks) rec.index = gd_system_dof(sys, m->disks[0].node, GD_X);
    if (!forcing[0] || rec.index < 0) {
        gd_transient_model_free(tm);
        return gd_plot_add_note(
            doc, "Run-up waterfall",
            !forcing[0] ? "None: nothing in the model excites a run-up (no unbalance, no mesh "
                          "time-varying stiffness or transmission error, no load, cam or law); "
                          "add `unbalances:` to the model file (docs/model-format.md)."
                        : "None: the model has no unbalance node, mesh or disk to record.",
            err);
    }
    /* the ramp over `revs` turns at the mean speed; the order tracking's S points per turn
     * (the power of two >= 2.5 x the highest order a mesh law excites, at least 32) and
     * 2 S samples and generalized-alpha steps per turn at the top speed */
    const double wm = 0.5 * fabs(w0 + w1), wt = fmax(fabs(w0), fabs(w1));
    double top = 1;
    for (int i = 0; i < tm->spec.nmeshes; i++) {
        int set;
        if (gd_model_planetary_mesh(m, tm->meshes[i].mesh, &set, NULL, NULL)) {
            /* a planetary mesh: Z_s times the sun's speed relative to the carrier */
            const gd_planetary *pg = &m->planetary[set];
            const gd_shaft *sh = m->shafts;
            top = fmax(
                top,
                pg->teeth[0] *
                    fabs(sh[m->nodes[pg->member[GD_PLANETARY_SUN].node].shaft].speed_ratio -
                         sh[m->nodes[pg->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio));
            continue;
        }
        const gd_mesh *g = &m->meshes[tm->meshes[i].mesh];
        if (tm->meshes[i].tvms || tm->meshes[i].ste || tm->meshes[i].backlash)
            top = fmax(top, g->teeth[0] * fabs(m->shafts[m->nodes[g->driver].shaft].speed_ratio));
    }
    int spr = 32;
    while (spr < 2.5 * top && spr < (1 << 16))
        spr *= 2;
    if (revs * 2.0 * spr * wt / wm > 2e7) {
        gd_transient_model_free(tm);
        return gd_plot_add_note(doc, "Run-up waterfall",
                                "None: the run-up would take over 2e7 steps (the mesh orders "
                                "need fine steps); run geardyn transient --speed-ramp "
                                "--waterfall with a shorter ramp or fewer turns.",
                                err);
    }
    gd_speed_profile prof = {GD_SPEED_RAMP, w0, w1, 0, 2 * PI * revs / wm, 0, NULL, NULL};
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    gd_waterfall *wf = NULL;
    double *ang = NULL;
    if ((st = gd_transient_new(sys, &tm->spec, 0.5 * (w0 + w1), &tr, err))) goto done;
    gd_transient_options to;
    gd_transient_options_init(&to);
    to.t_end = prof.t1;
    to.output_interval = 2 * PI / wt / (2.0 * spr);
    to.method = GD_TR_GEN_ALPHA;
    to.step = to.output_interval;
    to.profile = &prof;
    if ((st = gd_transient_run(tr, &to, &rec, 1, &res, err))) goto done;
    ang = malloc((size_t)res->nout * sizeof *ang);
    if (!ang) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    for (int k = 0; k < res->nout; k++)
        gd_speed_profile_eval(&prof, res->t[k], &ang[k], NULL, NULL);
    gd_order_track_options oo;
    gd_order_track_options_init(&oo);
    oo.revs_per_block = 8;
    oo.samples_per_rev = spr;
    if ((st = gd_waterfall_order_track(sys, res->t, res->values, ang, res->nout, &oo, &wf, err)))
        goto done;
    gd_plot *p;
    if ((st = gd_plot_waterfall(sys, wf, &rec, NULL, &p, err))) goto done;
    char note[700];
    double acc = (w1 - w0) / prof.t1;
    snprintf(note, sizeof note,
             "A run-up from %.6g to %.6g rpm in %.3g s (%.4g rpm/s, %g turns of the reference "
             "shaft), forced by %s, from rest; generalized-alpha at %d steps per turn at the "
             "top speed (%.3g s of CPU). Resolution: a block of 8 turns spans %.3g rpm at the "
             "mean speed, and a resonance swept through at this rate peaks late (less so the "
             "slower the ramp); orders up to %d resolved.",
             w0 * 30 / PI, w1 * 30 / PI, prof.t1, acc * 30 / PI, revs, forcing, 2 * spr,
             res->cpu_seconds, fabs(acc) * 2 * PI * 8 / wm * 30 / PI, spr / 2);
    st = gd_plot_add_note(doc, "Run-up", note, err);
    if (st)
        gd_plot_free(p);
    else
        st = gd_plot_append(doc, p, err);
done:
    free(ang);
    gd_waterfall_free(wf);
    gd_transient_result_free(res);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    return st;
}

gd_status gd_report_build(const gd_system *sys, const gd_report_options *opt, gd_plot **out,
                          gd_error *err)
{
    const gd_model *m = sys->model;
    gd_report_options def;
    if (!opt) {
        gd_report_options_init(&def);
        opt = &def;
    }
    double speed = opt->speed >= 0 ? opt->speed : m->speed;
    int ns = opt->nspeeds;
    double *own = NULL;
    const double *speeds = opt->speeds;
    if (ns <= 0 || !speeds) {
        ns = 41;
        own = malloc((size_t)ns * sizeof *own);
        if (!own) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        double top = m->speed > 0 ? 2 * m->speed : 10000 * PI / 30;
        for (int k = 0; k < ns; k++)
            own[k] = top * k / (ns - 1);
        speeds = own;
    }
    char title[400];
    snprintf(title, sizeof title, "geardyn report: %s", m->file);
    gd_plot *doc, *p;
    gd_status st = gd_plot_new(title, &doc, err);
    double wmax = 0;
    if (!st && !(st = gd_plot_model(m, &p, err))) st = gd_plot_append(doc, p, err);
    if (!st) st = add_modes(doc, sys, speed, &wmax, err);
    if (!st) st = add_campbell(doc, sys, opt, speeds, ns, err);
    if (!st) st = add_frf(doc, sys, opt, speed, wmax, err);
    if (!st && m->nunbalances)
        st = add_unbalance(doc, sys, opt, speeds, ns, err);
    else if (!st)
        st = gd_plot_add_note(doc, "Unbalance response",
                              "None: the model has no unbalance (add `unbalances:` to the model "
                              "file, docs/model-format.md).",
                              err);
    if (!st && opt->runup_to != opt->runup_from)
        st = add_runup(doc, sys, opt, err);
    else if (!st)
        st = gd_plot_add_note(doc, "Run-up waterfall",
                              "Not asked for: `geardyn report --run-up FROM:TO` adds one (a "
                              "transient through the ramp, order-tracked; docs/plots.md).",
                              err);
    int ngeo = 0;
    for (int g = 0; g < m->nmeshes; g++)
        ngeo += m->meshes[g].tvms != NULL;
    if (!st && !ngeo)
        st = gd_plot_add_note(doc, "Mesh stiffness",
                              "None: no mesh takes its stiffness from its geometry (`stiffness: "
                              "{from: geometry}`, docs/mesh-stiffness.md).",
                              err);
    for (int g = 0; !st && g < m->nmeshes; g++) {
        if (!m->meshes[g].tvms) continue;
        const gd_tvms_result *r = m->meshes[g].tvms;
        if (!(st = gd_plot_tvms(&r, NULL, 1, m->meshes[g].name, &p, err)))
            st = gd_plot_append(doc, p, err);
    }
    free(own);
    if (st) {
        gd_plot_free(doc);
        return st;
    }
    *out = doc;
    return GD_OK;
}
