/* geardyn transient MODEL: time integration of the nonlinear, time-varying system
 * (docs/transient.md), records, statistics, contact history and spectra. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "options.h"
#include "geardyn/spectrum.h"
#include "geardyn/transient_model.h"
#include "geardyn/units.h"
#include "transient_periods.h"
#include "transient_rattle.h"
#include "transient_poincare.h"
#include "transient_profile.h"
#include "transient_record.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static const char CMD[] = "transient";

enum { NPEAKS = 6 };

typedef struct progress {
    int last; /* last percentage drawn */
    int drawn;
} progress;

static void progress_cb(double t, double t0, double t1, void *data)
{
    progress *p = data;
    int pct = (int)(100.0 * (t - t0) / (t1 - t0));
    if (pct < 0) pct = 0;
    if (pct > 100) pct = 100;
    if (pct == p->last) return;
    p->last = pct;
    p->drawn = 1;
    char bar[41];
    int fill = pct * 40 / 100;
    for (int i = 0; i < 40; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[40] = 0;
    fprintf(stderr, "\r[%s] %3d%%  t = %.6g s", bar, pct, t);
    fflush(stderr);
}

static int parse_time(const char *opt, const char *text, double *out)
{
    gd_error why;
    if (gd_parse_quantity(text, GD_QTY_TIME, out, &why))
        return gd_cli_usage_error(CMD, "%s: %s (e.g. %s 12ms)", opt, why.message, opt);
    if (!isfinite(*out)) return gd_cli_usage_error(CMD, "%s: give a finite time", opt);
    return 0;
}

static int parse_positive(const char *opt, const char *text, double *out)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !isfinite(v) || v <= 0)
        return gd_cli_usage_error(CMD, "%s: '%s' is not a positive number", opt, text);
    *out = v;
    return 0;
}

/* --settle T|Nrev: a time, or revolutions of the reference shaft ("200rev"). */
static int parse_settle(const char *text, double *time, double *revs)
{
    *time = *revs = 0;
    size_t l = strlen(text);
    if (l > 3 && !strcmp(text + l - 3, "rev")) {
        char buf[64];
        if (l - 3 >= sizeof buf) return gd_cli_usage_error(CMD, "--settle: value too long");
        memcpy(buf, text, l - 3);
        buf[l - 3] = 0;
        char *end;
        *revs = strtod(buf, &end);
        if (end == buf || *end || !isfinite(*revs) || *revs < 0)
            return gd_cli_usage_error(CMD,
                                      "--settle: '%s' is not a number of revolutions >= 0 "
                                      "(e.g. 200rev)",
                                      text);
        return 0;
    }
    if (parse_time("--settle", text, time)) return GD_EXIT_INPUT;
    if (*time < 0) return gd_cli_usage_error(CMD, "--settle: give a time >= 0");
    return 0;
}

typedef struct run_info {
    double speed, t_end, from, dt;
    const char *method, *start;
    gd_window window;
    int spectrum;
    int kept, modes;      /* reduced model: physical DOFs kept, modes; kept -1: full */
    const char *condense; /* the default's choice, said in the output; NULL: none made */
} run_info;

static double order_of(double f_hz, double speed)
{
    return speed > 0 ? f_hz * 2 * M_PI / speed : 0.0;
}

static cJSON *spectrum_json(const gd_spectrum *s, double speed)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "window", gd_window_names[s->window]);
    cJSON_AddNumberToObject(o, "df_hz", s->df);
    gd_spectrum_peak pk[NPEAKS];
    int np = gd_spectrum_peaks(s, 1e-3, NPEAKS, pk);
    cJSON *a = cJSON_AddArrayToObject(o, "peaks");
    for (int k = 0; k < np; k++) {
        cJSON *p = cJSON_CreateObject();
        cJSON_AddNumberToObject(p, "frequency_hz", pk[k].frequency);
        if (speed > 0) cJSON_AddNumberToObject(p, "order", order_of(pk[k].frequency, speed));
        cJSON_AddNumberToObject(p, "amplitude", pk[k].amplitude);
        cJSON_AddItemToArray(a, p);
    }
    if (speed > 0) {
        double f1 = speed / (2 * M_PI), fa = 0, fb = 0;
        double one = gd_spectrum_band_max(s, 0.95 * f1, 1.05 * f1, &fa);
        /* below 1x: from 3 bins (clear of the mean) to 0.95x, and 4 bins clear of the
         * 1x main lobe */
        double below = gd_spectrum_band_max(s, 2.5 * s->df, fmin(0.95 * f1, f1 - 4 * s->df), &fb);
        cJSON_AddNumberToObject(o, "amplitude_1x", one);
        cJSON_AddNumberToObject(o, "max_below_1x", below);
        cJSON_AddNumberToObject(o, "max_below_1x_order", order_of(fb, speed));
    }
    return o;
}

static cJSON *summary_json(const gd_system *sys, const gd_transient_model *tm,
                           const gd_cli_records *recs, const gd_transient_result *res,
                           gd_spectrum *const *spec, const run_info *ri, int nfree)
{
    const gd_model *m = sys->model;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", m->file);
    cJSON_AddNumberToObject(o, "speed_rad_s", ri->speed);
    cJSON_AddNumberToObject(o, "speed_rpm", ri->speed * 30 / M_PI);
    cJSON_AddNumberToObject(o, "dofs", sys->ndof);
    cJSON_AddNumberToObject(o, "free_dofs", nfree);
    if (ri->kept >= 0) {
        cJSON_AddNumberToObject(o, "reduced_kept_dofs", ri->kept);
        cJSON_AddNumberToObject(o, "reduced_modes", ri->modes);
    }
    cJSON_AddNumberToObject(o, "t_end_s", ri->t_end);
    cJSON_AddNumberToObject(o, "record_from_s", ri->from);
    cJSON_AddNumberToObject(o, "output_interval_s", ri->dt);
    cJSON_AddNumberToObject(o, "samples", res->nout);
    cJSON_AddStringToObject(o, "method", ri->method);
    if (ri->condense) cJSON_AddStringToObject(o, "condense", ri->condense);
    if (!strncmp(ri->method, "auto:", 5)) {
        static const char *const names[] = {"bdf", "adams", "galpha", "auto", "lti"};
        cJSON_AddStringToObject(o, "method_used", names[res->method_used]);
        if (res->error_estimate >= 0 && res->method_used == GD_TR_LTI)
            cJSON_AddNumberToObject(o, "step_s", res->step);
    }
    /* the estimated global error of the records (LTI: step halving; CVODE: a run at
     * looser tolerances), relative to each record's peak */
    if (res->error_estimate >= 0) cJSON_AddNumberToObject(o, "error_estimate", res->error_estimate);
    cJSON_AddStringToObject(o, "start", ri->start);
    cJSON_AddNumberToObject(o, "steps", (double)res->steps);
    cJSON_AddNumberToObject(o, "rhs_evaluations", (double)res->rhs_evals);
    cJSON_AddNumberToObject(o, "linear_iterations", (double)res->lin_iters);
    cJSON_AddNumberToObject(o, "preconditioner_setups", (double)res->prec_setups);
    cJSON_AddNumberToObject(o, "events", (double)res->events);
    cJSON_AddNumberToObject(o, "restarts", (double)res->reinits);
    cJSON_AddNumberToObject(o, "cpu_seconds", res->cpu_seconds);
    cJSON *ra = cJSON_AddArrayToObject(o, "records");
    for (int r = 0; r < recs->n; r++) {
        const gd_tr_stats *st = &res->stats[r];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "name", recs->r[r].name);
        cJSON_AddStringToObject(e, "unit", recs->r[r].unit);
        cJSON_AddItemToObject(e, "min", gd_cli_json_number(st->min));
        cJSON_AddItemToObject(e, "max", gd_cli_json_number(st->max));
        cJSON_AddItemToObject(e, "mean", gd_cli_json_number(st->mean));
        cJSON_AddItemToObject(e, "rms", gd_cli_json_number(st->rms));
        cJSON_AddItemToObject(e, "peak_to_peak", gd_cli_json_number(st->peak_to_peak));
        cJSON_AddItemToObject(e, "std", gd_cli_json_number(st->std));
        if (spec && spec[r])
            cJSON_AddItemToObject(e, "spectrum", spectrum_json(spec[r], ri->speed));
        cJSON_AddItemToArray(ra, e);
    }
    cJSON *ma = cJSON_AddArrayToObject(o, "meshes");
    for (int i = 0; i < tm->spec.nmeshes; i++) {
        const gd_tr_mesh *tmsh = &tm->meshes[i];
        const gd_tr_contact_stats *c = &res->contacts[i];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "name", gd_model_mesh_name(m, tmsh->mesh));
        cJSON_AddBoolToObject(e, "backlash", tmsh->backlash);
        cJSON_AddNumberToObject(e, "contact_losses", c->contact_losses);
        cJSON_AddNumberToObject(e, "coast_impacts", c->coast_impacts);
        cJSON_AddNumberToObject(e, "drive_impacts", c->drive_impacts);
        cJSON_AddNumberToObject(e, "separated_time_s", c->separated_time);
        cJSON_AddNumberToObject(e, "coast_time_s", c->coast_time);
        cJSON_AddNumberToObject(e, "drive_time_s", c->drive_time);
        cJSON_AddItemToArray(ma, e);
    }
    return o;
}

static void print_text(const gd_system *sys, const gd_transient_model *tm,
                       const gd_cli_records *recs, const gd_transient_result *res,
                       gd_spectrum *const *spec, const run_info *ri, int nfree)
{
    const gd_model *m = sys->model;
    printf("%s: %d DOFs (%d free), speed %g rad/s (%g rpm), t = 0 .. %g s, %s start, %s\n", m->file,
           sys->ndof, nfree, ri->speed, ri->speed * 30 / M_PI, ri->t_end, ri->start, ri->method);
    if (ri->kept >= 0)
        printf("reduced: %d physical DOFs kept, %d interior modes\n", ri->kept, ri->modes);
    if (ri->condense) printf("%s\n", ri->condense);
    /* a given method's header names it only: the achieved accuracy on a line of its own */
    if (res->error_estimate >= 0 && ri->method != res->method_note)
        printf("estimated error %.2g of each record's peak\n", res->error_estimate);
    printf("records from %g s every %g s (%d samples); %ld steps, %ld RHS evaluations, %ld "
           "contact events, %.3g s CPU\n\n",
           ri->from, ri->dt, res->nout, res->steps, res->rhs_evals, res->events, res->cpu_seconds);
    int w = 6;
    for (int r = 0; r < recs->n; r++) {
        int l = (int)strlen(recs->r[r].name);
        if (l > w) w = l;
    }
    printf("%-*s %-6s %13s %13s %13s %13s %13s\n", w, "record", "unit", "min", "max", "mean", "rms",
           "peak_to_peak");
    for (int r = 0; r < recs->n; r++) {
        const gd_tr_stats *st = &res->stats[r];
        char b[5][32];
        printf("%-*s %-6s %s %s %s %s %s\n", w, recs->r[r].name, recs->r[r].unit,
               gd_cli_num(b[0], 32, 13, 6, st->min), gd_cli_num(b[1], 32, 13, 6, st->max),
               gd_cli_num(b[2], 32, 13, 6, st->mean), gd_cli_num(b[3], 32, 13, 6, st->rms),
               gd_cli_num(b[4], 32, 13, 6, st->peak_to_peak));
    }
    if (tm->spec.nmeshes) {
        printf("\n%-20s %8s %14s %8s %8s %14s\n", "mesh", "backlash", "contact_losses", "coast",
               "drive", "separated_s");
        printf("%-20s %8s %14s %8s %8s %14s\n", "", "", "", "impacts", "impacts", "");
        for (int i = 0; i < tm->spec.nmeshes; i++) {
            const gd_tr_contact_stats *c = &res->contacts[i];
            printf("%-20.20s %8s %14d %8d %8d %14.6g\n", gd_model_mesh_name(m, tm->meshes[i].mesh),
                   tm->meshes[i].backlash ? "yes" : "no", c->contact_losses, c->coast_impacts,
                   c->drive_impacts, c->separated_time);
        }
    }
    if (spec) {
        printf("\nspectrum peaks (%s window, df = %g Hz): frequency Hz (order) amplitude\n",
               gd_window_names[ri->window], spec[0] ? spec[0]->df : 0.0);
        for (int r = 0; r < recs->n; r++) {
            if (!spec[r]) continue;
            gd_spectrum_peak pk[NPEAKS];
            int np = gd_spectrum_peaks(spec[r], 1e-3, NPEAKS, pk);
            printf("%-*s", w, recs->r[r].name);
            for (int k = 0; k < np; k++)
                printf("  %.6g (%.4gx) %.4g", pk[k].frequency, order_of(pk[k].frequency, ri->speed),
                       pk[k].amplitude);
            printf("\n");
        }
    }
}

static int write_outputs(const char *dir, const gd_cli_records *recs,
                         const gd_transient_result *res, gd_spectrum *const *spec,
                         const cJSON *summary, double speed, int poincare,
                         const gd_cli_periods *per, const gd_waterfall *wf)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "records.csv", &err);
    if (!f) goto fail;
    fprintf(f, "time_s");
    for (int r = 0; r < recs->n; r++)
        fprintf(f, ",%s", recs->r[r].name);
    fprintf(f, "\n");
    for (int k = 0; k < res->nout; k++) {
        fprintf(f, "%.12g", res->t[k]);
        for (int r = 0; r < recs->n; r++)
            fprintf(f, ",%.10g", res->values[(size_t)r * res->nout + k]);
        fprintf(f, "\n");
    }
    if (gd_outdir_close(&od, f, "records.csv", &err)) goto fail;
    if (spec) {
        f = gd_outdir_open(&od, "spectrum.csv", &err);
        if (!f) goto fail;
        fprintf(f, "frequency_hz,order");
        for (int r = 0; r < recs->n; r++)
            fprintf(f, ",%s", recs->r[r].name);
        fprintf(f, "\n");
        int nb = spec[0] ? spec[0]->n : 0;
        for (int k = 0; k < nb; k++) {
            fprintf(f, "%.10g,%.8g", spec[0]->freq[k], order_of(spec[0]->freq[k], speed));
            for (int r = 0; r < recs->n; r++)
                fprintf(f, ",%.10g", spec[r] ? spec[r]->amplitude[k] : 0.0);
            fprintf(f, "\n");
        }
        if (gd_outdir_close(&od, f, "spectrum.csv", &err)) goto fail;
    }
    if (poincare) {
        f = gd_outdir_open(&od, "poincare.csv", &err);
        if (!f) goto fail;
        fprintf(f, "point,time_s");
        for (int r = 0; r < recs->n; r++)
            fprintf(f, ",%s", recs->r[r].name);
        fprintf(f, "\n");
        for (int k = 0; k < res->nsamples; k++) {
            fprintf(f, "%d,%.12g", k, res->sample_t[k]);
            for (int r = 0; r < recs->n; r++)
                fprintf(f, ",%.10g", res->sample_values[(size_t)r * res->nsamples + k]);
            fprintf(f, "\n");
        }
        if (gd_outdir_close(&od, f, "poincare.csv", &err)) goto fail;
    }
    if (per) {
        f = gd_outdir_open(&od, "periods.csv", &err);
        if (!f) goto fail;
        gd_cli_periods_csv(f, per, recs);
        if (gd_outdir_close(&od, f, "periods.csv", &err)) goto fail;
    }
    if (wf && gd_cli_waterfall_csv(&od, wf, &err)) goto fail;
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

typedef struct cli_opts {
    const char *file; /* the model */
    const char *duration, *revolutions, *speed, *from, *interval, *coupling, *out, *step, *reduce,
        *plot, *condense;
    const char *poincare, *settle, *sweep, *waterfall, *ramp, *table;
    double revs_per_block;
    int points, periods;
    int direction; /* 0 up, 1 --run-down, 2 --both-directions */
    const char *records[64];
    int nrecords;
    gd_cli_sets sets;
    double rtol, unbalance_scale, rho_inf;
    long max_steps;
    int json, quiet, spectrum;
    int rattle, rattle_batches; /* --rattle, --rattle-batches */
    int no_estimate;            /* --no-estimate */
    const char *rattle_extend;  /* --rattle-extend */
    const char *shift;          /* --shift FROM:TO@T */
    double rattle_target;       /* --rattle-precision */
    gd_tr_method method;
    gd_tr_init init;
    gd_window window;
} cli_opts;

/* --rtol R: a number in (0, 0.1). */
static int parse_rtol(const char *cmd, const char *text, void *field)
{
    if (parse_positive("--rtol", text, field)) return GD_EXIT_INPUT;
    if (*(double *)field >= 0.1) return gd_cli_usage_error(cmd, "--rtol: give a value below 0.1");
    return 0;
}

/* --method M: auto, bdf, adams or galpha (gd_tr_method). */
static int parse_method(const char *cmd, const char *text, void *field)
{
    static const char *const names[] = {"auto", "bdf", "adams", "galpha"};
    static const gd_tr_method methods[] = {GD_TR_AUTO, GD_TR_BDF, GD_TR_ADAMS, GD_TR_GEN_ALPHA};
    for (int k = 0; k < 4; k++)
        if (!strcmp(text, names[k])) {
            *(gd_tr_method *)field = methods[k];
            return 0;
        }
    return gd_cli_usage_error(cmd, "--method: '%s' is not auto, bdf, adams or galpha", text);
}

/* A run's error with the library's option names as this command's options (issue 38
 * L3: "t_end: 1e+30 s ..." for --duration). */
static gd_error *as_options(gd_error *err)
{
    static const char *const OPTION_OF[][2] = {
        {"t_end", "--duration"}, {"max_steps", "--max-steps"}, {"step", "--step"}};
    for (size_t k = 0; k < sizeof OPTION_OF / sizeof OPTION_OF[0]; k++)
        if (!strcmp(err->field, OPTION_OF[k][0]))
            snprintf(err->field, sizeof err->field, "%s", OPTION_OF[k][1]);
    return err;
}

/* --max-steps N: a whole number from 1 to 1e15 (written 5e7 or 50000000). */
static int parse_max_steps(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v >= 1 && v <= 1e15) || v != floor(v))
        return gd_cli_usage_error(cmd, "--max-steps: '%s' is not a whole number from 1 to 1e15",
                                  text);
    *(long *)field = (long)v;
    return 0;
}

/* --rho-inf R: a number from 0 to 1. */
static int parse_rho_inf(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v >= 0 && v <= 1))
        return gd_cli_usage_error(cmd, "--rho-inf: '%s' is not a number from 0 to 1", text);
    *(double *)field = v;
    return 0;
}

/* --unbalance-scale F: a finite number >= 0. */
static int parse_unbalance_scale(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !isfinite(v) || v < 0)
        return gd_cli_usage_error(cmd, "--unbalance-scale: '%s' is not a number >= 0", text);
    *(double *)field = v;
    return 0;
}

/* --revs-per-block N: revolutions from 1 to 1e5 (not only whole). */
static int parse_revs_per_block(const char *cmd, const char *text, void *field)
{
    if (parse_positive("--revs-per-block", text, field)) return GD_EXIT_INPUT;
    double v = *(double *)field;
    if (v < 1 || v > 1e5)
        return gd_cli_usage_error(cmd, "--revs-per-block: give 1 to 1e5 revolutions");
    return 0;
}

/* --rattle-precision P: a number in (0, 1]. */
static int parse_rattle_precision(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v > 0 && v <= 1))
        return gd_cli_usage_error(cmd, "--rattle-precision: '%s' is not a number in (0, 1]", text);
    *(double *)field = v;
    return 0;
}

#define F(m) offsetof(cli_opts, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("duration", GD_CLI_STRING, F(duration), "T",
               "simulated time, with units (e.g. 12ms); > 0"),
    GD_CLI_ROW("revolutions", GD_CLI_STRING, F(revolutions), "N",
               "or N revolutions of the reference shaft: T = 2 pi N / speed"),
    GD_CLI_ROW("speed", GD_CLI_STRING, F(speed), "S", "reference speed (e.g. 10000rpm)",
               .def = "the model's"),
    GD_CLI_ROW("record", GD_CLI_LIST, F(records), "WHAT",
               "what to record, comma-separated, repeatable (WHAT below); default: force and "
               "contact state of the nonlinear meshes, fx and fy of the dampers, the first "
               "record of each law",
               .aux = F(nrecords), .hi = 64),
    GD_CLI_ROW("from", GD_CLI_STRING, F(from), "T", "records and statistics from this time",
               .def = "last half"),
    GD_CLI_ROW("output-interval", GD_CLI_STRING, F(interval), "T",
               "sampling of the records (default: 2000 samples, at least 32 per revolution); "
               "frequencies above half the sampling rate fold back into a spectrum: sample fast "
               "enough"),
    GD_CLI_ROW("rtol", GD_CLI_CALL, F(rtol), "R", "relative tolerance", .def = "1e-6",
               .call = parse_rtol),
    GD_CLI_ROW("no-estimate", GD_CLI_FLAG, F(no_estimate), NULL,
               "bdf and adams: skip the error estimate (a second run at rtol / 10, about 1.5x "
               "the run's cost, docs/transient.md); --rattle never estimates (its metrics carry "
               "their 95 % intervals)"),
    GD_CLI_ROW("method", GD_CLI_CALL, F(method), "M",
               "auto (default): a linear time-invariant model (no law, no backlash, TVMS or STE, "
               "no cam) by its exact harmonic response plus the free motion at a step halved "
               "until two steps agree to --rtol; any other model by bdf; the header says which. "
               "bdf or adams: CVODE, error-controlled by --rtol, contact changes located; "
               "galpha: fixed-step generalized-alpha (Chung-Hulbert; Newmark's average "
               "acceleration at --rho-inf 1), contact changes resolved to the step",
               .call = parse_method),
    GD_CLI_ROW("step", GD_CLI_STRING, F(step), "T", "galpha: largest time step",
               .def = "output interval / 10"),
    GD_CLI_ROW("rho-inf", GD_CLI_CALL, F(rho_inf), "R",
               "galpha: spectral radius at infinite step, 0..1: below 1 damps the unresolved "
               "high modes",
               .def = "0.9", .call = parse_rho_inf),
    GD_CLI_ROW("max-steps", GD_CLI_CALL, F(max_steps), "N",
               "step limit: a run that needs more (galpha: duration / step; bdf, adams: the "
               "fastest shaft's revolutions) is refused before it starts",
               .def = "50 million", .call = parse_max_steps),
    GD_CLI_ROW("reduce", GD_CLI_STRING, F(reduce), "F",
               "modal reduction (Craig-Bampton): DOFs with laws stay physical, the rest become "
               "their modes below F (e.g. 5kHz) plus static constraint modes; any --method runs "
               "the reduced model"),
    GD_CLI_ROW("condense", GD_CLI_STRING, F(condense), "C",
               "integrate the structure condensed onto the DOFs the laws act on: its modes up "
               "to C (a frequency, e.g. 8kHz), 'auto' (5 x the highest excitation frequency and "
               "2.5 x the highest mesh contact frequency) or 'all' (every mode: exact), the rest "
               "as their static correction; dense solves on the small state (bdf or adams, "
               "started at rest, no prescribed DOF). Default: auto on a nonlinear model of 100 "
               "DOFs or more with laws on at most 1 in 4 of them, else off (the full model)"),
    GD_CLI_ROW("start", GD_CLI_CHOICE, F(init), "S",
               "rest: q = q' = 0 (nominal motion), or static: static equilibrium under the loads "
               "at t = 0",
               .def = "rest", .word = "rest|static"),
    GD_CLI_ROW("spectrum", GD_CLI_FLAG, F(spectrum), NULL,
               "amplitude spectrum (FFT, mean removed) of every record over the recorded part: "
               "leading peaks with their order of the reference speed; with --out, "
               "DIR/spectrum.csv"),
    GD_CLI_ROW("window", GD_CLI_CHOICE, F(window), "W", "hann or rect", .def = "hann",
               .word = "hann|rect"),
    GD_CLI_ROW("unbalance-scale", GD_CLI_CALL, F(unbalance_scale), "F",
               "multiplies every unbalance of the model (F >= 0)", .call = parse_unbalance_scale),
    GD_CLI_ROW_MODEL(cli_opts, coupling, sets),
    GD_CLI_ROW_JSON(cli_opts, json),
    GD_CLI_ROW_OUT(cli_opts, out,
                   "DIR/records.csv (time and one column per record), DIR/summary.json, "
                   "DIR/spectrum.csv with --spectrum"),
    GD_CLI_ROW("quiet", GD_CLI_FLAG, F(quiet), NULL,
               "no progress bar (it is shown on stderr only on a terminal)", .letter = 'q'),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "time histories, spectra, orbits, contact states: FILE.svg or FILE.html "
               "(interactive, self-contained; docs/plots.md); with --sweep-speeds or a speed "
               "profile, the run-up waterfall (--waterfall)"),
    GD_CLI_ROW("poincare", GD_CLI_STRING, F(poincare), "SRC",
               "stroboscopic (Poincare) samples of the records once per revolution of shaft SRC "
               "or per tooth-mesh cycle of mesh SRC (shaft:NAME or mesh:NAME when a name is "
               "both), at the exact times k T from --settle on: the points, their period "
               "(period-1, period-2, ... or many) and, with --out, DIR/poincare.csv"),
    GD_CLI_ROW("settle", GD_CLI_STRING, F(settle), "S",
               "settling time before the Poincare samples: a time (20ms) or revolutions of the "
               "reference shaft (200rev); default: --from for one run, 100rev for a sweep or "
               "--periods"),
    GD_CLI_ROW("sweep-speeds", GD_CLI_STRING, F(sweep), "R",
               "bifurcation diagram: FROM:TO:COUNT speeds (e.g. 500:3000rpm:26); each run starts "
               "from the previous speed's end state, settles, then takes --points Poincare "
               "samples (needs --poincare; replaces --duration, --revolutions, --speed); with "
               "--out, DIR/sweep.csv, DIR/poincare.csv, DIR/summary.json"),
    GD_CLI_ROW("points", GD_CLI_INT, F(points), "N", "Poincare points per speed in a sweep",
               .def = "64", .lo = 2, .hi = 1000000),
    GD_CLI_ROW("run-down", GD_CLI_VALUE, F(direction), NULL, "sweep from TO down to FROM",
               .ival = 1, .excludes = "both-directions"),
    GD_CLI_ROW("both-directions", GD_CLI_VALUE, F(direction), NULL, "sweep up, then down again",
               .ival = 2, .excludes = "run-down"),
    GD_CLI_ROW("waterfall", GD_CLI_STRING, F(waterfall), "REC",
               "the run-up waterfall of record REC. In a sweep: its spectrum over each speed's "
               "settled part, a stepped (quasi-steady) run-up (docs/transient.md). With a speed "
               "profile: order tracking of REC (resampled on the reference shaft's angle), one "
               "order spectrum per block of revolutions at its mean speed. Both: the order cuts "
               "(1x of each shaft, mesh orders) in the table and --json, with --out "
               "DIR/waterfall.csv and DIR/order_cuts.csv; --plot FILE draws it (cascade, colour "
               "map, order cuts; the first record without --waterfall)"),
    GD_CLI_ROW("periods", GD_CLI_INT, F(periods), "N",
               "responses with no stable periodic orbit (rattle): run --settle (rounded up to "
               "whole periods; default 100rev) plus N periods T of the excitations' fundamental, "
               "then give per record the median and 5-95 % band over the periods of each "
               "period's peak-to-peak, mean and RMS, and the Poincare verdict on the N + 1 "
               "once-per-period samples (periodic, period-N, quasi-periodic or irregular); "
               "records every T / 256 (finer for high excitation orders) unless "
               "--output-interval; with --out, DIR/periods.csv and DIR/poincare.csv",
               .lo = 1, .hi = 1000000),
    GD_CLI_ROW("speed-ramp", GD_CLI_STRING, F(ramp), "FROM:TO",
               "run-up (or run-down): the reference speed goes linearly from FROM to TO over "
               "--duration (e.g. 0:6000rpm); every shaft follows through its ratio; gyroscopic, "
               "unbalance (with the angular acceleration term), mesh, cam and law forces at the "
               "shafts' angles and speeds; records from 0 s; speed-table bearings held at "
               "--speed (default: the ramp's mid speed)"),
    GD_CLI_ROW("speed-table", GD_CLI_STRING, F(table), "FILE",
               "or the speed from rows 'time, speed' (linear between rows, held after the last; "
               "a header line may name the unit: rpm, rad/s (default), Hz); --duration defaults "
               "to the last time"),
    GD_CLI_ROW("rattle", GD_CLI_FLAG, F(rattle), NULL,
               "rattle metrics of every backlash mesh over the recorded part (docs/rattle.md): "
               "separated fraction, impacts per second on the drive and coast flank, impact-speed "
               "histograms and the impact-energy intensity, each with its 95 % confidence "
               "half-width from batch means, and the window that would reach "
               "--rattle-precision"),
    GD_CLI_ROW("rattle-batches", GD_CLI_INT, F(rattle_batches), "N",
               "--rattle: batches of the batch means", .def = "10", .lo = 2, .hi = 1000),
    GD_CLI_ROW("rattle-precision", GD_CLI_CALL, F(rattle_target), "P",
               "--rattle: the relative half-width wanted of the metrics", .def = "0.1",
               .call = parse_rattle_precision),
    GD_CLI_ROW("rattle-extend", GD_CLI_STRING, F(rattle_extend), "T",
               "--rattle: while a metric's relative half-width exceeds --rattle-precision, run "
               "again with the window it needs (times 1.2), up to a run of T (e.g. 60s)"),
    GD_CLI_ROW("shift", GD_CLI_STRING, F(shift), "A:B@T",
               "shift from gear A to gear B at time T (e.g. 3:4@0.5): the old gear released, the "
               "new one's synchroniser cone torque until the speeds meet, then locked "
               "(docs/rattle.md; the model's `shift:` key)"),
    GD_CLI_ROW("revs-per-block", GD_CLI_CALL, F(revs_per_block), "N",
               "with a speed profile: revolutions per order spectrum (bins 1/N order)", .def = "16",
               .call = parse_revs_per_block),
    {0}};
static const gd_cli_command TRANSIENT = {
    .name = CMD,
    .args = "MODEL.yaml",
    .opts = OPTS,
    .more = "       geardyn transient MODEL.yaml --periods N [--settle T|Nrev] [--speed S] ...\n"
            "       geardyn transient MODEL.yaml --speed-ramp FROM:TO --duration T\n"
            "                         [--waterfall REC] [--revs-per-block N] [--plot F] ...\n",
    .about = "Integrates the equations of motion at a constant reference speed with the model's\n"
             "nonlinear and time-varying laws (mesh TVMS, transmission error, backlash, squeeze\n"
             "film dampers, loads, prescribed motions, cam torques, unbalances), then prints\n"
             "statistics of the records over the steady part and the contact history of the\n"
             "meshes. Give --duration T or --revolutions N (one run), --periods N, "
             "--sweep-speeds\nor a speed profile (--speed-ramp, --speed-table).\n",
    .footer = "--record WHAT, comma-separated:\n"
              "  NODE.DOF[:disp|vel|angle|speed]  (disp: perturbation q; angle, speed: total,\n"
              "                                   nominal motion included)\n"
              "  ratio:NODE_A/NODE_B              angular speed of A over B (rz)\n"
              "  mesh:NAME[:force|state|deflection|stiffness]  (NAME or *)\n"
              "  sfd:BEARING[:fx|fy|ecc]          damper force, e/c (BEARING or *)\n"
              "  law:NAME[:RECORD]                a record of a law of `laws:` (NAME or *)\n"};

static int parse_args(int argc, char **argv, cli_opts *o)
{
    memset(o, 0, sizeof *o);
    o->rtol = 1e-6;
    o->unbalance_scale = 1.0;
    o->rho_inf = 0.9;
    o->method = GD_TR_AUTO;
    o->init = GD_TR_INIT_REST;
    o->window = GD_WINDOW_HANN;
    o->rattle_batches = 10;
    o->rattle_target = 0.1;
    int rc = gd_cli_parse(&TRANSIENT, argc, argv, o, &o->file);
    if (rc) return rc;
    if (o->rattle_extend && !o->rattle)
        return gd_cli_usage_error(CMD, "--rattle-extend needs --rattle");
    if (o->rattle_extend && (o->periods || o->poincare))
        return gd_cli_usage_error(CMD, "--rattle-extend runs again with a longer window: not with "
                                       "--periods or --poincare");
    if (o->rattle && (o->sweep || o->ramp || o->table))
        return gd_cli_usage_error(CMD, "--rattle is for one run at a constant speed, not with %s",
                                  o->sweep ? "--sweep-speeds" : "a speed profile");
    if (o->ramp || o->table) {
        const char *clash = o->ramp && o->table ? "--speed-table with --speed-ramp"
                            : o->sweep          ? "--sweep-speeds"
                            : o->periods        ? "--periods"
                            : o->poincare       ? "--poincare"
                            : o->revolutions    ? "--revolutions"
                            : o->reduce         ? "--reduce"
                            : o->condense       ? "--condense"
                            : o->spectrum       ? "--spectrum (use --waterfall)"
                            : o->direction      ? "--run-down/--both-directions"
                                                : NULL;
        if (clash)
            return gd_cli_usage_error(CMD,
                                      "%s does not apply to a speed profile (one run through "
                                      "the speeds; a reduced model keeps its modes at one speed)",
                                      clash);
        if (o->ramp && !o->duration)
            return gd_cli_usage_error(CMD, "--speed-ramp needs --duration T (the ramp's length)");
        return 0;
    }
    if (o->revs_per_block > 0)
        return gd_cli_usage_error(CMD, "--revs-per-block applies to --speed-ramp/--speed-table");
    if (o->periods) {
        const char *clash = o->sweep         ? "--sweep-speeds"
                            : o->poincare    ? "--poincare"
                            : o->duration    ? "--duration"
                            : o->revolutions ? "--revolutions"
                            : o->from        ? "--from"
                                             : NULL;
        if (clash)
            return gd_cli_usage_error(CMD,
                                      "%s does not apply to --periods (the run lasts --settle "
                                      "plus N periods; the section is once per period)",
                                      clash);
    }
    if (o->sweep) {
        if (!o->poincare)
            return gd_cli_usage_error(CMD, "--sweep-speeds needs --poincare SHAFT|MESH (what to "
                                           "sample at each speed)");
        const char *clash = o->duration                    ? "--duration"
                            : o->revolutions               ? "--revolutions"
                            : o->speed                     ? "--speed"
                            : o->from                      ? "--from"
                            : o->interval                  ? "--output-interval"
                            : o->spectrum                  ? "--spectrum"
                            : o->reduce                    ? "--reduce"
                            : o->condense                  ? "--condense"
                            : o->step                      ? "--step"
                            : o->method == GD_TR_GEN_ALPHA ? "--method galpha"
                                                           : NULL;
        if (clash)
            return gd_cli_usage_error(
                CMD,
                "%s does not apply to --sweep-speeds (each run lasts --settle "
                "plus --points Poincare periods)",
                clash);
        if ((o->waterfall || o->plot) && o->direction == 2)
            return gd_cli_usage_error(CMD,
                                      "%s: give one direction (the run-up, or --run-down), "
                                      "not --both-directions",
                                      o->waterfall ? "--waterfall" : "--plot");
        return 0;
    }
    if (o->waterfall) return gd_cli_usage_error(CMD, "--waterfall applies to --sweep-speeds only");
    if (o->points || o->direction)
        return gd_cli_usage_error(CMD, "%s applies to --sweep-speeds only",
                                  o->points           ? "--points"
                                  : o->direction == 1 ? "--run-down"
                                                      : "--both-directions");
    if (o->settle && !o->poincare && !o->periods)
        return gd_cli_usage_error(CMD, "--settle applies to --poincare and --periods only");
    if (o->periods) return 0;
    if (o->duration && o->revolutions)
        return gd_cli_usage_error(CMD, "--duration and --revolutions exclude each other");
    if (!o->duration && !o->revolutions)
        return gd_cli_usage_error(CMD, "give --duration T or --revolutions N");
    return 0;
}

/* The highest tooth-mesh order of the model (tooth-mesh frequency / reference speed) and
 * its mesh; 0 when no mesh has tooth counts. */
static double top_mesh_order(const gd_model *m, int *which)
{
    double top = 0;
    *which = -1;
    for (int i = 0; i < m->nmeshes; i++) {
        const gd_mesh *g = &m->meshes[i];
        if (g->teeth[0] <= 0) continue;
        double order = g->teeth[0] * fabs(m->shafts[m->nodes[g->driver].shaft].speed_ratio);
        if (order > top) {
            top = order;
            *which = i;
        }
    }
    /* a planetary set: Z_s times the sun's speed relative to the carrier (its first sun
       mesh named) */
    for (int k = 0, first = m->nmeshes; k < m->nplanetary;
         first += 2 * m->planetary[k++].nplanets) {
        const gd_planetary *g = &m->planetary[k];
        if (g->teeth[0] <= 0) continue;
        const gd_shaft *sh = m->shafts;
        double order = g->teeth[0] *
                       fabs(sh[m->nodes[g->member[GD_PLANETARY_SUN].node].shaft].speed_ratio -
                            sh[m->nodes[g->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio);
        if (order > top) {
            top = order;
            *which = first;
        }
    }
    return top;
}

/* Samples per tooth-mesh cycle of the default output interval: the records are samples,
 * not filtered, so a peak between two samples is missed; 20 a cycle keep a sinusoid's
 * peak-to-peak within 1 - cos(pi/20) = 1.2 % (at 1.3 a cycle the peak-to-peak mesh force
 * of a 5-speed gearbox at 5700 rpm came out 8 % off: issue 35). */
#define SAMPLES_PER_MESH_CYCLE 20.0

/* Times from the options: t_end, record_from, output interval. */
static int resolve_times(const cli_opts *o, const gd_model *m, double speed, run_info *ri)
{
    if (o->duration) {
        if (parse_time("--duration", o->duration, &ri->t_end)) return GD_EXIT_INPUT;
        if (ri->t_end <= 0)
            return gd_cli_usage_error(CMD, "--duration: give a time > 0 (got %s)", o->duration);
    } else {
        double n = 0;
        if (parse_positive("--revolutions", o->revolutions, &n)) return GD_EXIT_INPUT;
        if (!(speed > 0))
            return gd_cli_usage_error(CMD,
                                      "--revolutions needs a reference speed > 0: give --speed "
                                      "or 'speed:' in the model, or use --duration");
        ri->t_end = 2 * M_PI * n / speed;
    }
    ri->from = 0.5 * ri->t_end;
    if (o->from) {
        if (parse_time("--from", o->from, &ri->from)) return GD_EXIT_INPUT;
        if (ri->from < 0 || ri->from >= ri->t_end)
            return gd_cli_usage_error(CMD, "--from: give a time in [0, %g s)", ri->t_end);
    }
    /* 2000 samples, and at least 32 per revolution of the reference shaft (the records
     * are samples, not filtered: a spectrum shows frequencies above the Nyquist
     * frequency folded back) */
    ri->dt = (ri->t_end - ri->from) / 2000.0;
    if (speed > 0 && 2 * M_PI / speed / 32 < ri->dt)
        ri->dt = fmax(2 * M_PI / speed / 32, (ri->t_end - ri->from) / 2e6);
    int mesh = -1;
    double order = speed > 0 ? top_mesh_order(m, &mesh) : 0;
    double mesh_period = order > 0 ? 2 * M_PI / (speed * order) : 0;
    if (mesh_period > 0 && mesh_period / SAMPLES_PER_MESH_CYCLE < ri->dt)
        ri->dt = fmax(mesh_period / SAMPLES_PER_MESH_CYCLE, (ri->t_end - ri->from) / 2e6);
    if (o->interval) {
        if (parse_time("--output-interval", o->interval, &ri->dt)) return GD_EXIT_INPUT;
        if (ri->dt <= 0) return gd_cli_usage_error(CMD, "--output-interval: give a time > 0");
        if ((ri->t_end - ri->from) / ri->dt > 1e7)
            return gd_cli_usage_error(CMD,
                                      "--output-interval: more than 1e7 samples; give a longer "
                                      "interval or a later --from");
    }
    /* fewer than 4 samples a tooth-mesh cycle (given, or the 2e6-sample cap): said */
    if (mesh_period > 0 && ri->dt > mesh_period / 4 && !o->quiet)
        fprintf(stderr,
                "geardyn transient: note: the output interval %.3g s gives %.2g samples per "
                "tooth-mesh cycle of mesh '%s' (%.4g Hz): peaks and peak-to-peak of mesh "
                "quantities are not resolved; give --output-interval %.2g s or shorter\n",
                ri->dt, mesh_period / ri->dt, gd_model_mesh_name(m, mesh), 1.0 / mesh_period,
                mesh_period / SAMPLES_PER_MESH_CYCLE);
    return 0;
}

/* The Poincare sample times of one run: from --settle (default --from) to the end. */
static int poincare_times(const cli_opts *o, const gd_cli_poincare *pc, const run_info *ri,
                          double **times, int *n)
{
    *times = NULL;
    *n = 0;
    if (!(ri->speed > 0))
        return gd_cli_usage_error(CMD, "--poincare needs a reference speed > 0 (--speed or "
                                       "'speed:' in the model): the period is undefined at 0");
    double settle = ri->from, st = 0, revs = 0;
    if (o->settle) {
        if (parse_settle(o->settle, &st, &revs)) return GD_EXIT_INPUT;
        settle = revs > 0 ? revs * 2 * M_PI / ri->speed : st;
    }
    if (settle >= ri->t_end)
        return gd_cli_usage_error(CMD, "--settle: %g s is not before the end of the run (%g s)",
                                  settle, ri->t_end);
    *n = gd_cli_poincare_times(pc, ri->speed, settle, ri->t_end, times);
    if (*n < 2) {
        free(*times);
        *times = NULL;
        return gd_cli_usage_error(CMD,
                                  "--poincare: %d sample(s) between --settle (%g s) and the end "
                                  "(%g s), one every %g s: run longer or settle less",
                                  *n, settle, ri->t_end, pc->angle / ri->speed);
    }
    return 0;
}

static void print_poincare(const gd_cli_poincare *pc, const gd_cli_records *recs,
                           const gd_transient_result *res, double speed, int period, int distinct)
{
    char cls[32];
    gd_cli_poincare_class_name(period, cls, sizeof cls);
    printf("\nPoincare section (%s, every %g s): %d points from %g s, %s, %d distinct (same "
           "within %g of each record's peak-to-peak)\n",
           pc->name, pc->angle / speed, res->nsamples, res->sample_t[0], cls, distinct,
           GD_CLI_POINCARE_TOL);
    int show = period > 0 ? period : (res->nsamples < 8 ? res->nsamples : 8);
    for (int r = 0; r < recs->n; r++) {
        printf("  %s:", recs->r[r].name);
        for (int k = 0; k < show; k++)
            printf(" %.6g",
                   res->sample_values[(size_t)r * res->nsamples + res->nsamples - show + k]);
        printf("%s\n", period > 0 ? "" : " ...");
    }
}

/* --periods: the run's times from the excitations' period (transient_periods.c). */
static int periods_setup(const cli_opts *o, const gd_system *s, const gd_transient_model *tm,
                         run_info *ri, gd_cli_periods *per, double **times, int *n)
{
    if (!(ri->speed > 0))
        return gd_cli_usage_error(CMD, "--periods needs a reference speed > 0 (--speed or "
                                       "'speed:' in the model): the period is undefined at 0");
    double st = 0, revs = 0, interval = 0;
    if (o->settle && parse_settle(o->settle, &st, &revs)) return GD_EXIT_INPUT;
    if (o->interval) {
        if (parse_time("--output-interval", o->interval, &interval)) return GD_EXIT_INPUT;
        if (!(interval > 0)) return gd_cli_usage_error(CMD, "--output-interval: give a time > 0");
    }
    int rc = gd_cli_periods_plan(CMD, s, &tm->spec, ri->speed, (int)o->periods, st, revs, interval,
                                 per, times);
    if (rc) return rc;
    ri->t_end = per->t_end;
    ri->from = per->settle;
    ri->dt = per->dt;
    *n = per->count + 1;
    return 0;
}

/* --sweep-speeds: the bifurcation diagram (transient_sweep.c). */
static int sweep(const cli_opts *o, gd_model *m, gd_system *s)
{
    gd_cli_sweep sw;
    memset(&sw, 0, sizeof sw);
    double *speeds = NULL;
    gd_transient_model *tm = NULL;
    gd_cli_records recs = {0, 0, NULL};
    gd_cli_poincare pc;
    gd_error err;
    int rc = gd_cli_parse_range(CMD, "--sweep-speeds", o->sweep, &speeds, &sw.nspeeds);
    if (rc) return rc;
    if (!(speeds[0] > 0)) {
        rc = gd_cli_usage_error(CMD, "--sweep-speeds: FROM must be > 0 (the Poincare period is "
                                     "undefined at speed 0)");
        goto done;
    }
    sw.speeds = speeds;
    sw.settle_revs = 100;
    if (o->settle && (rc = parse_settle(o->settle, &sw.settle_time, &sw.settle_revs))) goto done;
    sw.points = o->points > 0 ? (int)o->points : 64;
    sw.direction = o->direction;
    gd_transient_options_init(&sw.base);
    sw.base.rtol = o->rtol;
    sw.base.method = o->method;
    sw.base.init = o->init;
    sw.json = o->json;
    sw.quiet = o->quiet;
    sw.out = o->out;
    sw.plot = o->plot;
    sw.waterfall = -1;
    if ((rc = gd_cli_poincare_parse(CMD, m, o->poincare, &pc))) goto done;
    for (int i = 0; i < m->nunbalances; i++)
        m->unbalances[i].amount *= o->unbalance_scale;
    gd_error_clear(&err);
    if (gd_transient_model_build(s, &tm, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    for (int k = 0; k < o->nrecords; k++)
        if ((rc = gd_cli_parse_records(CMD, s, tm, o->records[k], &recs))) goto done;
    if (!o->nrecords && (rc = gd_cli_default_records(s, tm, &recs))) goto done;
    if ((o->waterfall || o->plot) && (rc = gd_cli_waterfall_record(CMD, s, tm, o->waterfall, &recs,
                                                                   &sw.waterfall, &sw.max_order)))
        goto done;
    rc = gd_cli_transient_sweep(s, tm, &recs, &pc, &sw);
done:
    free(speeds);
    gd_cli_records_free(&recs);
    gd_transient_model_free(tm);
    return rc;
}

/* --speed-ramp / --speed-table: one run through the speeds (transient_profile.c), with
 * --waterfall REC its order-tracked waterfall. */
static int runup(const cli_opts *o, gd_model *m, gd_system *s, run_info *ri)
{
    gd_cli_profile cp;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    gd_waterfall *wf = NULL;
    gd_cli_records recs = {0, 0, NULL};
    cJSON *summary = NULL;
    gd_tr_record *rr = NULL;
    gd_error err;
    gd_error_clear(&err);
    int rc, wi = -1;
    double max_order = 1;
    memset(&cp, 0, sizeof cp);
    if (o->duration) {
        if (parse_time("--duration", o->duration, &ri->t_end)) return GD_EXIT_INPUT;
        if (!(ri->t_end > 0))
            return gd_cli_usage_error(CMD, "--duration: give a time > 0 (got %s)", o->duration);
    }
    if (o->table) {
        if ((rc = gd_cli_speed_table(CMD, o->table, &cp))) return rc;
        if (!o->duration) ri->t_end = cp.t[cp.p.n - 1];
        if (!(ri->t_end > 0)) {
            rc = gd_cli_usage_error(CMD, "%s: the last time is not > 0: give --duration", o->table);
            goto done;
        }
    } else if ((rc = gd_cli_speed_ramp(CMD, o->ramp, ri->t_end, &cp))) {
        return rc;
    }
    /* the reference speed (speed-table bearings, the matrices' W G) */
    double sign =
        (cp.p.kind == GD_SPEED_RAMP ? cp.p.from + cp.p.to : cp.w[cp.p.n - 1]) < 0 ? -1 : 1;
    if (!o->speed) ri->speed = sign * 0.5 * (cp.wmin + cp.wmax);
    for (int i = 0; i < m->nunbalances; i++)
        m->unbalances[i].amount *= o->unbalance_scale;
    if (gd_transient_model_build(s, &tm, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    for (int k = 0; k < o->nrecords; k++)
        if ((rc = gd_cli_parse_records(CMD, s, tm, o->records[k], &recs))) goto done;
    if (!o->nrecords && (rc = gd_cli_default_records(s, tm, &recs))) goto done;
    if (o->waterfall &&
        (rc = gd_cli_waterfall_record(CMD, s, tm, o->waterfall, &recs, &wi, &max_order)))
        goto done;
    const int spr = gd_cli_track_samples(max_order);
    ri->from = 0;
    if (o->from) {
        if (parse_time("--from", o->from, &ri->from)) {
            rc = GD_EXIT_INPUT;
            goto done;
        }
        if (ri->from < 0 || ri->from >= ri->t_end) {
            rc = gd_cli_usage_error(CMD, "--from: give a time in [0, %g s)", ri->t_end);
            goto done;
        }
    }
    /* 2000 samples, at least 32 per revolution at the top speed; for the order tracking
     * two per resampled point (linear interpolation on the angle) */
    ri->dt = (ri->t_end - ri->from) / 2000.0;
    if (cp.wmax > 0) ri->dt = fmin(ri->dt, 2 * M_PI / cp.wmax / (wi >= 0 ? 2.0 * spr : 32.0));
    if (o->interval) {
        if (parse_time("--output-interval", o->interval, &ri->dt)) {
            rc = GD_EXIT_INPUT;
            goto done;
        }
        if (!(ri->dt > 0)) {
            rc = gd_cli_usage_error(CMD, "--output-interval: give a time > 0");
            goto done;
        }
    }
    if ((ri->t_end - ri->from) / ri->dt > 1e7) {
        rc = gd_cli_usage_error(CMD,
                                "%.3g samples: over 1e7; give a longer --output-interval, a later "
                                "--from or a shorter run",
                                (ri->t_end - ri->from) / ri->dt);
        goto done;
    }
    if (gd_transient_new(s, &tm->spec, ri->speed, &tr, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    gd_transient_options opt;
    gd_transient_options_init(&opt);
    opt.t_end = ri->t_end;
    opt.record_from = ri->from;
    opt.output_interval = ri->dt;
    opt.rtol = o->rtol;
    opt.method = o->method;
    opt.error_estimate = !o->no_estimate;
    opt.init = o->init;
    opt.rho_inf = o->rho_inf;
    opt.max_steps = o->max_steps;
    opt.profile = &cp.p;
    if (o->step && (parse_time("--step", o->step, &opt.step) || !(opt.step > 0))) {
        rc = gd_cli_usage_error(CMD, "--step: give a time > 0");
        goto done;
    }
    progress pg = {-1, 0};
    if (!o->quiet && isatty(2)) {
        opt.progress = progress_cb;
        opt.progress_data = &pg;
    }
    rr = malloc((size_t)(recs.n > 0 ? recs.n : 1) * sizeof *rr);
    if (!rr) {
        rc = GD_EXIT_FAIL;
        goto done;
    }
    for (int r = 0; r < recs.n; r++)
        rr[r] = recs.r[r].rec;
    gd_status st = gd_transient_run(tr, &opt, rr, recs.n, &res, &err);
    if (pg.drawn) fprintf(stderr, "\r%60s\r", "");
    if (st) {
        rc = gd_cli_report(as_options(&err));
        goto done;
    }
    if (wi >= 0 && (rc = gd_cli_runup_waterfall(
                        CMD, s, &cp, res->t, res->values + (size_t)wi * res->nout, res->nout,
                        o->revs_per_block > 0 ? o->revs_per_block : 16, spr, &wf)))
        goto done;
    if (o->plot) {
        gd_plot *p = NULL;
        gd_status pst = wf ? gd_plot_waterfall(s, wf, &recs.r[wi].rec, NULL, &p, &err)
                           : gd_plot_transient(s, res, &p, &err);
        if ((rc = gd_cli_plot_finish(pst, p, &err, o->plot))) goto done;
    }
    int nfree = gd_transient_nstates(tr) / 2;
    if (o->method == GD_TR_AUTO) ri->method = res->method_note;
    summary = summary_json(s, tm, &recs, res, NULL, ri, nfree);
    {
        cJSON *pj = cJSON_CreateObject();
        cJSON_AddStringToObject(pj, "kind", cp.p.kind == GD_SPEED_RAMP ? "ramp" : "table");
        if (cp.p.kind == GD_SPEED_RAMP) {
            cJSON_AddNumberToObject(pj, "from_rad_s", cp.p.from);
            cJSON_AddNumberToObject(pj, "to_rad_s", cp.p.to);
            cJSON_AddNumberToObject(pj, "acceleration_rad_s2",
                                    (cp.p.to - cp.p.from) / (cp.p.t1 - cp.p.t0));
        } else {
            cJSON_AddStringToObject(pj, "file", o->table);
            cJSON_AddNumberToObject(pj, "rows", cp.p.n);
        }
        cJSON_AddItemToObject(summary, "speed_profile", pj);
    }
    if (wf) {
        cJSON *wj = gd_cli_waterfall_json(&recs.r[wi], wf);
        cJSON_AddNumberToObject(wj, "revs_per_block", wf->revs_per_block);
        cJSON_AddNumberToObject(wj, "samples_per_rev", spr);
        cJSON_AddItemToObject(summary, "waterfall", wj);
    }
    if (o->out && (rc = write_outputs(o->out, &recs, res, NULL, summary, ri->speed, 0, NULL, wf)))
        goto done;
    if (o->json) {
        gd_cli_print_json(stdout, summary);
    } else {
        if (cp.p.kind == GD_SPEED_RAMP)
            printf("speed ramp %g -> %g rpm over 0 .. %g s (%g rpm/s); the header's speed is "
                   "the reference for speed-table bearings\n",
                   cp.p.from * 30 / M_PI, cp.p.to * 30 / M_PI, ri->t_end,
                   (cp.p.to - cp.p.from) * 30 / M_PI / ri->t_end);
        else
            printf("speed table %s: %d rows, %g .. %g rpm; the header's speed is the reference "
                   "for speed-table bearings\n",
                   o->table, cp.p.n, cp.wmin * 30 / M_PI, cp.wmax * 30 / M_PI);
        print_text(s, tm, &recs, res, NULL, ri, nfree);
        if (wf)
            gd_cli_waterfall_print(&recs.r[wi], wf,
                                   cp.p.kind == GD_SPEED_RAMP && fabs(cp.p.to) < fabs(cp.p.from));
    }
    rc = GD_EXIT_OK;
done:
    free(rr);
    cJSON_Delete(summary);
    gd_waterfall_free(wf);
    gd_transient_result_free(res);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_cli_records_free(&recs);
    gd_cli_profile_free(&cp);
    return rc;
}

int gd_cmd_transient(int argc, char **argv)
{
    cli_opts o;
    int rc = parse_args(argc, argv, &o);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_error err;
    gd_error_clear(&err);
    if ((o.out && gd_outdir_check_writable(o.out, &err)) ||
        (o.plot && gd_plot_check_path(o.plot, NULL, &err)))
        return gd_cli_report(&err);
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    gd_spectrum **spec = NULL;
    gd_cli_records recs = {0, 0, NULL};
    cJSON *summary = NULL;
    gd_cli_periods per;
    memset(&per, 0, sizeof per);
    gd_cli_rattle rat;
    memset(&rat, 0, sizeof rat);
    double *ptimes = NULL;
    int npt = 0;
    char shift_set[160];
    if (o.shift) {
        int from, to, used = 0;
        char at[64];
        if (sscanf(o.shift, "%d:%d@%63s%n", &from, &to, at, &used) != 3 ||
            used != (int)strlen(o.shift))
            return gd_cli_usage_error(CMD, "--shift: '%s' is not FROM:TO@TIME (e.g. 3:4@0.5)",
                                      o.shift);
        snprintf(shift_set, sizeof shift_set, "shift={from: %d, to: %d, at: '%s'}", from, to, at);
        if ((rc = gd_cli_add_set(CMD, &o.sets, shift_set))) return rc;
    }
    rc = gd_cli_load(o.file, &o.sets, o.coupling, &m, &s);
    if (rc) return rc;
    run_info ri;
    memset(&ri, 0, sizeof ri);
    ri.kept = -1;
    ri.speed = m->speed;
    ri.method = o.method == GD_TR_ADAMS       ? "adams"
                : o.method == GD_TR_GEN_ALPHA ? "galpha"
                : o.method == GD_TR_AUTO      ? "auto"
                                              : "bdf";
    ri.start = o.init == GD_TR_INIT_STATIC ? "static" : "rest";
    ri.window = o.window;
    if (o.speed && gd_cli_parse_speed(CMD, o.speed, &ri.speed)) {
        rc = GD_EXIT_INPUT;
        goto done;
    }
    gd_cli_poincare pc;
    if (o.poincare && (rc = gd_cli_poincare_parse(CMD, m, o.poincare, &pc))) goto done;
    if (o.sweep) {
        rc = sweep(&o, m, s);
        goto done;
    }
    if (o.ramp || o.table) {
        rc = runup(&o, m, s, &ri);
        goto done;
    }
    if (!o.periods && (rc = resolve_times(&o, m, ri.speed, &ri))) goto done;
    if (o.poincare && (rc = poincare_times(&o, &pc, &ri, &ptimes, &npt))) goto done;
    for (int i = 0; i < m->nunbalances; i++)
        m->unbalances[i].amount *= o.unbalance_scale;
    if (gd_transient_model_build(s, &tm, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    for (int k = 0; k < o.nrecords; k++)
        if ((rc = gd_cli_parse_records(CMD, s, tm, o.records[k], &recs))) goto done;
    if (!o.nrecords && (rc = gd_cli_default_records(s, tm, &recs))) goto done;
    if (o.periods && (rc = periods_setup(&o, s, tm, &ri, &per, &ptimes, &npt))) goto done;
    double cutoff = 0;
    if (o.reduce) {
        gd_error why;
        if (gd_parse_quantity(o.reduce, GD_QTY_ANGULAR_SPEED, &cutoff, &why) || !(cutoff > 0) ||
            !isfinite(cutoff)) {
            rc = gd_cli_usage_error(CMD, "--reduce: '%s' is not a frequency > 0 (e.g. 5kHz)",
                                    o.reduce);
            goto done;
        }
    }
    double ccut = 0;
    if (o.condense && strcmp(o.condense, "off") && o.reduce) {
        rc = gd_cli_usage_error(CMD, "--condense and --reduce: give one of them");
        goto done;
    }
    const int cond_off = o.condense && !strcmp(o.condense, "off");
    if (cond_off) {
        o.condense = NULL;
    } else if (o.condense && !strcmp(o.condense, "auto")) {
        ccut = -1;
    } else if (o.condense && strcmp(o.condense, "all")) {
        gd_error why;
        if (gd_parse_quantity(o.condense, GD_QTY_ANGULAR_SPEED, &ccut, &why) || !(ccut > 0) ||
            !isfinite(ccut)) {
            rc = gd_cli_usage_error(CMD,
                                    "--condense: '%s' is not auto, off, all or a frequency > 0 "
                                    "(e.g. 8kHz)",
                                    o.condense);
            goto done;
        }
    }
    if (o.condense ? gd_transient_new_condensed(s, &tm->spec, ri.speed, ccut, &tr, &err)
        : o.reduce ? gd_transient_new_reduced(s, &tm->spec, ri.speed, cutoff, &tr, &err)
                   : gd_transient_new(s, &tm->spec, ri.speed, &tr, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    /* the default (issue 37): the condensed transient (--condense auto) where it pays,
     * said in the output; --condense off keeps the full model */
    char cond_why[256] = "";
    if (!o.condense && !o.reduce && !cond_off && o.init == GD_TR_INIT_REST &&
        (o.method == GD_TR_AUTO || o.method == GD_TR_BDF || o.method == GD_TR_ADAMS)) {
        char why[160];
        gd_transient *ct = NULL;
        gd_error cerr;
        if (gd_transient_condense_pays(tr, why, sizeof why) &&
            !gd_transient_new_condensed(s, &tm->spec, ri.speed, -1, &ct, &cerr)) {
            gd_transient_free(tr);
            tr = ct;
            o.condense = "auto";
            snprintf(cond_why, sizeof cond_why,
                     "condensed by default (%s; --condense off for the full model)", why);
        }
    }
    ri.condense = cond_why[0] ? cond_why : NULL;
    if (o.reduce) gd_transient_reduced_size(tr, &ri.kept, &ri.modes);
    gd_transient_options opt;
    gd_transient_options_init(&opt);
    opt.t_end = ri.t_end;
    opt.record_from = ri.from;
    opt.output_interval = ri.dt;
    opt.rtol = o.rtol;
    opt.method = o.method;
    /* the achieved accuracy with the result; not with --rattle: a rattling motion is
     * chaotic, its trajectories part whatever the tolerance (1.5 of the peak on the 5-speed
     * box, docs/rattle.md) and the metrics carry their own 95 % intervals, while the second
     * run at rtol / 10 cost 1.5 x the run */
    opt.error_estimate = !o.rattle && !o.no_estimate;
    opt.init = o.init;
    opt.rho_inf = o.rho_inf;
    opt.max_steps = o.max_steps;
    if (o.step) {
        if (parse_time("--step", o.step, &opt.step)) {
            rc = GD_EXIT_INPUT;
            goto done;
        }
        if (!(opt.step > 0)) {
            rc = gd_cli_usage_error(CMD, "--step: give a time > 0");
            goto done;
        }
    }
    opt.sample_times = ptimes;
    opt.nsample_times = npt;
    progress pg = {-1, 0};
    if (!o.quiet && isatty(2)) {
        opt.progress = progress_cb;
        opt.progress_data = &pg;
    }
    gd_tr_record *rr = malloc((size_t)(recs.n > 0 ? recs.n : 1) * sizeof *rr);
    if (!rr) {
        fprintf(stderr, "geardyn: error: out of memory\n");
        rc = GD_EXIT_FAIL;
        goto done;
    }
    for (int r = 0; r < recs.n; r++)
        rr[r] = recs.r[r].rec;
    gd_status st = gd_transient_run(tr, &opt, rr, recs.n, &res, &err);
    /* --rattle-extend: again over the window the metrics need (docs/rattle.md) */
    double extend = 0;
    if (!st && o.rattle_extend && parse_time("--rattle-extend", o.rattle_extend, &extend)) {
        free(rr);
        rc = GD_EXIT_INPUT;
        goto done;
    }
    for (int pass = 0; !st && extend > 0 && pass < 4; pass++) {
        if ((rc = gd_cli_rattle_analyse(tr, tm, res, ri.from, ri.t_end, o.rattle_batches,
                                        o.rattle_target, &rat))) {
            free(rr);
            goto done;
        }
        double need = 0;
        for (int j = 0; j < rat.n; j++)
            if (!rat.metrics[j].converged) need = fmax(need, rat.metrics[j].suggested_duration);
        gd_cli_rattle_free(&rat);
        double t_new = fmin(ri.from + 1.2 * need, extend);
        if (!(need > 0) || !(t_new > ri.t_end * (1 + 1e-9))) break;
        ri.t_end = opt.t_end = t_new;
        gd_transient_result_free(res);
        res = NULL;
        st = gd_transient_run(tr, &opt, rr, recs.n, &res, &err);
    }
    free(rr);
    if (pg.drawn) fprintf(stderr, "\r%60s\r", "");
    if (st) {
        rc = gd_cli_report(as_options(&err));
        goto done;
    }
    if (o.spectrum) {
        spec = calloc((size_t)(recs.n > 0 ? recs.n : 1), sizeof *spec);
        if (!spec) {
            rc = GD_EXIT_FAIL;
            goto done;
        }
        for (int r = 0; r < recs.n; r++) {
            gd_error serr;
            gd_error_clear(&serr);
            if (gd_spectrum_compute(res->values + (size_t)r * res->nout, res->nout, ri.dt, o.window,
                                    &spec[r], &serr)) {
                rc = gd_cli_report(&serr);
                goto done;
            }
        }
    }
    if (o.rattle && (rc = gd_cli_rattle_analyse(tr, tm, res, ri.from, ri.t_end, o.rattle_batches,
                                                o.rattle_target, &rat)))
        goto done;
    if (o.plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_transient(s, res, &p, &err);
        if (!pst && o.rattle && rat.n > 0) { /* the rattle section after the records' */
            const char *names[64];
            int nn = rat.n < 64 ? rat.n : 64;
            for (int j = 0; j < nn; j++)
                names[j] = gd_model_mesh_name(m, tm->meshes[rat.mesh[j]].mesh);
            gd_plot *pr = NULL;
            pst = gd_plot_rattle(names, rat.metrics, nn, &pr, &err);
            if (!pst) pst = gd_plot_append(p, pr, &err);
        }
        if ((rc = gd_cli_plot_finish(pst, p, &err, o.plot))) goto done;
    }
    gd_tr_condensed_info ci;
    const int condensed = gd_transient_condensed_info(tr, &ci);
    int nfree = condensed ? s->ndof - tm->spec.nprescribed : gd_transient_nstates(tr) / 2;
    /* auto: the method chosen and its error control, in place of the name */
    if (o.method == GD_TR_AUTO || o.condense) ri.method = res->method_note;
    summary = summary_json(s, tm, &recs, res, spec, &ri, nfree);
    if (condensed) {
        cJSON *c = cJSON_AddObjectToObject(summary, "condensed");
        cJSON_AddNumberToObject(c, "states", ci.nstates);
        cJSON_AddNumberToObject(c, "law_dofs", ci.ncoords);
        cJSON_AddNumberToObject(c, "modes_kept", ci.nkept);
        cJSON_AddNumberToObject(c, "modes_discarded", ci.ndiscarded);
        cJSON_AddNumberToObject(c, "cutoff_hz", ci.cutoff / (2 * M_PI));
        cJSON_AddNumberToObject(c, "excitation_hz", ci.excitation / (2 * M_PI));
        cJSON_AddNumberToObject(c, "contact_hz", ci.contact / (2 * M_PI));
        cJSON_AddNumberToObject(c, "truncation_estimate", ci.estimate);
    }
    int pperiod = 0, pdistinct = 0;
    char pverdict[32] = "";
    if (o.poincare) {
        double *scale = malloc((size_t)(recs.n > 0 ? recs.n : 1) * sizeof *scale);
        if (!scale) {
            rc = GD_EXIT_FAIL;
            goto done;
        }
        for (int r = 0; r < recs.n; r++)
            scale[r] = res->stats[r].peak_to_peak;
        /* the verdict also tells a torus from irregular motion (class "many") */
        gd_poincare_options po;
        gd_poincare_options_init(&po);
        po.tol = GD_CLI_POINCARE_TOL;
        gd_poincare_verdict pv;
        gd_error verr;
        gd_status vst =
            gd_poincare_classify(res->sample_values, recs.n, res->nsamples, scale, &po, &pv, &verr);
        free(scale);
        if (vst) {
            rc = gd_cli_report(&verr);
            goto done;
        }
        pperiod = pv.period;
        pdistinct = pv.distinct;
        gd_poincare_verdict_name(&pv, pverdict, sizeof pverdict);
        cJSON *pj = gd_cli_poincare_json(&pc, pc.angle / ri.speed, &recs, res->sample_t,
                                         res->sample_values, res->nsamples, pperiod, pdistinct);
        cJSON_AddStringToObject(pj, "verdict", pverdict);
        cJSON_AddItemToObject(summary, "poincare", pj);
    }
    if (o.periods) {
        if ((rc = gd_cli_periods_analyse(&per, &recs, res))) goto done;
        cJSON_AddItemToObject(summary, "periods", gd_cli_periods_json(&per, &recs));
    }
    if (o.rattle) cJSON_AddItemToObject(summary, "rattle", gd_cli_rattle_json(&rat, m, tm));
    if (o.out &&
        (rc = write_outputs(o.out, &recs, res, spec, summary, ri.speed,
                            o.poincare != NULL || o.periods > 0, o.periods ? &per : NULL, NULL)))
        goto done;
    if (o.json)
        gd_cli_print_json(stdout, summary);
    else
        print_text(s, tm, &recs, res, spec, &ri, nfree);
    if (!o.json && o.poincare) {
        print_poincare(&pc, &recs, res, ri.speed, pperiod, pdistinct);
        printf("verdict: %s%s\n", pverdict,
               pperiod == 0 && res->nsamples < 32
                   ? " (fewer than 32 points: not tested for a torus, see --periods)"
                   : "");
    }
    if (!o.json && o.periods) gd_cli_periods_print(&per, &recs);
    if (!o.json && o.rattle) gd_cli_rattle_print(&rat, m, tm);
    rc = GD_EXIT_OK;
done:
    gd_cli_rattle_free(&rat);
    free(ptimes);
    gd_cli_periods_free(&per);
    cJSON_Delete(summary);
    if (spec)
        for (int r = 0; r < recs.n; r++)
            gd_spectrum_free(spec[r]);
    free(spec);
    gd_transient_result_free(res);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_cli_records_free(&recs);
    gd_system_free(s);
    gd_model_free(m);
    return rc;
}
