/* geardyn periodic MODEL --speeds FROM:TO:COUNT: periodic steady state by harmonic
 * balance or shooting with continuation and Floquet stability (docs/periodic.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "options.h"
#include "geardyn/periodic.h"
#include "transient_record.h"

static const char CMD[] = "periodic";

#define PI 3.14159265358979323846

/* PATH=FROM:TO:COUNT */
static int parse_param(const char *text, char *path, size_t psize, double **vals, int *count)
{
    const char *eq = strrchr(text, '=');
    if (!eq || eq == text || (size_t)(eq - text) >= psize)
        return gd_cli_usage_error(CMD, "--parameter: expected PATH=FROM:TO:COUNT, got '%s'", text);
    memcpy(path, text, (size_t)(eq - text));
    path[eq - text] = 0;
    char *end;
    double a = strtod(eq + 1, &end);
    if (*end != ':') goto bad;
    double b = strtod(end + 1, &end);
    if (*end != ':') goto bad;
    long n = strtol(end + 1, &end, 10);
    if (*end || n < 1 || n > 100000 || !isfinite(a) || !isfinite(b)) goto bad;
    *vals = malloc((size_t)n * sizeof **vals);
    if (!*vals) return GD_EXIT_FAIL;
    gd_cli_linspace(a, b, n, *vals);
    *count = (int)n;
    return 0;
bad:
    return gd_cli_usage_error(CMD,
                              "--parameter: expected PATH=FROM:TO:COUNT with SI numbers and a "
                              "whole COUNT >= 1, got '%s'",
                              text);
}

/* --parameter: the problem at a value, the model file loaded with the command's
 * overrides and "PATH=VALUE" (the analysis itself reads no files) */
typedef struct rebuild_data {
    const char *file;
    const gd_load_options *base;
    const char *path;
} rebuild_data;

static gd_status rebuild(double value, void *data, gd_model **m, gd_system **sys,
                         gd_transient_model **tm, gd_error *err)
{
    const rebuild_data *d = data;
    int nb = d->base ? d->base->nset : 0;
    const char **sets = malloc((size_t)(nb + 1) * sizeof *sets);
    if (!sets) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    char assign[512];
    snprintf(assign, sizeof assign, "%s=%.17g", d->path, value);
    for (int i = 0; i < nb; i++)
        sets[i] = d->base->set[i];
    sets[nb] = assign;
    gd_load_options lo = {nb + 1, sets};
    *m = NULL, *sys = NULL, *tm = NULL;
    gd_status st = gd_model_load_opts(d->file, &lo, m, err);
    free(sets);
    if (!st) st = gd_system_build(*m, sys, err);
    if (!st) st = gd_transient_model_build(*sys, tm, err);
    if (st) {
        gd_transient_model_free(*tm);
        gd_system_free(*sys);
        gd_model_free(*m);
        *m = NULL, *sys = NULL, *tm = NULL;
    }
    return st;
}

static cJSON *num_array(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++)
        cJSON_AddItemToArray(a, gd_cli_json_number(v[i]));
    return a;
}

static cJSON *to_json(const gd_periodic_result *r, const gd_cli_records *recs, int param)
{
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "method", gd_per_kind_name(r->method));
    if (r->method_note[0]) cJSON_AddStringToObject(root, "method_choice", r->method_note);
    cJSON *pts = cJSON_AddArrayToObject(root, "points");
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddItemToObject(o, "speed_rad_s", gd_cli_json_number(p->speed));
        if (param) cJSON_AddItemToObject(o, "parameter", gd_cli_json_number(p->parameter));
        cJSON_AddNumberToObject(o, "direction", p->direction);
        cJSON_AddBoolToObject(o, "converged", p->converged);
        cJSON_AddStringToObject(o, "method", gd_per_kind_name(p->method));
        if (p->stability_method >= 0)
            cJSON_AddStringToObject(o, "stability_method",
                                    gd_per_kind_name((gd_per_kind)p->stability_method));
        else
            cJSON_AddNullToObject(o, "stability_method");
        if (!p->converged || p->reason[0]) cJSON_AddStringToObject(o, "reason", p->reason);
        if (p->stable >= 0)
            cJSON_AddBoolToObject(o, "stable", p->stable);
        else
            cJSON_AddNullToObject(o, "stable");
        cJSON_AddItemToObject(o, "floquet_multiplier_max_abs", gd_cli_json_number(p->mu_max));
        if (p->stable >= 0)
            cJSON_AddStringToObject(o, "floquet_method",
                                    p->floquet_basis    ? "reduced"
                                    : p->floquet_krylov ? "krylov"
                                                        : "dense");
        if (p->floquet_basis) cJSON_AddNumberToObject(o, "floquet_basis", p->floquet_basis);
        if (p->floquet_steps > 0) cJSON_AddNumberToObject(o, "floquet_steps", p->floquet_steps);
        cJSON_AddNumberToObject(o, "harmonics", p->harmonics);
        cJSON_AddItemToObject(o, "residual", gd_cli_json_number(p->residual));
        if (p->converged) {
            cJSON *t = cJSON_AddObjectToObject(o, "truncation");
            cJSON_AddNumberToObject(t, "harmonics_compared", p->harmonics_ref);
            cJSON_AddItemToObject(t, "peak_to_peak", gd_cli_json_number(p->harmonic_error_p2p));
            cJSON_AddItemToObject(t, "amplitudes", gd_cli_json_number(p->harmonic_error_amp));
            if (p->harmonic_ok >= 0)
                cJSON_AddBoolToObject(t, "within_tolerance", p->harmonic_ok);
            else
                cJSON_AddNullToObject(t, "within_tolerance");
            if (p->harmonic_ok != 1 && p->reason[0]) cJSON_AddStringToObject(t, "note", p->reason);
        }
        if (p->converged) {
            cJSON_AddItemToObject(o, "omega_rad_s", gd_cli_json_number(p->omega));
            cJSON_AddNumberToObject(o, "iterations", p->iterations);
            if (p->nmult) {
                cJSON_AddItemToObject(o, "floquet_re", num_array(p->mu_re, p->nmult));
                cJSON_AddItemToObject(o, "floquet_im", num_array(p->mu_im, p->nmult));
            }
            cJSON *rs = cJSON_AddObjectToObject(o, "records");
            for (int k = 0; k < recs->n; k++) {
                const gd_per_record_stats *s = &p->records[k];
                cJSON *x = cJSON_AddObjectToObject(rs, recs->r[k].name);
                cJSON_AddItemToObject(x, "mean", gd_cli_json_number(s->mean));
                cJSON_AddItemToObject(x, "rms", gd_cli_json_number(s->rms));
                cJSON_AddItemToObject(x, "peak_to_peak", gd_cli_json_number(s->peak_to_peak));
                cJSON_AddItemToObject(x, "peak_to_peak_error", gd_cli_json_number(s->p2p_error));
                cJSON_AddItemToObject(x, "amplitudes_error", gd_cli_json_number(s->amp_error));
                cJSON_AddItemToObject(x, "amplitudes", num_array(s->amplitude, p->harmonics + 1));
                cJSON_AddItemToObject(x, "phases_deg", num_array(s->phase_deg, p->harmonics + 1));
            }
        }
        cJSON_AddItemToArray(pts, o);
    }
    cJSON *bif = cJSON_AddArrayToObject(root, "bifurcations");
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "type", gd_bifurcation_name(b->type));
        cJSON_AddItemToObject(o, "speed_rad_s", gd_cli_json_number(b->speed));
        cJSON_AddItemToObject(o, "parameter", gd_cli_json_number(b->parameter));
        cJSON_AddNumberToObject(o, "direction", b->direction);
        cJSON_AddItemToObject(o, "multiplier_re", gd_cli_json_number(b->mu_re));
        cJSON_AddItemToObject(o, "multiplier_im", gd_cli_json_number(b->mu_im));
        cJSON_AddItemToArray(bif, o);
    }
    cJSON_AddNumberToObject(root, "continuation_steps", r->steps);
    /* no timings: the same command gives the same JSON (the CPU time goes to stderr) */
    return root;
}

static void print_table(const gd_periodic_result *r, const gd_cli_records *recs, int param)
{
    printf("method: %s\n", r->method_note[0] ? r->method_note : gd_per_kind_name(r->method));
    {
        /* how each point's orbit and multipliers were found, counted */
        int orb[3] = {0, 0, 0}, stab[3] = {0, 0, 0}, none = 0;
        for (int i = 0; i < r->npoints; i++) {
            const gd_periodic_point *p = &r->points[i];
            if (!p->converged) continue;
            orb[p->method == GD_PER_REDUCED_SHOOTING ? 2 : p->method == GD_PER_SHOOTING]++;
            if (p->stability_method < 0)
                none++;
            else
                stab[p->stability_method == GD_PER_REDUCED_SHOOTING
                         ? 2
                         : p->stability_method == GD_PER_SHOOTING]++;
        }
        printf("points: %d by harmonic balance, %d by shooting", orb[0], orb[1]);
        if (orb[2]) printf(", %d by reduced shooting", orb[2]);
        printf("; stability: %d from harmonic balance orbits, %d from shooting orbits", stab[0],
               stab[1]);
        if (stab[2]) printf(", %d from reduced shooting orbits", stab[2]);
        printf(", %d not computed\n", none);
    }
    for (int i = 0; i < r->npoints; i++)
        if (r->points[i].floquet_basis) {
            printf("stability: the Floquet multipliers of a reduced basis of %d vectors (the "
                   "modes below the cut-off and the laws' residual flexibility)\n",
                   r->points[i].floquet_basis);
            break;
        }
    for (int i = 0; i < r->npoints; i++)
        if (r->points[i].floquet_krylov) {
            printf("stability: the %d largest Floquet multipliers by Krylov-Schur on "
                   "monodromy-vector products (no dense monodromy)\n",
                   r->points[i].nmult);
            break;
        }
    printf("%3s %14s %12s%s %4s %9s %8s %8s %6s %10s", "dir", "speed_rad_s", "speed_rpm",
           param ? "      parameter" : "", "H", "residual", "err_p2p", "err_amp", "stable",
           "|mu|max");
    for (int k = 0; k < recs->n; k++)
        printf("  %s rms,p2p", recs->r[k].name);
    printf("\n");
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        printf("%3s %14.6f %12.3f", p->direction > 0 ? "+" : "-", p->speed, p->speed * 30 / PI);
        if (param) printf(" %14.6g", p->parameter);
        if (!p->converged) {
            printf("  not converged: %s\n", p->reason);
            continue;
        }
        printf(" %4d %9.2e %8.1e %8.1e %6s %10.6f", p->harmonics, p->residual,
               p->harmonic_error_p2p, p->harmonic_error_amp,
               p->stable < 0 ? "-"
               : p->stable   ? "yes"
                             : "no",
               p->mu_max);
        for (int k = 0; k < recs->n; k++)
            printf("  %.6g,%.6g", p->records[k].rms, p->records[k].peak_to_peak);
        printf("%s\n", p->harmonic_ok == 0 ? "  (truncation not within tolerance)" : "");
        if (p->stable < 0 && p->reason[0]) printf("      %s\n", p->reason);
    }
    if (r->nbifurcations) printf("\nbifurcations:\n");
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        printf("  %-16s speed %.6f rad/s", gd_bifurcation_name(b->type), b->speed);
        if (param) printf("  parameter %.9g", b->parameter);
        if (isfinite(b->mu_re)) printf("  multiplier %.6f%+.6fi", b->mu_re, b->mu_im);
        printf("\n");
    }
    printf("\n%d continuation steps\n", r->steps);
}

static void csv_header(FILE *f)
{
    fprintf(f, "point,direction,speed_rad_s,parameter,converged,harmonics,residual,stable,"
               "floquet_multiplier_max_abs,record,mean,rms,peak_to_peak,harmonics_compared,"
               "peak_to_peak_error,amplitudes_error\n");
}

static void csv_rows(FILE *f, int i, const gd_periodic_point *p, const gd_cli_records *recs)
{
    for (int k = 0; k < (p->converged && recs->n ? recs->n : 1); k++) {
        const gd_per_record_stats *s = p->converged && recs->n ? &p->records[k] : NULL;
        fprintf(f, "%d,%d,%.10g,%.10g,%d,%d,%.6g,%d,%.10g,%s,%.10g,%.10g,%.10g,%d,%.4g,%.4g\n", i,
                p->direction, p->speed, p->parameter, p->converged, p->harmonics, p->residual,
                p->stable, p->mu_max, s ? recs->r[k].name : "", s ? s->mean : NAN, s ? s->rms : NAN,
                s ? s->peak_to_peak : NAN, p->harmonics_ref,
                s ? s->p2p_error : p->harmonic_error_p2p, s ? s->amp_error : p->harmonic_error_amp);
    }
}

static int write_out(const char *dir, const gd_periodic_result *r, const gd_cli_records *recs)
{
    gd_error err;
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "periodic.csv", &err);
    if (!f) goto fail;
    csv_header(f);
    for (int i = 0; i < r->npoints; i++)
        csv_rows(f, i, &r->points[i], recs);
    if (gd_outdir_close(&od, f, "periodic.csv", &err)) goto fail;
    if (!(f = gd_outdir_open(&od, "harmonics.csv", &err))) goto fail;
    fprintf(f, "point,speed_rad_s,parameter,record,harmonic,amplitude,phase_deg\n");
    for (int i = 0; i < r->npoints; i++) {
        const gd_periodic_point *p = &r->points[i];
        if (!p->converged) continue;
        for (int k = 0; k < recs->n; k++)
            for (int h = 0; h <= p->harmonics; h++)
                fprintf(f, "%d,%.10g,%.10g,%s,%d,%.10g,%.10g\n", i, p->speed, p->parameter,
                        recs->r[k].name, h, p->records[k].amplitude[h], p->records[k].phase_deg[h]);
    }
    if (gd_outdir_close(&od, f, "harmonics.csv", &err)) goto fail;
    if (!(f = gd_outdir_open(&od, "bifurcations.csv", &err))) goto fail;
    fprintf(f, "type,direction,speed_rad_s,parameter,multiplier_re,multiplier_im\n");
    for (int i = 0; i < r->nbifurcations; i++) {
        const gd_bifurcation *b = &r->bifurcations[i];
        fprintf(f, "%s,%d,%.10g,%.10g,%.10g,%.10g\n", gd_bifurcation_name(b->type), b->direction,
                b->speed, b->parameter, b->mu_re, b->mu_im);
    }
    if (gd_outdir_close(&od, f, "bifurcations.csv", &err)) goto fail;
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

/* The continued quantity of point p with its unit, for messages: "speed 120 rad/s",
 * "load frequency 1.2 rad/s" or "PATH = VALUE" (issue 38 L6). */
static void point_value(char *buf, size_t cap, const gd_periodic_point *p, const char *param,
                        int freq)
{
    if (freq)
        snprintf(buf, cap, "load frequency %.6g rad/s", p->parameter);
    else if (param)
        snprintf(buf, cap, "%s = %.6g", param, p->parameter);
    else
        snprintf(buf, cap, "speed %.6g rad/s", p->speed);
}

/* Points as they converge: appended to DIR/periodic.partial.csv (flushed per point, so an
 * interrupted run keeps what it finished; removed once the complete files are in place)
 * and a progress line with the estimated time left on a terminal. */
typedef struct live {
    FILE *csv;
    const gd_cli_records *recs;
    int tty, drawn, nfail;
    int quiet;              /* --quiet: no progress at all */
    struct timespec t0, tl; /* the run's start, the last point's end */
    struct timespec tp;     /* the last progress output (a point or a step line) */
    const char *param;      /* the continued quantity's name (NULL: the speed) */
    int freq;
} live;

static double since(const struct timespec *a, const struct timespec *b)
{
    return (double)(b->tv_sec - a->tv_sec) + 1e-9 * (double)(b->tv_nsec - a->tv_nsec);
}

static void on_point(const gd_periodic_point *p, int index, double progress, void *user)
{
    live *l = user;
    if (!p->converged) l->nfail++;
    if (l->csv) {
        csv_rows(l->csv, index, p, l->recs);
        fflush(l->csv);
    }
    if (l->quiet) return;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    const double el = since(&l->t0, &t), took = since(&l->tl, &t);
    l->tl = l->tp = t;
    if (!l->tty) {
        /* not a terminal (a log, a pipe): one line per point that took more than a second,
         * so a long run is never silent; stdout is untouched (the same output every run) */
        if (took > 1.0) {
            char at[300];
            point_value(at, sizeof at, p, l->param, l->freq);
            fprintf(stderr,
                    "geardyn periodic: point %d (%s) %s by %s in %.1f s, %d%% of the range, "
                    "%d failed\n",
                    index + 1, at, p->converged ? "converged" : "failed",
                    gd_per_kind_name(p->method), took, (int)(100 * progress), l->nfail);
            fflush(stderr);
        }
        return;
    }
    char eta[32] = "?";
    if (progress > 0.005) snprintf(eta, sizeof eta, "%.0f s", el * (1 - progress) / progress);
    char bar[31];
    int fill = (int)(progress * 30);
    for (int i = 0; i < 30; i++)
        bar[i] = i < fill ? '#' : '.';
    bar[30] = 0;
    fprintf(stderr, "\r[%s] %3d%%  %d points (%d failed)  %.1f rpm  H %d  left %s   ", bar,
            (int)(100 * progress), index + 1, l->nfail, p->speed * 30 / PI, p->harmonics, eta);
    fflush(stderr);
    l->drawn = 1;
}

/* An arclength step between requested points: without a terminal, a line whenever more
 * than a second passed since the last line or point (a long branch is never silent); on
 * a terminal the bar stays (it is redrawn at the next point). */
static void on_step(double value, void *user)
{
    live *l = user;
    if (l->quiet || l->tty) return;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    if (since(&l->tp, &t) <= 1.0) return;
    const double el = since(&l->t0, &t);
    l->tp = t;
    if (l->freq)
        fprintf(stderr, "geardyn periodic: continuing, at load frequency %.6g rad/s (%.1f s)\n",
                value, el);
    else if (l->param)
        fprintf(stderr, "geardyn periodic: continuing, at %s = %.6g (%.1f s)\n", l->param, value,
                el);
    else
        fprintf(stderr, "geardyn periodic: continuing, at speed %.6g rad/s (%.1f s)\n", value, el);
    fflush(stderr);
}

/* Where no stable periodic orbit came out (a point unstable or not converged), the
 * response may have none (a rattling train): name the `transient` run that gives its
 * per-period statistics and Poincare verdict (docs/transient.md). */
static void rattle_hint(const char *model, const gd_periodic_result *r, const char *param, int freq,
                        int load_index, const gd_system *sys, const gd_transient_spec *spec)
{
    int first = -1, n = 0;
    for (int i = 0; i < r->npoints; i++)
        if (!r->points[i].converged || r->points[i].stable == 0) {
            if (first < 0) first = i;
            n++;
        }
    if (first < 0) return;
    const gd_periodic_point *p = &r->points[first];
    char at[300];
    point_value(at, sizeof at, p, param, freq);
    printf("\n%d of %d points have no stable periodic orbit (unstable or not converged; "
           "first at %s). Where the response has none (rattle, a torus), its statistics over "
           "many periods and the Poincare verdict come from `geardyn transient`",
           n, r->npoints, at);
    double w0 = 0;
    gd_error perr;
    gd_error_clear(&perr);
    if (!freq && p->speed > 0 && gd_periodic_fundamental(sys, spec, p->speed, &w0, NULL, &perr)) {
        /* no common period (incommensurate excitations): --periods has none to count, so a
           run of a given length, its statistics over the last 100 revolutions */
        const double rev = 6.283185307179586 / p->speed;
        char set[300] = "";
        if (param) snprintf(set, sizeof set, " --set %s=%.9g", param, p->parameter);
        printf(" over a given time instead (the excitations have no common period: no "
               "Poincare section, and --periods has none to count), e.g. 300 revolutions, the "
               "statistics of the last 100:\n"
               "  geardyn transient %s%s --speed %.6g --duration %.6g --from %.6g\n",
               model, set, p->speed, 300.0 * rev, 200.0 * rev);
    } else if (freq) {
        /* a forced response: the model's loads at that frequency, set in the model file
         * (transient has no frequency option; the speed is the model's) */
        const double T = p->parameter > 0 ? 6.283185307179586 / p->parameter : 1.0;
        printf(" with the load at that frequency over 300 of its periods (the statistics of the "
               "last 100), e.g.\n  geardyn transient %s --set "
               "excitations.loads.%d.frequency=%.9grad/s --duration %.6g --from %.6g\n",
               model, load_index, p->parameter, 300.0 * T, 200.0 * T);
    } else if (param) {
        printf(", e.g.\n  geardyn transient %s --set %s=%.9g --speed %.6g --periods 100 "
               "--settle 200rev\n",
               model, param, p->parameter, p->speed);
    } else if (p->speed > 0) {
        printf(", e.g.\n  geardyn transient %s --speed %.6g --periods 100 --settle 200rev\n", model,
               p->speed);
    } else {
        printf(" (at a reference speed of 0 a driven model has no shaft period to count: give "
               "--duration)\n");
    }
    printf("with the same --set, --dofs and --coupling options (docs/transient.md).\n");
}

/* --frequency FROM:TO:COUNT with units, either way (a branch followed downwards, as
 * NLvib's example 03 does): TO < FROM is parsed as TO:FROM and reversed. */
static int parse_down_range(const char *text, double **v, int *n)
{
    char buf[256], *a, *b;
    if (strlen(text) >= sizeof buf || !(a = strchr(strcpy(buf, text), ':')) ||
        !(b = strchr(a + 1, ':')))
        return gd_cli_parse_range(CMD, "--frequency", text, v, n);
    *a = *b = '\0';
    double lo, hi;
    if (gd_cli_parse_speed(CMD, buf, &lo) || gd_cli_parse_speed(CMD, a + 1, &hi) || !(hi < lo))
        return gd_cli_parse_range(CMD, "--frequency", text, v, n);
    char rev[300];
    snprintf(rev, sizeof rev, "%s:%s:%s", a + 1, buf, b + 1);
    int rc = gd_cli_parse_range(CMD, "--frequency", rev, v, n);
    for (int i = 0; !rc && i < *n / 2; i++) {
        double t = (*v)[i];
        (*v)[i] = (*v)[*n - 1 - i];
        (*v)[*n - 1 - i] = t;
    }
    return rc;
}

typedef struct periodic_args {
    gd_periodic_options opt; /* first: --harmonics's parser reaches fixed_h through it */
    int fixed_h;             /* --harmonics H given (--no-estimate needs it) */
    const char *speeds, *coupling, *out, *param, *freq, *plot;
    const char *records[64];
    int nrec, json, quiet;
    gd_cli_sets sets;
} periodic_args;

/* --harmonics H|auto */
static int parse_harmonics(const char *cmd, const char *text, void *field)
{
    periodic_args *a = field; /* field is .opt, the first member */
    long h;
    if (!strcmp(text, "auto")) {
        a->opt.adaptive = 1;
        return 0;
    }
    if (gd_cli_parse_count(text, 1, 1 << 20, &h))
        return gd_cli_usage_error(cmd, "--harmonics: expected a whole H >= 1 or auto, got '%s'",
                                  text);
    a->opt.harmonics = (int)h;
    a->opt.adaptive = 0;
    a->fixed_h = 1;
    return 0;
}

static int parse_max_harmonics(const char *cmd, const char *text, void *field)
{
    long h;
    if (gd_cli_parse_count(text, 1, 1 << 20, &h))
        return gd_cli_usage_error(cmd, "--max-harmonics: expected a whole H >= 1, got '%s'", text);
    *(int *)field = (int)h;
    return 0;
}

/* --method hb|harmonic-balance|condensed|full-hb|shooting|reduced-shooting|multifreq|auto */
static int parse_method(const char *cmd, const char *text, void *field)
{
    periodic_args *a = field; /* field is .opt, the first member */
    gd_per_kind *k = &a->opt.kind;
    a->opt.condensed = 0;
    if (!strcmp(text, "hb") || !strcmp(text, "harmonic-balance"))
        *k = GD_PER_HB;
    else if (!strcmp(text, "condensed")) {
        *k = GD_PER_HB;
        a->opt.condensed = 1;
    } else if (!strcmp(text, "full-hb")) {
        *k = GD_PER_HB;
        a->opt.condensed = -1;
    } else if (!strcmp(text, "shooting"))
        *k = GD_PER_SHOOTING;
    else if (!strcmp(text, "auto"))
        *k = GD_PER_AUTO;
    else if (!strcmp(text, "multifreq"))
        *k = GD_PER_MULTIFREQ;
    else if (!strcmp(text, "reduced-shooting"))
        *k = GD_PER_REDUCED_SHOOTING;
    else
        return gd_cli_usage_error(cmd,
                                  "--method: expected hb, condensed, full-hb, shooting, "
                                  "reduced-shooting, multifreq or auto, got '%s'",
                                  text);
    return 0;
}

static int parse_shoot_rtol(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (*end || !(v >= 1e-14 && v < 1e-2))
        return gd_cli_usage_error(
            cmd, "--shoot-rtol: expected a tolerance in [1e-14, 1e-2), got '%s'", text);
    *(double *)field = v;
    return 0;
}

static int parse_shoot_dense_max(const char *cmd, const char *text, void *field)
{
    long n;
    if (gd_cli_parse_count(text, 1, 1 << 20, &n))
        return gd_cli_usage_error(
            cmd, "--shoot-dense-max: expected a whole number of states >= 1, got '%s'", text);
    *(int *)field = (int)n;
    return 0;
}

static int parse_seconds(const char *cmd, const char *option, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v >= 0 && v < 1e9))
        return gd_cli_usage_error(
            cmd, "--%s: expected seconds >= 0 (counted work; 0: no limit), got '%s'", option, text);
    *(double *)field = v;
    return 0;
}

static int parse_shoot_budget(const char *cmd, const char *text, void *field)
{
    return parse_seconds(cmd, "shoot-budget", text, field);
}

static int parse_floquet_cutoff(const char *cmd, const char *text, void *field)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end || !(v > 0 && v < 1e6))
        return gd_cli_usage_error(cmd, "--floquet-cutoff: expected a multiple > 0, got '%s'", text);
    *(double *)field = v;
    return 0;
}

static int parse_floquet_budget(const char *cmd, const char *text, void *field)
{
    return parse_seconds(cmd, "floquet-budget", text, field);
}

static int parse_subharmonic(const char *cmd, const char *text, void *field)
{
    long n;
    if (gd_cli_parse_count(text, 1, 1000, &n))
        return gd_cli_usage_error(
            cmd, "--subharmonic: expected a whole number 1..1000 (period N T), got '%s'", text);
    *(int *)field = (int)n;
    return 0;
}

/* --tol, --harmonic-tol: a relative tolerance in [1e-15, 1) */
static int parse_tol(const char *cmd, const char *text, void *field)
{
    return gd_cli_parse_tolerance(cmd, "--tol", text, field);
}
static int parse_harmonic_tol(const char *cmd, const char *text, void *field)
{
    return gd_cli_parse_tolerance(cmd, "--harmonic-tol", text, field);
}

/* A count per period from lo to 2^20 (AFT samples, Magnus steps). */
static int parse_per_period(const char *cmd, const char *name, long lo, const char *text,
                            void *field)
{
    long n;
    if (gd_cli_parse_count(text, lo, GD_PERIODIC_MAX_SAMPLES, &n))
        return gd_cli_usage_error(cmd,
                                  "--%s: expected a whole number from %ld to %d (2^20), got '%s'",
                                  name, lo, GD_PERIODIC_MAX_SAMPLES, text);
    *(int *)field = (int)n;
    return 0;
}

static int parse_samples(const char *cmd, const char *text, void *field)
{
    return parse_per_period(cmd, "samples", 4, text, field);
}

static int parse_monodromy_steps(const char *cmd, const char *text, void *field)
{
    return parse_per_period(cmd, "monodromy-steps", 1, text, field);
}

#define F(m) offsetof(periodic_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("speeds", GD_CLI_STRING, F(speeds), "FROM:TO:COUNT",
               "reference speeds, units allowed (required, or --frequency); each requested speed "
               "is solved exactly wherever the branch crosses it"),
    GD_CLI_ROW("method", GD_CLI_CALL, F(opt), "M",
               "auto (default): shooting where a law is not smooth (backlash, contact, a "
               "unilateral spring: its orbits solve the time-domain equations), else the cheaper "
               "by a cost counted from the model's sizes; a point the chosen method fails is "
               "handed to the other (each choice is printed); hb: harmonic balance (condensed "
               "onto the laws' coordinates where that applies, else the full solve); condensed: "
               "always condensed; full-hb: never; shooting: "
               "Newton on the period map of transient's integrator (every law transient has, "
               "cams with include_acceleration included; pseudo-arclength through folds as hb, "
               "--sequential natural); multifreq: harmonic balance with one base frequency per "
               "mesh group on their torus (co-prime tooth counts; auto takes it where the common "
               "period holds more than 16 periods of the highest); reduced-shooting: laws linear "
               "in the state at fixed time only (meshes without backlash: TVMS, STE; constant "
               "loads): the orbit by one Magnus sweep in the modes below 30 kHz, no harmonic "
               "truncation, each point at S and 2 S steps (their change is the error column), "
               "natural continuation (auto takes it with --harmonics auto where harmonic "
               "balance's truncation estimate at H = 591 is over --harmonic-tol)",
               .def = "auto", .call = parse_method),
    GD_CLI_ROW("shoot-rtol", GD_CLI_CALL, F(opt.shoot_rtol), "TOL",
               "shooting: the integrator's relative tolerance", .def = "1e-9",
               .call = parse_shoot_rtol),
    GD_CLI_ROW("shoot-dense-max", GD_CLI_CALL, F(opt.shoot_dense_max), "N",
               "shooting: the dense monodromy up to N states; above, Newton-Krylov on "
               "monodromy-vector products",
               .def = "64", .call = parse_shoot_dense_max),
    GD_CLI_ROW("shoot-budget", GD_CLI_CALL, F(opt.shoot_budget), "S",
               "shooting: seconds per point (counted work at 2 GFlop/s, never a clock: the same "
               "decision every run) before it stops, not converged, saying why (0: no limit)",
               .def = "30", .call = parse_shoot_budget),
    GD_CLI_ROW("harmonics", GD_CLI_CALL, F(opt), "H|auto",
               "harmonics of the period; auto (default): from the least H that holds every "
               "excitation, doubled per point until every record's peak-to-peak and harmonic "
               "amplitudes agree with those at 2 H to --harmonic-tol; a fixed H is checked "
               "against 2 H the same way",
               .call = parse_harmonics),
    GD_CLI_ROW("harmonic-tol", GD_CLI_CALL, F(opt.harmonic_tol), "TOL",
               "truncation tolerance, relative", .def = "0.01", .call = parse_harmonic_tol),
    GD_CLI_ROW("max-harmonics", GD_CLI_CALL, F(opt.max_harmonics), "H", "cap of H",
               .def = "the largest whose workspace fits in half the memory",
               .call = parse_max_harmonics),
    GD_CLI_ROW("no-estimate", GD_CLI_CLEAR, F(opt.estimate), NULL,
               "with a fixed H: no solution at 2 H, no truncation estimate"),
    GD_CLI_ROW("subharmonic", GD_CLI_CALL, F(opt.subharmonic), "N",
               "solutions of period N times the fundamental", .def = "1",
               .call = parse_subharmonic),
    GD_CLI_ROW("record", GD_CLI_LIST, F(records), "WHAT",
               "as for transient: NODE.DOF[:disp|vel|speed], ratio:A/B, "
               "mesh:NAME[:force|deflection|stiffness|state], sfd:BEARING[:fx|fy|ecc], "
               "law:NAME[:RECORD]",
               .aux = F(nrec), .hi = 64),
    GD_CLI_ROW("parameter", GD_CLI_STRING, F(param), "PATH=FROM:TO:COUNT",
               "continue in a model value (SI numbers, the --set path syntax) at the first speed "
               "of --speeds instead of the speed"),
    GD_CLI_ROW("frequency", GD_CLI_STRING, F(freq), "FROM:TO:COUNT",
               "continue in the frequency of the time-harmonic loads (rad/s, or units: "
               "0.1Hz:0.2Hz:51; several loads keep their ratios) at the first speed of --speeds "
               "(or the model's speed)"),
    GD_CLI_ROW("both-directions", GD_CLI_FLAG, F(opt.both_directions), NULL,
               "also the run from the end back to the start"),
    GD_CLI_ROW("sequential", GD_CLI_VALUE, F(opt.method), NULL,
               "no arclength: one solution per speed from the previous one (jumps at folds, as a "
               "slow run-up)",
               .ival = GD_PER_SEQUENTIAL),
    GD_CLI_ROW("no-stability", GD_CLI_CLEAR, F(opt.stability), NULL,
               "skip the Floquet multipliers (and bifurcations)"),
    GD_CLI_ROW("floquet", GD_CLI_CHOICE, F(opt.floquet), "M",
               "auto (dense up to 300 states when its counted cost fits --floquet-budget, reduced "
               "else), dense, krylov (the 8 largest "
               "multipliers from monodromy-vector products) or reduced (every multiplier of the "
               "monodromy in the modes below --floquet-cutoff plus the local laws' residual "
               "flexibility)",
               .def = "auto", .word = "auto|dense|krylov|reduced"),
    GD_CLI_ROW("stability-orbit", GD_CLI_CHOICE, F(opt.shoot_stability), "M",
               "harmonic balance points' multipliers: auto (where a law is not smooth, from the "
               "orbit corrected by shooting: a few Newton steps on the period map, then its "
               "integrated monodromy), fourier (the Magnus monodromy about the truncated Fourier "
               "orbit) or shooting (always corrected); JSON stability_method says which",
               .def = "auto", .word = "fourier|auto|shooting"),
    GD_CLI_ROW("floquet-cutoff", GD_CLI_CALL, F(opt.floquet_cutoff), "C",
               "reduced multipliers: keep the modes up to C times the highest excitation "
               "frequency (the top tooth-mesh frequency)",
               .def = "4", .call = parse_floquet_cutoff),
    GD_CLI_ROW("monodromy-steps", GD_CLI_CALL, F(opt.monodromy_steps), "N",
               "Magnus steps per period of the multipliers; the reduced method's default: 8 per "
               "period of the top mesh order, doubled until two counts agree",
               .def = "4 x samples, at least 256", .call = parse_monodromy_steps),
    GD_CLI_ROW("floquet-budget", GD_CLI_CALL, F(opt.floquet_budget), "S",
               "seconds for one point's multipliers (counted work at 2 GFlop/s, never a clock); a "
               "point whose multipliers would take longer keeps its orbit with stability not "
               "computed and says how long they would "
               "take (0: no limit)",
               .def = "30", .call = parse_floquet_budget),
    GD_CLI_ROW("tol", GD_CLI_CALL, F(opt.tol), "TOL", "Newton's relative residual", .def = "1e-10",
               .call = parse_tol),
    GD_CLI_ROW("samples", GD_CLI_CALL, F(opt.samples), "N", "AFT time samples per period",
               .def = "4 (H + 1), power of 2", .call = parse_samples),
    GD_CLI_ROW_COUPLING(periodic_args, coupling),
    GD_CLI_ROW_DOFS(periodic_args, sets),
    GD_CLI_ROW_SET(periodic_args, sets),
    GD_CLI_ROW("json", GD_CLI_FLAG, F(json), NULL,
               "one JSON object on stdout: points, bifurcations"),
    GD_CLI_ROW_OUT(periodic_args, out, "DIR/periodic.csv, DIR/harmonics.csv, DIR/bifurcations.csv"),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "peak-to-peak and harmonics of each record over the branch (stable solid, "
               "unstable dashed), bifurcations marked, Floquet multipliers: FILE.svg or "
               "FILE.html (interactive, self-contained; docs/plots.md)"),
    GD_CLI_ROW("quiet", GD_CLI_FLAG, F(quiet), NULL,
               "no progress on stderr (a bar on a terminal; otherwise a line for every point "
               "that took more than a second); the closing CPU time line stays"),
    {0}};
static const gd_cli_command PERIODIC = {
    .name = CMD,
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about = "Periodic steady state by harmonic balance (alternating frequency-time on every\n"
             "nonlinear and time-varying law of `transient`) or shooting (--method auto, the\n"
             "default, picks per model and hands failed points over), continued by\n"
             "pseudo-arclength over the speed (through folds: a hysteresis loop gives several\n"
             "points per speed), with Floquet multipliers and the bifurcations found on the\n"
             "way. The same command gives the same output on every run.\n",
    .footer = "Exit status 1 when a requested point did not converge (after writing what did, "
              "with\na summary on stderr).\n"};
int gd_cmd_periodic(int argc, char **argv)
{
    periodic_args a = {0};
    const char *file;
    gd_periodic_options_init(&a.opt);
    a.opt.adaptive = 1;          /* the default: H from the excitations, raised until it holds */
    a.opt.kind = GD_PER_AUTO;    /* the method from the model, failed points handed over */
    a.opt.shoot_stability = 1;   /* non-smooth laws: multipliers of a time-domain orbit */
    a.opt.shoot_budget = 30.0;   /* a point never runs for minutes in silence */
    a.opt.floquet_budget = 30.0; /* nor its multipliers */
    int rc = gd_cli_parse(&PERIODIC, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_periodic_options opt = a.opt;
    if (!opt.estimate && !a.fixed_h)
        return gd_cli_usage_error(CMD, "--no-estimate needs a fixed --harmonics H (auto always "
                                       "compares H with 2 H)");
    if (!a.speeds && !a.freq)
        return gd_cli_usage_error(CMD, "--speeds FROM:TO:COUNT (or --frequency) is required");
    if (a.freq && a.param)
        return gd_cli_usage_error(CMD, "give --frequency or --parameter, not both");
    if (opt.samples && opt.samples < 2 * opt.harmonics + 2)
        return gd_cli_usage_error(CMD, "--samples %d cannot resolve %d harmonics (give >= %d)",
                                  opt.samples, opt.harmonics, 2 * opt.harmonics + 2);
    if (a.param && a.coupling)
        return gd_cli_usage_error(CMD, "--parameter reloads the model: give the coupling "
                                       "with --set instead of --coupling");
    if (a.param && a.sets.dofs)
        return gd_cli_usage_error(CMD, "--parameter reloads the model at every value and keeps "
                                       "every DOF: drop --dofs (or continue in --speeds or "
                                       "--frequency, which take it)");
    double *sp = NULL, *pv = NULL;
    int nsp = 0, npv = 0;
    char ppath[256], partial[1100] = "";
    int made_dir = 0;
    if (a.speeds && (rc = gd_cli_parse_range(CMD, "--speeds", a.speeds, &sp, &nsp))) return rc;
    if (a.param && (rc = parse_param(a.param, ppath, sizeof ppath, &pv, &npv))) {
        free(sp);
        return rc;
    }
    if (a.freq && (rc = parse_down_range(a.freq, &pv, &npv))) {
        free(sp);
        return rc;
    }
    if (a.freq) snprintf(ppath, sizeof ppath, "load frequency");
    gd_error err;
    gd_error_clear(&err);
    if ((a.out && gd_outdir_check_writable(a.out, &err)) ||
        (a.plot && gd_plot_check_path(a.plot, NULL, &err))) {
        free(sp);
        free(pv);
        return gd_cli_report(&err);
    }
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_periodic_result *r = NULL;
    gd_cli_records recs = {0};
    if ((rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s))) goto done;
    if (gd_transient_model_build(s, &tm, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    for (int k = 0; k < a.nrec; k++)
        if ((rc = gd_cli_parse_records(CMD, s, tm, a.records[k], &recs))) goto done;
    if (!a.nrec && (rc = gd_cli_default_records(s, tm, &recs))) goto done;
    gd_tr_record *rv = malloc((size_t)(recs.n > 0 ? recs.n : 1) * sizeof *rv);
    if (!rv) {
        rc = GD_EXIT_FAIL;
        goto done;
    }
    for (int k = 0; k < recs.n; k++) {
        rv[k] = recs.r[k].rec;
        if (rv[k].kind == GD_REC_ANGLE) {
            free(rv);
            rc = gd_cli_usage_error(CMD,
                                    "--record %s: a total angle grows with time and has no "
                                    "periodic steady state; record the DOF's displacement "
                                    "(its perturbation) or its speed",
                                    recs.r[k].name);
            goto done;
        }
    }
    gd_load_options lo = gd_cli_load_options(&a.sets);
    gd_blas_set_threads(1); /* small dense blocks: threads cost more than they give */
    rebuild_data rd = {file, &lo, ppath};
    /* --frequency: at the first of --speeds, or the model's speed */
    gd_periodic_param prm = {rebuild, &rd, ppath, sp ? sp[0] : m->speed, a.freq != NULL};
    live lv2 = {0};
    lv2.recs = &recs;
    lv2.tty = !a.quiet && isatty(2);
    lv2.quiet = a.quiet;
    lv2.param = pv && !a.freq ? ppath : NULL;
    lv2.freq = a.freq != NULL;
    clock_gettime(CLOCK_MONOTONIC, &lv2.t0);
    lv2.tl = lv2.tp = lv2.t0;
    if (a.out) {
        made_dir = mkdir(a.out, 0777) == 0; /* the partial file goes in it */
        snprintf(partial, sizeof partial, "%s/periodic.partial.csv", a.out);
        if ((lv2.csv = fopen(partial, "w"))) csv_header(lv2.csv);
    }
    opt.on_point = on_point;
    opt.on_step = on_step;
    opt.user = &lv2;
    gd_status pst0 = gd_periodic_run(s, &tm->spec, pv ? &prm : NULL, pv ? pv : sp, pv ? npv : nsp,
                                     &opt, rv, recs.n, &r, &err);
    if (lv2.drawn) fprintf(stderr, "\r%100s\r", "");
    if (lv2.csv) fclose(lv2.csv);
    if (!pst0) /* timings on stderr only (always: the benches read it); stdout is the same */
        fprintf(stderr, "geardyn periodic: %d points, %.3f s CPU\n", r->npoints, r->cpu_seconds);
    if (pst0) {
        free(rv);
        rc = gd_cli_report(&err);
        goto done;
    }
    if (a.plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_periodic(s, r, rv, &p, &err);
        if (pst) {
            /* nothing to plot (no point converged): no file, but the table that says
             * why is still printed before the error */
            free(rv);
            if (a.json) {
                cJSON *j = to_json(r, &recs, pv != NULL);
                gd_cli_print_json(stdout, j);
                cJSON_Delete(j);
            } else {
                print_table(r, &recs, pv != NULL);
            }
            fflush(stdout);
            rc = gd_cli_report(&err);
            goto done;
        }
        if ((rc = gd_cli_plot_finish(pst, p, &err, a.plot))) {
            free(rv);
            goto done;
        }
    }
    free(rv);
    if (a.out && (rc = write_out(a.out, r, &recs))) goto done;
    if (a.json) {
        cJSON *j = to_json(r, &recs, pv != NULL);
        gd_cli_print_json(stdout, j);
        cJSON_Delete(j);
    } else {
        print_table(r, &recs, pv != NULL);
    }
    rc = GD_EXIT_OK;
    {
        /* a run in which requested points failed is not a success: say which */
        int nf = 0, nt = 0, ne = 0;
        for (int i = 0; i < r->npoints; i++) {
            nf += !r->points[i].converged;
            nt += r->points[i].converged && r->points[i].harmonic_ok == 0;
            ne += r->points[i].converged && r->points[i].harmonic_ok < 0 &&
                  (opt.estimate || opt.adaptive) && r->points[i].method == GD_PER_HB;
        }
        if (ne)
            fprintf(stderr,
                    "geardyn periodic: %d of %d points have no truncation estimate (the "
                    "solution at 2 H + 1 failed or H is at its cap: see their note)\n",
                    ne, r->npoints);
        if (nt)
            fprintf(stderr,
                    "geardyn periodic: %d of %d points do not meet the harmonic truncation "
                    "tolerance (their truncation estimate says by how much)\n",
                    nt, r->npoints);
        if (nf) {
            fprintf(stderr, "geardyn periodic: %d of %d points did not converge:\n", nf,
                    r->npoints);
            for (int i = 0, shown = 0; i < r->npoints && shown < 5; i++)
                if (!r->points[i].converged) {
                    char at[300];
                    point_value(at, sizeof at, &r->points[i], pv && !a.freq ? ppath : NULL,
                                a.freq != NULL);
                    fprintf(stderr, "  %s: %s\n", at, r->points[i].reason);
                    shown++;
                }
            if (nf > 5) fprintf(stderr, "  ...\n");
            rc = GD_EXIT_FAIL;
        }
    }
    if (!a.json) {
        int li = 0; /* the first time-harmonic load (the model's order) */
        while (li < tm->spec.nloads && tm->spec.loads[li].law.kind != GD_LOAD_HARMONIC_TIME)
            li++;
        rattle_hint(file, r, pv && !a.freq ? ppath : NULL, a.freq != NULL, li, s, &tm->spec);
    }
done:
    /* the partial file goes once the complete files are in place, and on an error (which
     * writes nothing); only an interrupted run leaves it */
    if (partial[0]) remove(partial);
    if (made_dir && rc != GD_EXIT_OK && rc != GD_EXIT_FAIL) rmdir(a.out);
    gd_periodic_result_free(r);
    gd_cli_records_free(&recs);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    free(sp);
    free(pv);
    return rc;
}
