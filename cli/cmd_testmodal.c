/* geardyn testmodal FILE...: modal parameters from measured FRFs (UFF 58/58b or the FRF
 * CSV): LSCF with its stabilisation diagram and LSFD shapes, or peak picking. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "options.h"
#include "testdata_cli.h"
#include "geardyn/plot.h"

typedef struct testmodal_args {
    const char *band, *plot;
    int order, method, json, skip;
} testmodal_args;

#define F(m) offsetof(testmodal_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("band", GD_CLI_STRING, F(band), "F1:F2",
               "fit the lines from F1 to F2 Hz (default: every line above 0 Hz)"),
    GD_CLI_ROW("order", GD_CLI_INT, F(order), "N", "LSCF's highest model order", .def = "40",
               .lo = 2, .hi = 200),
    GD_CLI_ROW("method", GD_CLI_CHOICE, F(method), "lscf|peaks",
               "LSCF with a stabilisation diagram, or peak picking with half-power damping",
               .def = "lscf", .word = "lscf|peaks"),
    GD_CLI_ROW("skip-datasets", GD_CLI_FLAG, F(skip), NULL,
               "skip UFF datasets other than 58 (default: refuse them)"),
    GD_CLI_ROW_JSON(testmodal_args, json),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "write the stabilisation diagram (.svg, .html, .png, .pdf)"),
    {0}};
static const gd_cli_command CMD = {
    .name = "testmodal",
    .args = "FILE...",
    .missing = "give at least one test-data file (UFF 58/58b or FRF CSV)",
    .opts = OPTS,
    .about = "Modes from measured FRFs (docs/testing.md): natural frequencies, damping ratios\n"
             "and, where several points were measured, shapes. LSCF fits one common denominator\n"
             "to every FRF at model orders 1..N; the poles stable over most of the upper orders\n"
             "are the modes, their residues (shapes) fitted by least squares (LSFD). The FRFs\n"
             "must share one frequency axis.\n"};

int gd_cmd_testmodal(int argc, char **argv)
{
    testmodal_args a = {0};
    a.order = 40;
    char **files;
    int nfiles;
    int rc = gd_cli_parse_files(&CMD, argc, argv, &a, 1, &files, &nfiles);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_ema_options opt;
    gd_ema_options_init(&opt);
    opt.max_order = a.order;
    if (a.band && (rc = gd_cli_parse_band(CMD.name, a.band, &opt))) return rc;
    if (a.plot && a.method == 1)
        return gd_cli_usage_error(CMD.name, "--plot draws LSCF's stabilisation diagram: leave "
                                            "out --method peaks");
    if (a.plot && (rc = gd_cli_plot_check(a.plot))) return rc;
    gd_error err;
    gd_error_clear(&err);
    gd_testdata *td;
    if (gd_testdata_read(nfiles, (const char *const *)files, a.skip, &td, &err))
        return gd_cli_report(&err);
    const gd_td_function **frfs;
    int n;
    rc = gd_cli_td_frfs(td, &frfs, &n);
    if (!rc && n == 0) {
        gd_error_set(&err, GD_EINPUT, files[0], 0, 0, "",
                     "give UFF 58 FRFs (function type 4) or an FRF CSV",
                     "no FRF in the files (%d functions, %d measured frequencies)", td->nfunctions,
                     td->nmodes);
        rc = gd_cli_report(&err);
    }
    gd_ema_result *r = NULL;
    if (!rc) {
        gd_status st = a.method == 1 ? gd_ema_peaks(n, frfs, &opt, &r, &err)
                                     : gd_ema_lscf(n, frfs, &opt, &r, &err);
        if (st) rc = gd_cli_report(&err);
    }
    if (!rc && a.plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_stabilisation(r, n, frfs, &p, &err);
        rc = gd_cli_plot_finish(pst, p, &err, a.plot);
    }
    if (!rc) {
        const char *method = a.method == 1 ? "peaks" : "lscf";
        if (a.json) {
            cJSON *o = cJSON_CreateObject();
            cJSON_AddStringToObject(o, "method", method);
            cJSON *fl = cJSON_AddArrayToObject(o, "files");
            for (int i = 0; i < nfiles; i++)
                cJSON_AddItemToArray(fl, cJSON_CreateString(files[i]));
            cJSON_AddNumberToObject(o, "frfs", n);
            cJSON *b = cJSON_AddArrayToObject(o, "band_hz");
            cJSON_AddItemToArray(b, cJSON_CreateNumber(r->band_lo_hz));
            cJSON_AddItemToArray(b, cJSON_CreateNumber(r->band_hi_hz));
            cJSON_AddNumberToObject(o, "lines", r->nlines);
            cJSON_AddItemToObject(o, "modes", gd_cli_ema_json(r, n, frfs));
            if (r->npoles) {
                cJSON_AddNumberToObject(o, "max_order", r->max_order);
                cJSON *sd = cJSON_AddArrayToObject(o, "stabilisation");
                for (int i = 0; i < r->npoles; i++) {
                    cJSON *q = cJSON_CreateObject();
                    cJSON_AddNumberToObject(q, "order", r->poles[i].order);
                    cJSON_AddNumberToObject(q, "frequency_hz", r->poles[i].frequency_hz);
                    cJSON_AddNumberToObject(q, "damping_ratio", r->poles[i].damping_ratio);
                    char stt[2] = {r->poles[i].status, 0};
                    cJSON_AddStringToObject(q, "status", stt);
                    cJSON_AddItemToArray(sd, q);
                }
            }
            gd_cli_print_json(stdout, o);
            cJSON_Delete(o);
        } else {
            gd_cli_ema_print(r, method);
        }
    }
    gd_ema_free(r);
    free(frfs);
    gd_testdata_free(td);
    return rc;
}
