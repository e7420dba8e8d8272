/* `geardyn transient --sweep-speeds FROM:TO:COUNT --poincare SHAFT|MESH`: a bifurcation
 * diagram by time integration, the state carried from one speed to the next (run-up,
 * run-down or both), Poincare points per speed and their periodicity; with --waterfall
 * REC the spectrum of REC over each speed's settled part, the run-up waterfall and its
 * order cuts (geardyn/waterfall.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "geardyn/plot.h"
#include "geardyn/waterfall.h"
#include "transient_poincare.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct sweep_point {
    double speed, t_start, t_end;
    int down, n, period, distinct;
    char verdict[32];   /* gd_poincare_verdict_name */
    double *t, *values; /* n; nrec * n */
    double cpu;
    long steps;
    gd_spectrum *spec; /* --waterfall: the record's spectrum over the settled part */
} sweep_point;

static void points_free(sweep_point *pts, int n)
{
    for (int i = 0; i < n; i++) {
        free(pts[i].t);
        free(pts[i].values);
        gd_spectrum_free(pts[i].spec);
    }
    free(pts);
}

/* One speed: rebuild, run from (t0, q, v) (q NULL: the base start), sample; q, v
 * receive the end state. */
static gd_status one_speed(const gd_system *sys, const gd_transient_model *tm,
                           const gd_cli_records *recs, const gd_tr_record *rr,
                           const gd_cli_poincare *p, const gd_cli_sweep *sw, double W, double t0,
                           double *q, double *v, int given, sweep_point *pt, gd_error *err)
{
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    double *times = NULL;
    gd_status st = gd_transient_new(sys, &tm->spec, W, &tr, err);
    if (st) return st;
    double P = p->angle / W;
    double settle = sw->settle_time > 0 ? sw->settle_time : sw->settle_revs * 2 * M_PI / W;
    double k0 = ceil((t0 + settle) / P - 1e-9);
    gd_transient_options opt = sw->base;
    opt.t_start = t0;
    opt.record_from = k0 * P;
    opt.t_end = (k0 + sw->points - 1) * P;
    /* 16 samples per Poincare period; for a waterfall also 2.5 per period of the highest
     * order at the top speed, so every spectrum reaches the same frequency (whole samples
     * per period, so the settled part is a whole number of them) */
    int per = 16;
    if (sw->waterfall >= 0) { /* at every speed, up to the top speed's highest order */
        double wtop = sw->speeds[sw->nspeeds - 1] > W ? sw->speeds[sw->nspeeds - 1] : W;
        per = (int)fmax(16, ceil(2.5 * sw->max_order * p->angle / (2 * M_PI) * wtop / W));
    }
    opt.output_interval = P / per;
    if (given) {
        opt.init = GD_TR_INIT_GIVEN;
        opt.q0 = q;
        opt.v0 = v;
    }
    int n = gd_cli_poincare_times(p, W, opt.record_from, opt.t_end, &times);
    if (n != sw->points) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "Poincare times (%d of %d)", n,
                          sw->points);
        goto done;
    }
    opt.sample_times = times;
    opt.nsample_times = n;
    if ((st = gd_transient_run(tr, &opt, rr, recs->n, &res, err))) goto done;
    double *scale = malloc((size_t)(recs->n > 0 ? recs->n : 1) * sizeof *scale);
    if (!scale) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    for (int r = 0; r < recs->n; r++)
        scale[r] = res->stats[r].peak_to_peak;
    /* the spectrum over the settled part: samples k0 P .. t_end less the last, a whole
     * number of Poincare periods */
    if (sw->waterfall >= 0 &&
        (st = gd_spectrum_compute(res->values + (size_t)sw->waterfall * res->nout, res->nout - 1,
                                  res->t[1] - res->t[0], GD_WINDOW_HANN, &pt->spec, err))) {
        free(scale);
        goto done;
    }
    pt->speed = W;
    pt->t_start = t0;
    pt->t_end = opt.t_end;
    pt->n = n;
    gd_cli_poincare_classify(res->sample_values, recs->n, n, scale, &pt->period, &pt->distinct,
                             pt->verdict, sizeof pt->verdict);
    free(scale);
    pt->t = times;
    times = NULL;
    pt->values = res->sample_values;
    res->sample_values = NULL;
    pt->cpu = res->cpu_seconds;
    pt->steps = res->steps;
    memcpy(q, res->q_end, (size_t)sys->ndof * sizeof *q);
    memcpy(v, res->v_end, (size_t)sys->ndof * sizeof *v);
done:
    free(times);
    gd_transient_result_free(res);
    gd_transient_free(tr);
    return st;
}

static double range_of(const double *x, int n, double *mx)
{
    double mn = n ? x[0] : 0;
    *mx = mn;
    for (int k = 1; k < n; k++) {
        mn = fmin(mn, x[k]);
        *mx = fmax(*mx, x[k]);
    }
    return mn;
}

static cJSON *sweep_json(const gd_system *sys, const gd_cli_records *recs, const gd_cli_poincare *p,
                         const gd_cli_sweep *sw, const sweep_point *pts, int npts, double cpu)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", sys->model->file);
    cJSON_AddStringToObject(o, "mode", "sweep");
    cJSON_AddStringToObject(o, "poincare_source", p->name);
    if (sw->settle_time > 0)
        cJSON_AddNumberToObject(o, "settle_s", sw->settle_time);
    else
        cJSON_AddNumberToObject(o, "settle_revolutions", sw->settle_revs);
    cJSON_AddNumberToObject(o, "points_per_speed", sw->points);
    cJSON_AddNumberToObject(o, "tolerance", GD_CLI_POINCARE_TOL);
    cJSON_AddNumberToObject(o, "rtol", sw->base.rtol);
    cJSON_AddNumberToObject(o, "cpu_seconds", cpu);
    cJSON *sa = cJSON_AddArrayToObject(o, "speeds");
    for (int i = 0; i < npts; i++) {
        const sweep_point *pt = &pts[i];
        char cls[32];
        gd_cli_poincare_class_name(pt->period, cls, sizeof cls);
        cJSON *e = cJSON_CreateObject();
        cJSON_AddNumberToObject(e, "speed_rad_s", pt->speed);
        cJSON_AddNumberToObject(e, "speed_rpm", pt->speed * 30 / M_PI);
        cJSON_AddStringToObject(e, "direction", pt->down ? "down" : "up");
        cJSON_AddNumberToObject(e, "t_start_s", pt->t_start);
        cJSON_AddNumberToObject(e, "t_end_s", pt->t_end);
        cJSON_AddNumberToObject(e, "period", pt->period);
        cJSON_AddNumberToObject(e, "distinct_points", pt->distinct);
        cJSON_AddStringToObject(e, "class", cls);
        cJSON_AddStringToObject(e, "verdict", pt->verdict);
        cJSON_AddNumberToObject(e, "steps", (double)pt->steps);
        cJSON_AddNumberToObject(e, "cpu_seconds", pt->cpu);
        cJSON *ra = cJSON_AddArrayToObject(e, "records");
        for (int r = 0; r < recs->n; r++) {
            const double *x = pt->values + (size_t)r * pt->n;
            double mx, mn = range_of(x, pt->n, &mx);
            cJSON *re = cJSON_CreateObject();
            cJSON_AddStringToObject(re, "name", recs->r[r].name);
            cJSON_AddItemToObject(re, "min", gd_cli_json_number(mn));
            cJSON_AddItemToObject(re, "max", gd_cli_json_number(mx));
            cJSON *va = cJSON_AddArrayToObject(re, "values");
            for (int k = 0; k < pt->n; k++)
                cJSON_AddItemToArray(va, gd_cli_json_number(x[k]));
            cJSON_AddItemToArray(ra, re);
        }
        cJSON_AddItemToArray(sa, e);
    }
    return o;
}

static int write_sweep(const char *dir, const gd_cli_records *recs, const sweep_point *pts,
                       int npts, const cJSON *summary, const gd_waterfall *w)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "poincare.csv", &err);
    if (!f) goto fail;
    fprintf(f, "direction,speed_rad_s,speed_rpm,point,time_s");
    for (int r = 0; r < recs->n; r++)
        fprintf(f, ",%s", recs->r[r].name);
    fprintf(f, "\n");
    for (int i = 0; i < npts; i++)
        for (int k = 0; k < pts[i].n; k++) {
            fprintf(f, "%s,%.10g,%.10g,%d,%.12g", pts[i].down ? "down" : "up", pts[i].speed,
                    pts[i].speed * 30 / M_PI, k, pts[i].t[k]);
            for (int r = 0; r < recs->n; r++)
                fprintf(f, ",%.10g", pts[i].values[(size_t)r * pts[i].n + k]);
            fprintf(f, "\n");
        }
    if (gd_outdir_close(&od, f, "poincare.csv", &err)) goto fail;
    f = gd_outdir_open(&od, "sweep.csv", &err);
    if (!f) goto fail;
    fprintf(f, "direction,speed_rad_s,speed_rpm,class,period,distinct_points,cpu_s");
    for (int r = 0; r < recs->n; r++)
        fprintf(f, ",%s_min,%s_max", recs->r[r].name, recs->r[r].name);
    fprintf(f, ",verdict\n");
    for (int i = 0; i < npts; i++) {
        char cls[32];
        gd_cli_poincare_class_name(pts[i].period, cls, sizeof cls);
        fprintf(f, "%s,%.10g,%.10g,%s,%d,%d,%.4g", pts[i].down ? "down" : "up", pts[i].speed,
                pts[i].speed * 30 / M_PI, cls, pts[i].period, pts[i].distinct, pts[i].cpu);
        for (int r = 0; r < recs->n; r++) {
            double mx, mn = range_of(pts[i].values + (size_t)r * pts[i].n, pts[i].n, &mx);
            fprintf(f, ",%.10g,%.10g", mn, mx);
        }
        fprintf(f, ",%s\n", pts[i].verdict);
    }
    if (gd_outdir_close(&od, f, "sweep.csv", &err)) goto fail;
    if (w && gd_cli_waterfall_csv(&od, w, &err)) goto fail;
    f = gd_outdir_open(&od, "summary.json", &err);
    if (!f) goto fail;
    gd_cli_print_json(f, summary);
    if (gd_outdir_close(&od, f, "summary.json", &err)) goto fail;
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

static void print_sweep(const gd_system *sys, const gd_cli_records *recs, const gd_cli_poincare *p,
                        const gd_cli_sweep *sw, const sweep_point *pts, int npts, double cpu)
{
    printf("%s: bifurcation sweep, %d runs, Poincare samples once per period of %s, %d per "
           "speed after settling ",
           sys->model->file, npts, p->name, sw->points);
    if (sw->settle_time > 0)
        printf("%g s", sw->settle_time);
    else
        printf("%g revolutions", sw->settle_revs);
    printf("; same point within %g of each record's peak-to-peak; %.3g s CPU\n\n",
           GD_CLI_POINCARE_TOL, cpu);
    const char *r0 = recs->n ? recs->r[0].name : "";
    printf("%-4s %12s %12s %-10s %8s %14s %14s  %s\n", "dir", "speed_rad_s", "speed_rpm", "class",
           "distinct", "min", "max", "verdict");
    printf("%-4s %12s %12s %-10s %8s %29.29s\n", "", "", "", "", "", r0);
    for (int i = 0; i < npts; i++) {
        char cls[32];
        gd_cli_poincare_class_name(pts[i].period, cls, sizeof cls);
        double mx = 0, mn = recs->n ? range_of(pts[i].values, pts[i].n, &mx) : 0;
        printf("%-4s %12.6g %12.6g %-10s %8d %14.6g %14.6g  %s\n", pts[i].down ? "down" : "up",
               pts[i].speed, pts[i].speed * 30 / M_PI, cls, pts[i].distinct, mn, mx,
               pts[i].verdict);
    }
}

int gd_cli_waterfall_record(const char *cmd, const gd_system *sys, const gd_transient_model *tm,
                            const char *text, gd_cli_records *recs, int *index, double *max_order)
{
    const gd_model *m = sys->model;
    *max_order = 1;
    for (int s = 0; s < m->nshafts; s++)
        *max_order = fmax(*max_order, fabs(m->shafts[s].speed_ratio));
    for (int k = 0; k < m->nmeshes; k++)
        if (m->meshes[k].teeth[0] > 0)
            *max_order = fmax(*max_order,
                              m->meshes[k].teeth[0] *
                                  fabs(m->shafts[m->nodes[m->meshes[k].driver].shaft].speed_ratio));
    *index = 0;
    if (!text) {
        if (recs->n < 1) return gd_cli_usage_error(cmd, "--plot: give a record (--waterfall REC)");
        return 0;
    }
    gd_cli_records one = {0, 0, NULL};
    int rc = gd_cli_parse_records(cmd, sys, tm, text, &one);
    if (!rc && one.n != 1)
        rc = gd_cli_usage_error(cmd, "--waterfall: give one record (got %d in '%s')", one.n, text);
    if (rc) {
        gd_cli_records_free(&one);
        return rc;
    }
    const gd_tr_record *w = &one.r[0].rec;
    for (*index = 0; *index < recs->n; (*index)++) {
        const gd_tr_record *r = &recs->r[*index].rec;
        if (r->kind == w->kind && r->index == w->index && r->index2 == w->index2) break;
    }
    gd_cli_records_free(&one);
    if (*index == recs->n) return gd_cli_parse_records(cmd, sys, tm, text, recs);
    return 0;
}

/* --waterfall: the spectra, the orders and the order cuts */
cJSON *gd_cli_waterfall_json(const gd_cli_record *rec, const gd_waterfall *w)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "record", rec->name);
    cJSON_AddStringToObject(o, "unit", rec->unit ? rec->unit : "");
    cJSON_AddStringToObject(o, "window", "hann");
    cJSON *oa = cJSON_AddArrayToObject(o, "orders");
    for (int k = 0; k < w->norders; k++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "label", w->orders[k].label);
        cJSON_AddStringToObject(e, "kind",
                                w->orders[k].kind == GD_ORDER_MESH    ? "mesh"
                                : w->orders[k].kind == GD_ORDER_SHAFT ? "shaft"
                                                                      : "user");
        cJSON_AddNumberToObject(e, "order", w->orders[k].order);
        cJSON *aa = cJSON_AddArrayToObject(e, "amplitude");
        cJSON *fa = cJSON_AddArrayToObject(e, "frequency_hz");
        for (int i = 0; i < w->nspeeds; i++) {
            cJSON_AddItemToArray(
                aa, gd_cli_json_number(w->order_amplitude[(size_t)k * w->nspeeds + i]));
            cJSON_AddItemToArray(
                fa, gd_cli_json_number(w->order_frequency[(size_t)k * w->nspeeds + i]));
        }
        cJSON_AddItemToArray(oa, e);
    }
    cJSON *sa = cJSON_AddArrayToObject(o, "spectra");
    for (int i = 0; i < w->nspeeds; i++) {
        const gd_spectrum *sp = w->spectra[i];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddNumberToObject(e, "speed_rad_s", w->speeds[i]);
        cJSON_AddNumberToObject(e, "speed_rpm", w->speeds[i] * 30 / M_PI);
        cJSON_AddNumberToObject(e, "samples", sp->nsamples);
        cJSON_AddNumberToObject(e, "dt_s", sp->dt);
        cJSON_AddNumberToObject(e, "df_hz", sp->df);
        cJSON *fa = cJSON_AddArrayToObject(e, "frequency_hz");
        cJSON *aa = cJSON_AddArrayToObject(e, "amplitude");
        for (int k = 0; k < sp->n; k++) {
            cJSON_AddItemToArray(fa, gd_cli_json_number(sp->freq[k]));
            cJSON_AddItemToArray(aa, gd_cli_json_number(sp->amplitude[k]));
        }
        cJSON_AddItemToArray(sa, e);
    }
    return o;
}

int gd_cli_waterfall_csv(gd_outdir *od, const gd_waterfall *w, gd_error *err)
{
    FILE *f = gd_outdir_open(od, "waterfall.csv", err);
    if (!f) return 1;
    fprintf(f, "speed_rad_s,speed_rpm,frequency_hz,amplitude\n");
    for (int i = 0; i < w->nspeeds; i++)
        for (int k = 0; k < w->spectra[i]->n; k++)
            fprintf(f, "%.10g,%.10g,%.10g,%.10g\n", w->speeds[i], w->speeds[i] * 30 / M_PI,
                    w->spectra[i]->freq[k], w->spectra[i]->amplitude[k]);
    if (gd_outdir_close(od, f, "waterfall.csv", err)) return 1;
    if (!(f = gd_outdir_open(od, "order_cuts.csv", err))) return 1;
    fprintf(f, "speed_rad_s,speed_rpm");
    for (int k = 0; k < w->norders; k++)
        fprintf(f, ",\"%s\"", w->orders[k].label);
    fprintf(f, "\n");
    for (int i = 0; i < w->nspeeds; i++) {
        fprintf(f, "%.10g,%.10g", w->speeds[i], w->speeds[i] * 30 / M_PI);
        for (int k = 0; k < w->norders; k++)
            fprintf(f, ",%.10g", w->order_amplitude[(size_t)k * w->nspeeds + i]);
        fprintf(f, "\n");
    }
    return gd_outdir_close(od, f, "order_cuts.csv", err) ? 1 : 0;
}

void gd_cli_waterfall_print(const gd_cli_record *rec, const gd_waterfall *w, int down)
{
    if (w->tracked)
        printf("\n%s waterfall of %s (order tracking: the record resampled on the reference "
               "shaft's angle, one Hann-windowed order spectrum per %g revolutions at its mean "
               "speed): amplitude (%s) of each order, the largest within 1.5 bins (%.3g orders)\n",
               down ? "run-down" : "run-up", rec->name, w->revs_per_block,
               rec->unit ? rec->unit : "", 1.5 / w->revs_per_block);
    else
        printf("\n%s waterfall of %s (stepped: one steady run per speed; Hann window over the "
               "settled part): amplitude (%s) of each order, the largest within 1.5 bins of order "
               "x speed\n",
               down ? "run-down" : "run-up", rec->name, rec->unit ? rec->unit : "");
    printf("%12s", "speed_rpm");
    for (int k = 0; k < w->norders; k++) { /* "mesh 16x shaft_a", not "mesh mesh 16x ..." */
        const char *l = w->orders[k].label;
        if (w->orders[k].kind == GD_ORDER_MESH && !strncmp(l, "mesh mesh ", 10)) l += 5;
        printf(" %18.18s", l);
    }
    printf("\n");
    for (int i = 0; i < w->nspeeds; i++) {
        printf("%12.6g", w->speeds[i] * 30 / M_PI);
        for (int k = 0; k < w->norders; k++)
            printf(" %18.6g", w->order_amplitude[(size_t)k * w->nspeeds + i]);
        printf("\n");
    }
}

int gd_cli_transient_sweep(const gd_system *sys, const gd_transient_model *tm,
                           const gd_cli_records *recs, const gd_cli_poincare *p,
                           const gd_cli_sweep *sw)
{
    const int n = sw->nspeeds, nrun = sw->direction == 2 ? 2 * n : n;
    sweep_point *pts = calloc((size_t)nrun, sizeof *pts);
    gd_tr_record *rr = malloc((size_t)(recs->n > 0 ? recs->n : 1) * sizeof *rr);
    double *q = calloc((size_t)sys->ndof + 1, sizeof *q),
           *v = calloc((size_t)sys->ndof + 1, sizeof *v);
    cJSON *summary = NULL;
    gd_waterfall *wf = NULL;
    int rc = GD_EXIT_OK, done = 0;
    if (!pts || !rr || !q || !v) {
        fprintf(stderr, "geardyn: error: out of memory\n");
        rc = GD_EXIT_FAIL;
        goto out;
    }
    for (int r = 0; r < recs->n; r++)
        rr[r] = recs->r[r].rec;
    int tty = !sw->quiet && isatty(2);
    double t0 = 0, cpu = 0;
    for (int k = 0; k < nrun; k++) {
        int down = sw->direction == 1 || (sw->direction == 2 && k >= n);
        int i = k < n ? k : k - n;
        int idx = down ? n - 1 - i : i;
        double W = sw->speeds[idx];
        if (k > 0) t0 = pts[k - 1].t_end * pts[k - 1].speed / W; /* nominal angles W t go on */
        if (tty) fprintf(stderr, "\rspeed %d of %d: %g rad/s   ", k + 1, nrun, W);
        gd_error err;
        gd_error_clear(&err);
        pts[k].down = down;
        if (one_speed(sys, tm, recs, rr, p, sw, W, t0, q, v, k > 0, &pts[k], &err)) {
            if (tty) fprintf(stderr, "\r%60s\r", "");
            char msg[sizeof err.message + 64];
            snprintf(msg, sizeof msg, "at %g rad/s (%s): %s", W, down ? "run-down" : "run-up",
                     err.message);
            size_t l = strlen(msg) < sizeof err.message ? strlen(msg) : sizeof err.message - 1;
            memcpy(err.message, msg, l);
            err.message[l] = 0;
            rc = gd_cli_report(&err);
            goto out;
        }
        cpu += pts[k].cpu;
        done = k + 1;
    }
    if (tty) fprintf(stderr, "\r%60s\r", "");
    if (sw->waterfall >= 0) {
        gd_spectrum **spec = malloc((size_t)done * sizeof *spec);
        double *speeds = malloc((size_t)done * sizeof *speeds);
        gd_error err;
        gd_error_clear(&err);
        gd_status st = GD_ENOMEM;
        if (spec && speeds) {
            for (int k = 0; k < done; k++) {
                speeds[k] = pts[k].speed;
                spec[k] = pts[k].spec;
                pts[k].spec = NULL;
            }
            st = gd_waterfall_new(sys, done, speeds, spec, &wf, &err);
        } else
            gd_error_set(&err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        free(spec);
        free(speeds);
        if (st) {
            rc = gd_cli_report(&err);
            goto out;
        }
        if (sw->plot) { /* before any other output: a refused plot leaves nothing */
            gd_plot *pl = NULL;
            st = gd_plot_waterfall(sys, wf, &recs->r[sw->waterfall].rec, NULL, &pl, &err);
            if ((rc = gd_cli_plot_finish(st, pl, &err, sw->plot))) goto out;
        }
    }
    summary = sweep_json(sys, recs, p, sw, pts, done, cpu);
    if (wf)
        cJSON_AddItemToObject(summary, "waterfall",
                              gd_cli_waterfall_json(&recs->r[sw->waterfall], wf));
    if (sw->out && (rc = write_sweep(sw->out, recs, pts, done, summary, wf))) goto out;
    if (sw->json)
        gd_cli_print_json(stdout, summary);
    else {
        print_sweep(sys, recs, p, sw, pts, done, cpu);
        if (wf) gd_cli_waterfall_print(&recs->r[sw->waterfall], wf, sw->direction == 1);
    }
out:
    gd_waterfall_free(wf);
    cJSON_Delete(summary);
    if (pts) points_free(pts, nrun);
    free(rr);
    free(q);
    free(v);
    return rc;
}
