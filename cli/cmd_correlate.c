/* geardyn correlate MODEL FILE...: the model against measurements (docs/testing.md): the
 * measured modes (a modes CSV, or LSCF on measured FRFs) paired with the model's, the
 * table of [MMT2018] Tables 4-5, the model's FRF overlaid on each measured one, and
 * with --update the parameters fitted to the measured frequencies. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "options.h"
#include "testdata_cli.h"
#include "geardyn/plot.h"

enum { MAX_UPDATE = 16 };

typedef struct correlate_args {
    const char *setup, *band, *plot;
    const char *update[MAX_UPDATE];
    int nupdate, order, json, fd_check, skip;
    gd_cli_sets sets;
} correlate_args;

#define F(m) offsetof(correlate_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("setup", GD_CLI_STRING, F(setup), "SETUP.yaml",
               "the test points' model nodes, `points: {2: gear32}` (default: point N is the "
               "model's node N)"),
    GD_CLI_ROW("update", GD_CLI_LIST, F(update), "KEY=LO:HI",
               "update the model value at KEY (a --set path; several joined by ',' move "
               "together) within LO:HI (SI) to the measured frequencies (repeatable)",
               .hi = MAX_UPDATE, .aux = F(nupdate)),
    GD_CLI_ROW("fd-check", GD_CLI_FLAG, F(fd_check), NULL,
               "with --update: also differentiate the frequencies by central differences "
               "beside the eigenvalue derivatives"),
    GD_CLI_ROW("band", GD_CLI_STRING, F(band), "F1:F2",
               "fit the measured FRFs from F1 to F2 Hz (default: every line above 0 Hz)"),
    GD_CLI_ROW("order", GD_CLI_INT, F(order), "N", "LSCF's highest model order", .def = "40",
               .lo = 2, .hi = 200),
    GD_CLI_ROW("skip-datasets", GD_CLI_FLAG, F(skip), NULL,
               "skip UFF datasets other than 58 (default: refuse them)"),
    GD_CLI_ROW_SET(correlate_args, sets),
    GD_CLI_ROW_JSON(correlate_args, json),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "write the table and the model's FRFs over the measured ones (.svg, .html, "
               ".png, .pdf)"),
    {0}};
static const gd_cli_command CMD = {
    .name = "correlate",
    .args = "MODEL.yaml FILE...",
    .missing = "give a model file and at least one test-data file",
    .opts = OPTS,
    .about =
        "Correlates a model with measurements (docs/testing.md). FILE is a modes CSV (measured\n"
        "natural frequencies) or measured FRFs (UFF 58/58b, FRF CSV), whose modes LSCF\n"
        "extracts. Measured modes are paired with the model's undamped modes by frequency and,\n"
        "where shapes were measured at several points, MAC; % difference = (f_model - f_test) /\n"
        "f_model x 100. --update fits model values to the measured frequencies (bounded\n"
        "Levenberg-Marquardt, sensitivities from the eigenvalue derivatives) and prints the\n"
        "values with their standard deviation and the table before and after.\n"};

static int parse_update(const char *text, gd_update_param *p, char *key, size_t size)
{
    const char *eq = strrchr(text, '=');
    if (!eq || eq == text || (size_t)(eq - text) >= size) return 0;
    snprintf(key, size, "%.*s", (int)(eq - text), text);
    char *e;
    p->lo = strtod(eq + 1, &e);
    if (e == eq + 1 || *e != ':') return 0;
    const char *q = e + 1;
    p->hi = strtod(q, &e);
    if (e == q || *e) return 0;
    p->key = key;
    return 1;
}

static cJSON *table_json(const gd_corr_table *t)
{
    cJSON *o = cJSON_CreateObject();
    cJSON *a = cJSON_AddArrayToObject(o, "pairs");
    for (int i = 0; i < t->npairs; i++) {
        const gd_corr_pair *q = &t->pairs[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "mode", i + 1);
        cJSON_AddNumberToObject(j, "test_hz", q->f_test);
        cJSON_AddNumberToObject(j, "model_hz", q->f_model);
        cJSON_AddNumberToObject(j, "model_mode", q->model + 1);
        cJSON_AddNumberToObject(j, "difference_pct", q->diff_pct);
        cJSON_AddItemToObject(j, "mac", gd_cli_json_number(q->mac));
        cJSON_AddItemToObject(j, "test_damping_ratio", gd_cli_json_number(q->zeta_test));
        cJSON_AddItemToArray(a, j);
    }
    cJSON_AddNumberToObject(o, "rms_difference_pct", t->rms_pct);
    return o;
}

static void table_print(const char *title, const gd_corr_table *t)
{
    printf("%s\n%-5s %12s %12s %8s %14s %8s\n", title, "mode", "test (Hz)", "model (Hz)", "model #",
           "difference (%)", "MAC");
    for (int i = 0; i < t->npairs; i++) {
        const gd_corr_pair *q = &t->pairs[i];
        printf("%-5d %12.2f %12.2f %8d %14.2f ", i + 1, q->f_test, q->f_model, q->model + 1,
               q->diff_pct);
        if (isfinite(q->mac))
            printf("%8.4f\n", q->mac);
        else
            printf("%8s\n", "-");
    }
    printf("rms difference %.3f %%\n", t->rms_pct);
}

typedef struct run {
    gd_model_source *src;
    gd_model *m;
    gd_system *s;
    gd_test_setup *setup;
    gd_testdata *td;
    const gd_td_function **frfs;
    int nfrf;
    gd_ema_result *ema;
    gd_measured_modes mm;
    int own_mm;
    gd_corr_table *t;
    double **mre, **mim;
    gd_update_result *up;
    gd_update_param par[MAX_UPDATE];
    char keys[MAX_UPDATE][256];
} run;

static void run_free(run *r)
{
    for (int o = 0; r->mre && o < r->nfrf; o++)
        free(r->mre[o]), free(r->mim[o]);
    free(r->mre), free(r->mim);
    gd_update_free(r->up);
    gd_corr_table_free(r->t);
    if (r->own_mm) gd_measured_modes_free(&r->mm);
    gd_ema_free(r->ema);
    free(r->frfs);
    gd_testdata_free(r->td);
    gd_test_setup_free(r->setup);
    gd_system_free(r->s);
    gd_model_free(r->m);
    gd_model_source_free(r->src);
}

static int compute(const correlate_args *a, char **files, int nfiles, run *r, gd_error *err)
{
    gd_load_options lo = gd_cli_load_options(&a->sets);
    for (int k = 0; k < a->nupdate; k++)
        if (!parse_update(a->update[k], &r->par[k], r->keys[k], sizeof r->keys[k]))
            return gd_cli_usage_error(CMD.name,
                                      "--update: write KEY=LO:HI with numbers in SI, e.g. "
                                      "--update 'bearings.*.k=5e7:2e8', not '%s'",
                                      a->update[k]);
    if (gd_model_source_load(files[0], &r->src, err) ||
        gd_model_source_model(r->src, &lo, &r->m, err) || gd_system_build(r->m, &r->s, err))
        return gd_cli_report(err);
    if (a->setup && gd_test_setup_load(a->setup, &r->setup, err)) return gd_cli_report(err);
    if (gd_testdata_read(nfiles - 1, (const char *const *)files + 1, a->skip, &r->td, err))
        return gd_cli_report(err);
    if (gd_cli_td_frfs(r->td, &r->frfs, &r->nfrf)) return GD_EXIT_FAIL;
    if (r->td->nmodes > 0) {
        if (gd_measured_from_testdata(r->td, &r->mm, err)) return gd_cli_report(err);
    } else {
        gd_ema_options eo;
        gd_ema_options_init(&eo);
        eo.max_order = a->order;
        int rc;
        if (a->band && (rc = gd_cli_parse_band(CMD.name, a->band, &eo))) return rc;
        if (gd_ema_lscf(r->nfrf, r->frfs, &eo, &r->ema, err) ||
            gd_measured_from_ema(r->s, r->setup, r->nfrf, r->frfs, r->ema, &r->mm, err))
            return gd_cli_report(err);
    }
    r->own_mm = 1;
    if (gd_correlate_modes(r->s, &r->mm, &r->t, err)) return gd_cli_report(err);
    /* the model's FRF at every measured one */
    r->mre = calloc((size_t)r->nfrf + 1, sizeof *r->mre);
    r->mim = calloc((size_t)r->nfrf + 1, sizeof *r->mim);
    if (!r->mre || !r->mim) return GD_EXIT_FAIL;
    for (int o = 0; o < r->nfrf; o++) {
        r->mre[o] = malloc((size_t)r->frfs[o]->n * sizeof(double));
        r->mim[o] = malloc((size_t)r->frfs[o]->n * sizeof(double));
        if (!r->mre[o] || !r->mim[o]) return GD_EXIT_FAIL;
        if (gd_correlate_frf(r->s, r->setup, r->frfs[o], (gd_frf_quantity)r->frfs[o]->quantity,
                             r->mre[o], r->mim[o], err))
            return gd_cli_report(err);
    }
    if (a->nupdate) {
        gd_update_options uo;
        gd_update_options_init(&uo);
        uo.nparams = a->nupdate;
        uo.params = r->par;
        uo.load = lo;
        uo.fd_check = a->fd_check;
        if (gd_model_update(r->src, &r->mm, &uo, &r->up, err)) return gd_cli_report(err);
    }
    return GD_EXIT_OK;
}

static void print_json(const correlate_args *a, const char *model, const run *r)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", model);
    cJSON_AddStringToObject(o, "measured_modes", r->ema ? "lscf" : "file");
    if (r->ema) cJSON_AddItemToObject(o, "modes", gd_cli_ema_json(r->ema, r->nfrf, r->frfs));
    cJSON_AddItemToObject(o, "correlation", table_json(r->t));
    cJSON *fa = cJSON_AddArrayToObject(o, "frfs");
    for (int q = 0; q < r->nfrf; q++) {
        const gd_td_function *f = r->frfs[q];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", f->name);
        cJSON_AddNumberToObject(j, "response_point", f->response_node);
        cJSON_AddStringToObject(j, "response_direction", gd_td_dir_name(f->response_dir));
        cJSON_AddNumberToObject(j, "reference_point", f->reference_node);
        cJSON_AddStringToObject(j, "reference_direction", gd_td_dir_name(f->reference_dir));
        cJSON_AddStringToObject(j, "quantity", gd_td_quantity_names[f->quantity]);
        cJSON_AddItemToObject(j, "frequency_hz", cJSON_CreateDoubleArray(f->freq_hz, f->n));
        cJSON_AddItemToObject(j, "test_re", cJSON_CreateDoubleArray(f->re, f->n));
        cJSON_AddItemToObject(j, "test_im", cJSON_CreateDoubleArray(f->im, f->n));
        cJSON_AddItemToObject(j, "model_re", cJSON_CreateDoubleArray(r->mre[q], f->n));
        cJSON_AddItemToObject(j, "model_im", cJSON_CreateDoubleArray(r->mim[q], f->n));
        cJSON_AddItemToArray(fa, j);
    }
    if (r->up) {
        cJSON *u = cJSON_AddObjectToObject(o, "update");
        cJSON *pa = cJSON_AddArrayToObject(u, "parameters");
        for (int k = 0; k < r->up->nparams; k++) {
            cJSON *j = cJSON_CreateObject();
            cJSON_AddStringToObject(j, "key", r->par[k].key);
            cJSON_AddNumberToObject(j, "lower", r->par[k].lo);
            cJSON_AddNumberToObject(j, "upper", r->par[k].hi);
            cJSON_AddNumberToObject(j, "initial", r->up->initial[k]);
            cJSON_AddNumberToObject(j, "updated", r->up->value[k]);
            cJSON_AddItemToObject(j, "std_dev", gd_cli_json_number(r->up->sigma[k]));
            cJSON *sv = cJSON_AddArrayToObject(j, "df_dp_hz");
            cJSON *sf = r->up->sens_fd ? cJSON_AddArrayToObject(j, "df_dp_hz_differences") : NULL;
            for (int i = 0; i < r->up->ntargets; i++) {
                cJSON_AddItemToArray(sv, cJSON_CreateNumber(r->up->sens[i * r->up->nparams + k]));
                if (sf)
                    cJSON_AddItemToArray(
                        sf, cJSON_CreateNumber(r->up->sens_fd[i * r->up->nparams + k]));
            }
            cJSON_AddItemToArray(pa, j);
        }
        cJSON_AddNumberToObject(u, "iterations", r->up->iterations);
        cJSON_AddBoolToObject(u, "at_bound", r->up->at_bound);
        cJSON_AddItemToObject(u, "before", table_json(r->up->before));
        cJSON_AddItemToObject(u, "after", table_json(r->up->after));
    }
    (void)a;
    gd_cli_print_json(stdout, o);
    cJSON_Delete(o);
}

static void print_text(const char *model, const run *r)
{
    if (r->ema) {
        gd_cli_ema_print(r->ema, "measured modes by lscf");
        printf("\n");
    }
    char title[512];
    snprintf(title, sizeof title, "%s against %s:", model,
             r->ema ? "the modes of the measured FRFs" : "the measured frequencies");
    table_print(title, r->t);
    if (!r->up) return;
    printf("\nupdating: %d iterations%s\n", r->up->iterations,
           r->up->at_bound ? " (a parameter ends on a bound)" : "");
    printf("%-40s %12s %12s %12s\n", "parameter", "initial", "updated", "std dev");
    for (int k = 0; k < r->up->nparams; k++)
        printf("%-40s %12.5g %12.5g %12.3g\n", r->par[k].key, r->up->initial[k], r->up->value[k],
               r->up->sigma[k]);
    if (r->up->sens_fd) {
        printf("\nsensitivities df/dp (Hz per SI unit) at the start: eigenvalue derivative | "
               "central difference\n");
        for (int i = 0; i < r->up->ntargets; i++) {
            printf("mode %-3d", i + 1);
            for (int k = 0; k < r->up->nparams; k++)
                printf("  %12.5g | %12.5g", r->up->sens[i * r->up->nparams + k],
                       r->up->sens_fd[i * r->up->nparams + k]);
            printf("\n");
        }
    }
    printf("\n");
    table_print("after updating:", r->up->after);
}

int gd_cmd_correlate(int argc, char **argv)
{
    correlate_args a = {0};
    a.order = 40;
    char **files;
    int nfiles;
    int rc = gd_cli_parse_files(&CMD, argc, argv, &a, 2, &files, &nfiles);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    if (a.plot && (rc = gd_cli_plot_check(a.plot))) return rc;
    gd_error err;
    gd_error_clear(&err);
    run r;
    memset(&r, 0, sizeof r);
    rc = compute(&a, files, nfiles, &r, &err);
    if (!rc && a.plot) {
        gd_plot *p = NULL;
        gd_status pst =
            gd_plot_correlation(r.nfrf, r.frfs, (const double *const *)r.mre,
                                (const double *const *)r.mim, r.up ? r.up->after : r.t, &p, &err);
        rc = gd_cli_plot_finish(pst, p, &err, a.plot);
    }
    if (!rc) {
        if (a.json)
            print_json(&a, files[0], &r);
        else
            print_text(files[0], &r);
    }
    run_free(&r);
    return rc;
}
