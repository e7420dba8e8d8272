/* geardyn campbell MODEL --speeds FROM:TO:COUNT: Campbell diagram, critical speeds,
 * stability. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "operating_point.h"
#include "options.h"
#include "geardyn/campbell.h"
#include "geardyn/units.h"

typedef struct campbell_args {
    gd_campbell_options opt;
    const char *speeds, *coupling, *out, *orders, *plot, *maxf, *oper, *units;
    gd_cli_sets sets;
    int json;
    gd_cli_operating op;
} campbell_args;

#define F(m) offsetof(campbell_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("speeds", GD_CLI_STRING, F(speeds), "FROM:TO:COUNT",
               "reference speeds, units allowed: 0:12000rpm:121", .required = 1),
    GD_CLI_ROW("modes", GD_CLI_INT, F(opt.nmodes), "N|all",
               "elastic modes tracked (rigid-body modes are left out)",
               .def = "every mode up to 1.25 x the highest order at the top speed, at least 12",
               .lo = 1, .hi = 100000, .word = "all", .ival = 0),
    GD_CLI_ROW("orders", GD_CLI_STRING, F(orders), "LIST",
               "extra orders of the reference speed, comma-separated: 2,0.5"),
    GD_CLI_ROW("no-shaft-orders", GD_CLI_CLEAR, F(opt.shaft_orders), NULL,
               "leave out the 1x order of each shaft"),
    GD_CLI_ROW("no-mesh-orders", GD_CLI_CLEAR, F(opt.mesh_orders), NULL,
               "leave out the tooth-mesh orders (teeth x shaft speed)"),
    GD_CLI_ROW_EIG_METHOD(campbell_args, opt.method,
                          "auto (the cheaper by a measured cost model), dense (LAPACK) or sparse"),
    GD_CLI_ROW("undamped", GD_CLI_VALUE, F(opt.kind), NULL, "drop damping (gyroscopic terms stay)",
               .ival = GD_MODAL_UNDAMPED),
    GD_CLI_ROW("shift", GD_CLI_QUANTITY, F(opt.shift), "VALUE",
               "sparse shift below zero, e.g. 10Hz", .def = "automatic", .lo = GD_CLI_ABOVE_ZERO,
               .qty = GD_QTY_ANGULAR_SPEED, .example = "10Hz"),
    GD_CLI_ROW("max-frequency", GD_CLI_STRING, F(maxf), "F",
               "the plot's frequency axis ends at F (Hz; or 5000rpm, rad/s): modes and critical "
               "speeds wholly above it are left out of the plot"),
    GD_CLI_ROW_UNITS(campbell_args, units),
    GD_CLI_ROW("operating-range", GD_CLI_STRING, F(oper), "FROM:TO",
               "shade this speed range on the plot and give each critical speed's separation "
               "margin to it (e.g. 2500:3500rpm)"),
    GD_CLI_ROW_THREADS(campbell_args, opt.nthreads, "speeds"),
    GD_CLI_ROWS_OPERATING(campbell_args, op),
    GD_CLI_ROW_MODEL(campbell_args, coupling, sets),
    GD_CLI_ROW_JSON(campbell_args, json),
    GD_CLI_ROW_OUT(campbell_args, out,
                   "write DIR/campbell.csv (long form) and DIR/critical_speeds.csv"),
    GD_CLI_ROW_PLOT(campbell_args, plot),
    {0}};
static const gd_cli_command CMD = {
    .name = "campbell",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "Damped modes at every speed, tracked across speeds by mode shape (MAC), with whirl\n"
        "direction, dominant motion and log decrement; critical speeds where a mode meets an\n"
        "excitation order (1x of each shaft, --orders, tooth-mesh orders); instability onset.\n"};

#define PI 3.14159265358979323846

static double fd_hz(const gd_mode *md)
{
    return md->omega_d / (2 * PI);
}

static void print_tables(const gd_system *s, const gd_campbell_result *r, const gd_cli_units *u)
{
    int ns = r->nspeeds;
    printf("%s: %d DOFs, %d speeds, %d tracked modes (%s eigensolver), %d rigid-body mode(s) left "
           "out\n\n",
           s->model->file, s->ndof, ns, r->ntracks, r->sparse ? "sparse shift-invert" : "dense",
           r->nrigid);
    printf("damped natural frequencies (%s)\n%10s", gd_cli_freq_unit(u), gd_cli_speed_unit(u));
    for (int t = 0; t < r->ntracks; t++)
        printf(" %10s%d", "mode", r->tracks[t].id);
    printf("\n");
    for (int k = 0; k < ns; k++) {
        printf("%10.1f", gd_cli_speed_out(u, r->speeds[k]));
        for (int t = 0; t < r->ntracks; t++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + k];
            if (md->rigid_body < 0)
                printf(" %11s", "-");
            else
                printf(" %11.5g", gd_cli_freq_out(u, md->omega_d));
        }
        printf("\n");
    }
    char h0[32], h1[32];
    snprintf(h0, sizeof h0, "f_first(%s)", gd_cli_freq_unit(u));
    snprintf(h1, sizeof h1, "f_last(%s)", gd_cli_freq_unit(u));
    printf("\n%4s  %-9s %-10s %12s %12s %10s\n", "mode", "whirl", "dominant", h0, h1, "min logdec");
    for (int t = 0; t < r->ntracks; t++) {
        double f0 = NAN, f1 = NAN, ld = INFINITY;
        for (int k = 0; k < ns; k++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + k];
            if (md->rigid_body < 0) continue;
            if (isnan(f0)) f0 = gd_cli_freq_out(u, md->omega_d);
            f1 = gd_cli_freq_out(u, md->omega_d);
            if (!isnan(md->log_decrement) && md->log_decrement < ld) ld = md->log_decrement;
        }
        char b[3][32];
        printf("%4d  %-9s %-10s %s %s %s\n", r->tracks[t].id, gd_whirl_names[r->tracks[t].whirl],
               gd_motion_names[r->tracks[t].dominant_motion], gd_cli_num(b[0], 32, 12, 6, f0),
               gd_cli_num(b[1], 32, 12, 6, f1),
               gd_cli_num(b[2], 32, 10, 4, isfinite(ld) ? gd_cli_logdec_shown(ld) : NAN));
    }
    snprintf(h0, sizeof h0, "f(%s)", gd_cli_freq_unit(u));
    printf("\ncritical speeds\n%4s  %-32s %12s %12s\n", "mode", "order", gd_cli_speed_unit(u), h0);
    for (int c = 0; c < r->ncritical; c++)
        printf("%4d  %-32.32s %12.6g %12.6g\n", r->critical[c].mode,
               r->orders[r->critical[c].order].label, gd_cli_speed_out(u, r->critical[c].speed),
               gd_cli_freq_out(u, 2 * PI * r->critical[c].frequency_hz));
    if (!r->ncritical) printf("  (none in the speed range)\n");
    if (isnan(r->instability_onset))
        printf("\nstable over the whole speed range\n");
    else
        printf("\nUNSTABLE from %.6g %s (mode %d)\n", gd_cli_speed_out(u, r->instability_onset),
               gd_cli_speed_unit(u), r->instability_track);
}

static cJSON *result_json(const gd_system *s, const gd_campbell_result *r)
{
    int ns = r->nspeeds;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", s->model->file);
    cJSON_AddStringToObject(o, "eigensolver", r->sparse ? "sparse" : "dense");
    cJSON *sp = cJSON_AddArrayToObject(o, "speeds_rad_s");
    cJSON *rpm = cJSON_AddArrayToObject(o, "speeds_rpm");
    for (int k = 0; k < ns; k++) {
        cJSON_AddItemToArray(sp, cJSON_CreateNumber(r->speeds[k]));
        cJSON_AddItemToArray(rpm, cJSON_CreateNumber(r->speeds[k] * 30 / PI));
    }
    cJSON *modes = cJSON_AddArrayToObject(o, "modes");
    for (int t = 0; t < r->ntracks; t++) {
        cJSON *m = cJSON_CreateObject();
        cJSON_AddNumberToObject(m, "id", r->tracks[t].id);
        cJSON_AddStringToObject(m, "whirl", gd_whirl_names[r->tracks[t].whirl]);
        cJSON_AddStringToObject(m, "dominant_motion",
                                gd_motion_names[r->tracks[t].dominant_motion]);
        cJSON *f = cJSON_AddArrayToObject(m, "frequency_hz");
        cJSON *fn = cJSON_AddArrayToObject(m, "natural_frequency_hz");
        cJSON *z = cJSON_AddArrayToObject(m, "damping_ratio");
        cJSON *ld = cJSON_AddArrayToObject(m, "log_decrement");
        cJSON *wh = cJSON_AddArrayToObject(m, "whirl_by_speed");
        for (int k = 0; k < ns; k++) {
            const gd_mode *md = &r->modes[(size_t)t * ns + k];
            int ex = md->rigid_body >= 0;
            cJSON_AddItemToArray(f, gd_cli_json_number(ex ? fd_hz(md) : NAN));
            cJSON_AddItemToArray(fn, gd_cli_json_number(md->frequency_hz));
            cJSON_AddItemToArray(z, gd_cli_json_number(md->damping_ratio));
            cJSON_AddItemToArray(ld, gd_cli_json_number(md->log_decrement));
            cJSON_AddItemToArray(wh, ex ? cJSON_CreateString(gd_whirl_names[md->whirl])
                                        : cJSON_CreateNull());
        }
        cJSON_AddItemToArray(modes, m);
    }
    cJSON *cs = cJSON_AddArrayToObject(o, "critical_speeds");
    for (int c = 0; c < r->ncritical; c++) {
        cJSON *x = cJSON_CreateObject();
        cJSON_AddNumberToObject(x, "mode", r->critical[c].mode);
        cJSON_AddStringToObject(x, "order", r->orders[r->critical[c].order].label);
        cJSON_AddNumberToObject(x, "order_value", r->orders[r->critical[c].order].order);
        cJSON_AddNumberToObject(x, "speed_rpm", r->critical[c].speed_rpm);
        cJSON_AddNumberToObject(x, "frequency_hz", r->critical[c].frequency_hz);
        cJSON_AddItemToArray(cs, x);
    }
    cJSON_AddItemToObject(o, "instability_onset_rpm",
                          gd_cli_json_number(r->instability_onset * 30 / PI));
    return o;
}

static int write_csv(const gd_campbell_result *r, const char *dir)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "campbell.csv", &err);
    if (!f) goto fail;
    fprintf(f, "speed_rad_s,speed_rpm,mode,frequency_hz,natural_frequency_hz,damping_ratio,"
               "log_decrement,whirl,dominant_motion\n");
    for (int k = 0; k < r->nspeeds; k++)
        for (int t = 0; t < r->ntracks; t++) {
            const gd_mode *md = &r->modes[(size_t)t * r->nspeeds + k];
            if (md->rigid_body < 0) continue;
            fprintf(f, "%.10g,%.10g,%d,%.10g,%.10g,%.10g,%.10g,%s,%s\n", r->speeds[k],
                    r->speeds[k] * 30 / PI, r->tracks[t].id, fd_hz(md), md->frequency_hz,
                    md->damping_ratio, md->log_decrement, gd_whirl_names[md->whirl],
                    gd_motion_names[md->dominant_motion]);
        }
    if (gd_outdir_close(&od, f, "campbell.csv", &err)) goto fail;
    f = gd_outdir_open(&od, "critical_speeds.csv", &err);
    if (!f) goto fail;
    fprintf(f, "mode,order,order_value,speed_rpm,frequency_hz\n");
    for (int c = 0; c < r->ncritical; c++)
        fprintf(f, "%d,%s,%.10g,%.10g,%.10g\n", r->critical[c].mode,
                r->orders[r->critical[c].order].label, r->orders[r->critical[c].order].order,
                r->critical[c].speed_rpm, r->critical[c].frequency_hz);
    if (gd_outdir_close(&od, f, "critical_speeds.csv", &err)) goto fail;
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

static int parse_orders(const char *text, double **out, int *n)
{
    int cap = 1;
    for (const char *p = text; *p; p++)
        cap += *p == ',';
    double *v = malloc((size_t)cap * sizeof *v);
    if (!v) return 1;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", text);
    int k = 0;
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok;
         tok = strtok_r(NULL, ",", &save)) {
        char *end;
        double x = strtod(tok, &end);
        if (end == tok || *end || !(x > 0) || !isfinite(x)) {
            free(v);
            return 1;
        }
        v[k++] = x;
    }
    if (k == 0) {
        free(v);
        return 1;
    }
    *out = v;
    *n = k;
    return 0;
}

/* --max-frequency: a plain number is in Hz (the plot's unit), else a quantity with units
 * (Hz, rpm, rad/s). 0 on success. */
static int plot_frequency(const char *text, double *hz)
{
    char *end;
    double v = strtod(text, &end);
    gd_error why;
    if (end == text || *end) {
        if (gd_parse_quantity(text, GD_QTY_ANGULAR_SPEED, &v, &why)) return 1;
        v /= 2 * 3.14159265358979323846;
    }
    *hz = v;
    return !(v > 0 && isfinite(v));
}

/* --operating-range FROM:TO, speeds with units (a unit on TO alone applies to FROM);
 * rad/s out. 0 on success. */
static int plot_speed_range(const char *text, double *lo, double *hi)
{
    const char *colon = strchr(text, ':');
    if (!colon || strchr(colon + 1, ':')) return 1;
    char a[64], b[64];
    snprintf(a, sizeof a, "%.*s", (int)(colon - text < 63 ? colon - text : 63), text);
    snprintf(b, sizeof b, "%.63s", colon + 1);
    const char *unit = b;
    while (*unit && (strchr("0123456789.+-eE ", *unit)))
        unit++;
    char *end;
    strtod(a, &end);
    if (end != a && !*end && *unit) strncat(a, unit, sizeof a - strlen(a) - 1);
    gd_error why;
    if (gd_parse_quantity(a, GD_QTY_ANGULAR_SPEED, lo, &why) ||
        gd_parse_quantity(b, GD_QTY_ANGULAR_SPEED, hi, &why))
        return 1;
    return !(*lo >= 0 && *lo < *hi);
}

int gd_cmd_campbell(int argc, char **argv)
{
    const char *cmd = "campbell", *file;
    campbell_args a = {0};
    gd_campbell_options_init(&a.opt);
    a.opt.nmodes = -1; /* not given: chosen from the orders (gd_campbell_default_modes) */
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_campbell_options opt = a.opt;
    const char *speeds = a.speeds, *out = a.out, *orders = a.orders, *plot = a.plot, *maxf = a.maxf,
               *oper = a.oper;
    double *ord = NULL;
    if (orders && parse_orders(orders, &ord, &opt.norders))
        return gd_cli_usage_error(
            cmd, "--orders: '%s' is not a comma-separated list of positive numbers", orders);
    opt.orders = ord;
    gd_cli_units u = {.speed_rpm = 1, .freq_hz = 1}; /* rpm and Hz unless rad/s is written */
    if (gd_cli_units_parse(cmd, a.units, speeds, maxf, &u)) {
        free(ord);
        return GD_EXIT_INPUT;
    }
    gd_plot_campbell_options popt;
    gd_plot_campbell_options_init(&popt);
    popt.speed_rad_s = !u.speed_rpm;
    popt.frequency_rad_s = !u.freq_hz;
    if (maxf && plot_frequency(maxf, &popt.max_frequency_hz)) {
        free(ord);
        return gd_cli_usage_error(cmd,
                                  "--max-frequency: '%s' is not a frequency above zero "
                                  "(e.g. 2000 or 2000Hz, in Hz)",
                                  maxf);
    }
    if (oper && plot_speed_range(oper, &popt.operating_lo, &popt.operating_hi)) {
        free(ord);
        return gd_cli_usage_error(cmd,
                                  "--operating-range: '%s' is not FROM:TO with FROM < TO (e.g. "
                                  "2500:3500rpm)",
                                  oper);
    }
    double *sp = NULL;
    rc = gd_cli_parse_range(cmd, "--speeds", speeds, &sp, &opt.nspeeds);
    if (rc) {
        free(ord);
        return rc;
    }
    opt.speeds = sp;
    gd_error oerr;
    gd_error_clear(&oerr);
    if ((out && gd_outdir_check(out, &oerr)) || (plot && gd_plot_check_path(plot, NULL, &oerr))) {
        free(ord);
        free(sp);
        return gd_cli_report(&oerr);
    }
    gd_model *m;
    gd_system *s;
    rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s);
    if (rc) {
        free(ord);
        free(sp);
        return rc;
    }
    if ((rc = gd_cli_operating_apply(s, &a.op, -1, 0))) {
        gd_system_free(s);
        gd_model_free(m);
        free(ord);
        free(sp);
        return rc;
    }
    gd_campbell_result *r;
    gd_error err;
    gd_error_clear(&err);
    double limit = 0;
    if (opt.nmodes < 0 && gd_campbell_default_modes(s, &opt, &opt.nmodes, &limit, &err)) {
        rc = gd_cli_report(&err);
        gd_system_free(s);
        gd_model_free(m);
        free(ord);
        free(sp);
        return rc;
    }
    if (limit > 0 && !a.json)
        printf("tracking %d modes: every mode up to %.4g Hz (1.25 x the highest order at the top "
               "speed; --modes N to choose)\n",
               opt.nmodes, limit / (2 * PI));
    gd_blas_set_threads(1); /* the sweep is parallel over speeds instead */
    if (gd_campbell(s, &opt, &r, &err)) {
        rc = gd_cli_report(&err);
    } else {
        if (plot) {
            gd_plot *p = NULL;
            gd_status pst = gd_plot_campbell_opt(r, &popt, &p, &err);
            rc = gd_cli_plot_finish(pst, p, &err, plot);
        }
        if (out && rc == GD_EXIT_OK) rc = write_csv(r, out);
        /* the speeds without an equilibrium, as the sweep found them (not solved again) */
        int *none = r->no_equilibrium ? NULL : calloc((size_t)r->nspeeds + 1, sizeof *none);
        const int *bad = r->no_equilibrium ? r->no_equilibrium : none;
        if (rc == GD_EXIT_OK) gd_cli_operating_warn(r->speeds, bad, r->nspeeds);
        if (rc == GD_EXIT_OK) {
            if (a.json) {
                cJSON *o = result_json(s, r);
                gd_cli_operating_json(o, s, &a.op, r->speeds, bad, bad ? r->nspeeds : 0);
                gd_cli_print_json(stdout, o);
                cJSON_Delete(o);
            } else {
                print_tables(s, r, &u);
                gd_cli_operating_print(s, &a.op, 1);
            }
        }
        free(none);
        gd_campbell_free(r);
    }
    gd_system_free(s);
    gd_model_free(m);
    free(ord);
    free(sp);
    return rc;
}
