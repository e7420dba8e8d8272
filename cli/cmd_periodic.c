/* geardyn periodic MODEL --speeds FROM:TO:COUNT: periodic steady state by harmonic
 * balance or shooting with continuation and Floquet stability (docs/periodic.md). */
#include <cblas.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli.h"
#include "geardyn/periodic.h"
#include "transient_record.h"

static const char *CMD = "periodic";

static const char USAGE[] =
    "usage: geardyn periodic MODEL.yaml --speeds FROM:TO:COUNT [--harmonics H|auto]\n"
    "                        [--subharmonic N] [--record WHAT]... [--parameter "
    "PATH=FROM:TO:COUNT]\n"
    "                        [--both-directions] [--sequential] [--no-stability] [--tol TOL]\n"
    "                        [--harmonic-tol TOL] [--max-harmonics H] [--no-estimate]\n"
    "                        [--samples N] [--coupling LEVEL] [--set PATH=VALUE]... [--json]\n"
    "                        [--out DIR] [--plot FILE.svg|FILE.html] [--quiet]\n"
    "                        [--method hb|shooting|auto] [--shoot-rtol TOL] [--shoot-budget S]\n"
    "                        [--shoot-dense-max N] [--floquet auto|dense|krylov]\n\n"
    "Periodic steady state by harmonic balance (alternating frequency-time on every\n"
    "nonlinear and time-varying law of `transient`), continued by pseudo-arclength over\n"
    "the speed (through folds: a hysteresis loop gives several points per speed), with\n"
    "Floquet multipliers and the bifurcations found on the way.\n\n"
    "  --speeds FROM:TO:COUNT  reference speeds, units allowed (required); each requested\n"
    "                    speed is solved exactly wherever the branch crosses it\n"
    "  --method M        hb (default): harmonic balance; shooting: Newton on the period map\n"
    "                    of transient's integrator (every law transient has, cams with\n"
    "                    include_acceleration included; natural continuation, one point\n"
    "                    per speed); auto: the cheaper for the model by a measured cost\n"
    "                    (the choice and the costs are printed)\n"
    "  --shoot-rtol TOL  shooting: the integrator's relative tolerance (default 1e-9)\n"
    "  --shoot-dense-max N  shooting: the dense monodromy up to N states (default 64);\n"
    "                    above, Newton-Krylov on monodromy-vector products\n"
    "  --shoot-budget S  shooting: CPU seconds per point before it stops, not converged,\n"
    "                    saying why (default 30; 0: no limit)\n"
    "  --harmonics H|auto  harmonics of the period; auto (default): from the least H that\n"
    "                    holds every excitation, doubled per point until every record's\n"
    "                    peak-to-peak and harmonic amplitudes agree with those at 2 H to\n"
    "                    --harmonic-tol; a fixed H is checked against 2 H the same way\n"
    "  --harmonic-tol TOL  truncation tolerance, relative (default 0.01)\n"
    "  --max-harmonics H   cap of H (default: the largest whose workspace fits in half\n"
    "                    the memory)\n"
    "  --no-estimate     with a fixed H: no solution at 2 H, no truncation estimate\n"
    "  --subharmonic N   solutions of period N times the fundamental (default 1)\n"
    "  --record WHAT     as for transient: NODE.DOF[:disp|vel|speed], ratio:A/B,\n"
    "                    mesh:NAME[:force|deflection|stiffness|state], sfd:BEARING[:fx|fy|ecc],\n"
    "                    law:NAME[:RECORD]\n"
    "  --parameter PATH=FROM:TO:COUNT  continue in a model value (SI numbers, the --set\n"
    "                    path syntax) at the first speed of --speeds instead of the speed\n"
    "  --both-directions also the run from the end back to the start\n"
    "  --sequential      no arclength: one solution per speed from the previous one (jumps\n"
    "                    at folds, as a slow run-up)\n"
    "  --no-stability    skip the Floquet multipliers (and bifurcations)\n";
/* the rest (one literal may hold 4095 characters in ISO C) */
static const char USAGE2[] =
    "  --floquet M       auto (default: dense up to 300 states), dense or krylov (the 8\n"
    "                    largest multipliers from monodromy-vector products)\n"
    "  --tol TOL         Newton's relative residual (default 1e-10)\n"
    "  --samples N       AFT time samples per period (default 4 (H + 1), power of 2)\n"
    "  --coupling LEVEL  torsional | lateral-torsional | full\n"
    "  --set PATH=VALUE  change a value of the model file (repeatable)\n"
    "  --json            one JSON object on stdout: points, bifurcations\n"
    "  --out DIR         DIR/periodic.csv, DIR/harmonics.csv, DIR/bifurcations.csv\n"
    "  --plot FILE       peak-to-peak and harmonics of each record over the branch (stable\n"
    "                    solid, unstable dashed), bifurcations marked, Floquet multipliers:\n"
    "                    FILE.svg or FILE.html (interactive, self-contained; docs/plots.md)\n"
    "  --quiet           no progress line (it is shown on stderr only on a terminal)\n\n"
    "Exit status 1 when a requested point did not converge (after writing what did, with\n"
    "a summary on stderr).\n";

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
    for (long i = 0; i < n; i++)
        (*vals)[i] = n > 1 ? a + (b - a) * (double)i / (double)(n - 1) : a;
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
        if (!p->converged || p->reason[0]) cJSON_AddStringToObject(o, "reason", p->reason);
        if (p->stable >= 0)
            cJSON_AddBoolToObject(o, "stable", p->stable);
        else
            cJSON_AddNullToObject(o, "stable");
        cJSON_AddItemToObject(o, "floquet_multiplier_max_abs", gd_cli_json_number(p->mu_max));
        if (p->stable >= 0)
            cJSON_AddStringToObject(o, "floquet_method", p->floquet_krylov ? "krylov" : "dense");
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
    cJSON_AddNumberToObject(root, "cpu_seconds", r->cpu_seconds);
    return root;
}

static void print_table(const gd_periodic_result *r, const gd_cli_records *recs, int param)
{
    /* harmonic balance by default says nothing (the table's layout is unchanged) */
    if (r->method != GD_PER_HB || r->method_note[0])
        printf("method: %s\n", r->method_note[0] ? r->method_note : gd_per_kind_name(r->method));
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
    printf("\n%d continuation steps, %.3f s\n", r->steps, r->cpu_seconds);
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

/* Points as they converge: appended to DIR/periodic.partial.csv (flushed per point, so an
 * interrupted run keeps what it finished; removed once the complete files are in place)
 * and a progress line with the estimated time left on a terminal. */
typedef struct live {
    FILE *csv;
    const gd_cli_records *recs;
    int tty, drawn, nfail;
    struct timespec t0;
} live;

static void on_point(const gd_periodic_point *p, int index, double progress, void *user)
{
    live *l = user;
    if (!p->converged) l->nfail++;
    if (l->csv) {
        csv_rows(l->csv, index, p, l->recs);
        fflush(l->csv);
    }
    if (!l->tty) return;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    double el = (double)(t.tv_sec - l->t0.tv_sec) + 1e-9 * (double)(t.tv_nsec - l->t0.tv_nsec);
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

enum {
    OPT_BOTH = 0x700,
    OPT_SEQ,
    OPT_NOSTAB,
    OPT_FLOQUET,
    OPT_TOL,
    OPT_SAMPLES,
    OPT_PARAM,
    OPT_HTOL,
    OPT_MAXH,
    OPT_NOEST,
    OPT_QUIET,
    OPT_METHOD,
    OPT_SRTOL,
    OPT_SBUDGET,
    OPT_SDENSE
};

/* Where no stable periodic orbit came out (a point unstable or not converged), the
 * response may have none (a rattling train): name the `transient` run that gives its
 * per-period statistics and Poincare verdict (docs/transient.md). */
static void rattle_hint(const char *model, const gd_periodic_result *r)
{
    int first = -1, n = 0;
    for (int i = 0; i < r->npoints; i++)
        if (!r->points[i].converged || r->points[i].stable == 0) {
            if (first < 0) first = i;
            n++;
        }
    if (first < 0) return;
    const gd_periodic_point *p = &r->points[first];
    printf("\n%d of %d points have no stable periodic orbit (unstable or not converged; "
           "first at %.6g rad/s). Where the response has none (rattle, a torus), its "
           "statistics over many periods and the Poincare verdict come from\n"
           "  geardyn transient %s --speed %.6g --periods 100 --settle 200rev\n"
           "with the same --set, --dofs and --coupling options (docs/transient.md).\n",
           n, r->npoints, p->speed, model, p->speed);
}

int gd_cmd_periodic(int argc, char **argv)
{
    static const struct option opts[] = {{"speeds", required_argument, 0, 's'},
                                         {"harmonics", required_argument, 0, 'H'},
                                         {"subharmonic", required_argument, 0, 'N'},
                                         {"record", required_argument, 0, 'r'},
                                         {"parameter", required_argument, 0, OPT_PARAM},
                                         {"both-directions", no_argument, 0, OPT_BOTH},
                                         {"sequential", no_argument, 0, OPT_SEQ},
                                         {"no-stability", no_argument, 0, OPT_NOSTAB},
                                         {"floquet", required_argument, 0, OPT_FLOQUET},
                                         {"tol", required_argument, 0, OPT_TOL},
                                         {"harmonic-tol", required_argument, 0, OPT_HTOL},
                                         {"samples", required_argument, 0, OPT_SAMPLES},
                                         {"max-harmonics", required_argument, 0, OPT_MAXH},
                                         {"no-estimate", no_argument, 0, OPT_NOEST},
                                         {"quiet", no_argument, 0, OPT_QUIET},
                                         {"method", required_argument, 0, OPT_METHOD},
                                         {"shoot-rtol", required_argument, 0, OPT_SRTOL},
                                         {"shoot-budget", required_argument, 0, OPT_SBUDGET},
                                         {"shoot-dense-max", required_argument, 0, OPT_SDENSE},
                                         {"coupling", required_argument, 0, 'c'},
                                         {"json", no_argument, 0, 'j'},
                                         {"out", required_argument, 0, 'o'},
                                         GD_CLI_SET_OPTION,
                                         GD_CLI_PLOT_OPTION,
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *speeds = NULL, *coupling = NULL, *out = NULL, *param_text = NULL, *plot = NULL;
    const char *records[64];
    int nrec = 0, json = 0, c, quiet = 0, fixed_h = 0;
    long lv;
    gd_cli_sets sets = {0};
    gd_periodic_options opt;
    gd_periodic_options_init(&opt);
    opt.adaptive = 1;        /* the default: H from the excitations, raised until it holds */
    opt.shoot_budget = 30.0; /* a point never runs for minutes in silence */
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        switch (c) {
        case 's':
            speeds = optarg;
            break;
        case 'H':
            if (!strcmp(optarg, "auto")) {
                opt.adaptive = 1;
                break;
            }
            if (gd_cli_parse_count(optarg, 1, 1 << 20, &lv))
                return gd_cli_usage_error(CMD,
                                          "--harmonics: expected a whole H >= 1 or auto, "
                                          "got '%s'",
                                          optarg);
            opt.harmonics = (int)lv;
            opt.adaptive = 0;
            fixed_h = 1;
            break;
        case OPT_MAXH:
            if (gd_cli_parse_count(optarg, 1, 1 << 20, &lv))
                return gd_cli_usage_error(CMD, "--max-harmonics: expected a whole H >= 1, got '%s'",
                                          optarg);
            opt.max_harmonics = (int)lv;
            break;
        case OPT_NOEST:
            opt.estimate = 0;
            break;
        case OPT_QUIET:
            quiet = 1;
            break;
        case OPT_FLOQUET:
            opt.floquet = !strcmp(optarg, "dense")    ? GD_FLOQUET_DENSE
                          : !strcmp(optarg, "krylov") ? GD_FLOQUET_KRYLOV
                          : !strcmp(optarg, "auto")   ? GD_FLOQUET_AUTO
                                                      : -1;
            if (opt.floquet < 0)
                return gd_cli_usage_error(
                    CMD, "--floquet: expected auto, dense or krylov, got '%s'", optarg);
            break;
        case OPT_METHOD:
            if (!strcmp(optarg, "hb") || !strcmp(optarg, "harmonic-balance"))
                opt.kind = GD_PER_HB;
            else if (!strcmp(optarg, "shooting"))
                opt.kind = GD_PER_SHOOTING;
            else if (!strcmp(optarg, "auto"))
                opt.kind = GD_PER_AUTO;
            else
                return gd_cli_usage_error(CMD, "--method: expected hb, shooting or auto, got '%s'",
                                          optarg);
            break;
        case OPT_SRTOL: {
            char *end;
            double v = strtod(optarg, &end);
            if (*end || !(v >= 1e-14 && v < 1e-2))
                return gd_cli_usage_error(CMD,
                                          "--shoot-rtol: expected a tolerance in [1e-14, 1e-2), "
                                          "got '%s'",
                                          optarg);
            opt.shoot_rtol = v;
            break;
        }
        case OPT_SDENSE:
            if (gd_cli_parse_count(optarg, 1, 1 << 20, &lv))
                return gd_cli_usage_error(CMD,
                                          "--shoot-dense-max: expected a whole number of "
                                          "states >= 1, got '%s'",
                                          optarg);
            opt.shoot_dense_max = (int)lv;
            break;
        case OPT_SBUDGET: {
            char *end;
            double v = strtod(optarg, &end);
            if (*end || !(v >= 0 && v < 1e9))
                return gd_cli_usage_error(CMD,
                                          "--shoot-budget: expected CPU seconds >= 0 (0: no "
                                          "limit), got '%s'",
                                          optarg);
            opt.shoot_budget = v;
            break;
        }
        case 'N':
            if (gd_cli_parse_count(optarg, 1, 1000, &lv))
                return gd_cli_usage_error(
                    CMD, "--subharmonic: expected a whole number 1..1000 (period N T), got '%s'",
                    optarg);
            opt.subharmonic = (int)lv;
            break;
        case 'r':
            if (nrec == 64) return gd_cli_usage_error(CMD, "at most 64 --record options");
            records[nrec++] = optarg;
            break;
        case OPT_PARAM:
            param_text = optarg;
            break;
        case OPT_BOTH:
            opt.both_directions = 1;
            break;
        case OPT_SEQ:
            opt.method = GD_PER_SEQUENTIAL;
            break;
        case OPT_NOSTAB:
            opt.stability = 0;
            break;
        case OPT_TOL:
        case OPT_HTOL: {
            char *end;
            double v = strtod(optarg, &end);
            if (*end || !(v >= 1e-15 && v < 1))
                return gd_cli_usage_error(CMD,
                                          "%s: expected a number in [1e-15, 1) (a tolerance "
                                          "below 1e-15 is unreachable in double precision), "
                                          "got '%s'",
                                          c == OPT_TOL ? "--tol" : "--harmonic-tol", optarg);
            if (c == OPT_TOL)
                opt.tol = v;
            else
                opt.harmonic_tol = v;
            break;
        }
        case OPT_SAMPLES:
            if (gd_cli_parse_count(optarg, 4, GD_PERIODIC_MAX_SAMPLES, &lv))
                return gd_cli_usage_error(CMD,
                                          "--samples: expected a whole number from 4 to %d "
                                          "(2^20), got '%s'",
                                          GD_PERIODIC_MAX_SAMPLES, optarg);
            opt.samples = (int)lv;
            break;
        case 'c':
            coupling = optarg;
            break;
        case GD_CLI_OPT_SET:
            if (gd_cli_add_set(CMD, &sets, optarg)) return GD_EXIT_INPUT;
            break;
        case 'j':
            json = 1;
            break;
        case 'o':
            out = optarg;
            break;
        case GD_CLI_OPT_PLOT:
            plot = optarg;
            break;
        case 'h':
            fputs(USAGE, stdout);
            fputs(USAGE2, stdout);
            return GD_EXIT_OK;
        default:
            return gd_cli_option_error(CMD, c, argv, optind);
        }
    }
    if (optind != argc - 1) return gd_cli_usage_error(CMD, "give exactly one model file");
    if (!opt.estimate && !fixed_h)
        return gd_cli_usage_error(CMD, "--no-estimate needs a fixed --harmonics H (auto always "
                                       "compares H with 2 H)");
    if (!speeds) return gd_cli_usage_error(CMD, "--speeds FROM:TO:COUNT is required");
    if (opt.samples && opt.samples < 2 * opt.harmonics + 2)
        return gd_cli_usage_error(CMD, "--samples %d cannot resolve %d harmonics (give >= %d)",
                                  opt.samples, opt.harmonics, 2 * opt.harmonics + 2);
    if (param_text && coupling)
        return gd_cli_usage_error(CMD, "--parameter reloads the model: give the coupling "
                                       "with --set instead of --coupling");
    double *sp = NULL, *pv = NULL;
    int nsp = 0, npv = 0, rc;
    char ppath[256], partial[1100] = "";
    int made_dir = 0;
    if ((rc = gd_cli_parse_range(CMD, "--speeds", speeds, &sp, &nsp))) return rc;
    if (param_text && (rc = parse_param(param_text, ppath, sizeof ppath, &pv, &npv))) {
        free(sp);
        return rc;
    }
    gd_error err;
    gd_error_clear(&err);
    if ((out && gd_outdir_check_writable(out, &err)) ||
        (plot && gd_plot_check_path(plot, NULL, &err))) {
        free(sp);
        free(pv);
        return gd_cli_report(&err);
    }
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_transient_model *tm = NULL;
    gd_periodic_result *r = NULL;
    gd_cli_records recs = {0};
    if ((rc = gd_cli_load(argv[optind], &sets, coupling, &m, &s))) goto done;
    if (gd_transient_model_build(s, &tm, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    for (int k = 0; k < nrec; k++)
        if ((rc = gd_cli_parse_records(CMD, s, tm, records[k], &recs))) goto done;
    if (!nrec && (rc = gd_cli_default_records(s, tm, &recs))) goto done;
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
    gd_load_options lo = gd_cli_load_options(&sets);
    openblas_set_num_threads(1); /* small dense blocks: threads cost more than they give */
    rebuild_data rd = {argv[optind], &lo, ppath};
    gd_periodic_param prm = {rebuild, &rd, ppath, sp[0]};
    live lv2 = {0};
    lv2.recs = &recs;
    lv2.tty = !quiet && isatty(2);
    clock_gettime(CLOCK_MONOTONIC, &lv2.t0);
    if (out) {
        made_dir = mkdir(out, 0777) == 0; /* the partial file goes in it */
        snprintf(partial, sizeof partial, "%s/periodic.partial.csv", out);
        if ((lv2.csv = fopen(partial, "w"))) csv_header(lv2.csv);
    }
    opt.on_point = on_point;
    opt.user = &lv2;
    gd_status pst0 = gd_periodic_run(s, &tm->spec, pv ? &prm : NULL, pv ? pv : sp, pv ? npv : nsp,
                                     &opt, rv, recs.n, &r, &err);
    if (lv2.drawn) fprintf(stderr, "\r%100s\r", "");
    if (lv2.csv) fclose(lv2.csv);
    if (pst0) {
        free(rv);
        rc = gd_cli_report(&err);
        goto done;
    }
    if (plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_periodic(s, r, rv, &p, &err);
        if (pst) {
            /* nothing to plot (no point converged): no file, but the table that says
             * why is still printed before the error */
            free(rv);
            if (json) {
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
        if ((rc = gd_cli_plot_finish(pst, p, &err, plot))) {
            free(rv);
            goto done;
        }
    }
    free(rv);
    if (out && (rc = write_out(out, r, &recs))) goto done;
    if (json) {
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
                  (opt.estimate || opt.adaptive) && r->method == GD_PER_HB;
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
                    fprintf(stderr, "  %.6g rad/s: %s\n", r->points[i].speed, r->points[i].reason);
                    shown++;
                }
            if (nf > 5) fprintf(stderr, "  ...\n");
            rc = GD_EXIT_FAIL;
        }
    }
    if (!json) rattle_hint(argv[optind], r);
done:
    /* the partial file goes once the complete files are in place, and on an error (which
     * writes nothing); only an interrupted run leaves it */
    if (partial[0]) remove(partial);
    if (made_dir && rc != GD_EXIT_OK && rc != GD_EXIT_FAIL) rmdir(out);
    gd_periodic_result_free(r);
    gd_cli_records_free(&recs);
    gd_transient_model_free(tm);
    gd_system_free(s);
    gd_model_free(m);
    free(sp);
    free(pv);
    return rc;
}
