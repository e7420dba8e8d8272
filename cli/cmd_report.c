/* geardyn report MODEL --out report.html: the whole study in one file. */
#include <stdlib.h>
#include <string.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "operating_point.h"
#include "options.h"
#include "geardyn/report.h"

typedef struct report_args {
    gd_report_options opt;
    const char *out, *speeds, *speed, *coupling, *runup;
    gd_cli_sets sets;
    gd_cli_operating op; /* the laws' operating point, as modal, campbell, frf, unbalance */
} report_args;

/* --run-up-revolutions N: a number (not only whole) from 16 to 1e5. */
static int parse_revolutions(const char *cmd, const char *text, void *field)
{
    char *end;
    double *v = field;
    *v = strtod(text, &end);
    if (end == text || *end || !(*v >= 16) || !(*v <= 1e5))
        return gd_cli_usage_error(cmd,
                                  "--run-up-revolutions: '%s' is not a number from 16 "
                                  "(two blocks of 8 turns) to 1e5",
                                  text);
    return 0;
}

#define F(m) offsetof(report_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("out", GD_CLI_STRING, F(out), "FILE.html",
               "the report, FILE.html, FILE.svg, FILE.png or FILE.pdf", .required = 1),
    GD_CLI_ROW("speeds", GD_CLI_STRING, F(speeds), "FROM:TO:COUNT", "Campbell and unbalance speeds",
               .def = "41 from 0 to twice the model's speed, or to 10000 rpm"),
    GD_CLI_ROW("speed", GD_CLI_STRING, F(speed), "VALUE", "reference speed of the modes and FRFs",
               .def = "the model's"),
    GD_CLI_ROW("modes", GD_CLI_INT, F(opt.nmodes), "N", "modes tracked in the Campbell diagram",
               .def = "8", .lo = 1, .hi = 1000),
    GD_CLI_ROW("freq-points", GD_CLI_INT, F(opt.nfreq), "N", "FRF frequencies", .def = "400",
               .lo = 2, .hi = 100000),
    GD_CLI_ROW_THREADS(report_args, opt.nthreads, "the points of the sweeps"),
    GD_CLI_ROW("run-up", GD_CLI_STRING, F(runup), "FROM:TO",
               "a run-up through this ramp (e.g. 0:6000rpm): a transient forced by the "
               "unbalances, transmission errors and laws, order-tracked into a waterfall and "
               "order cuts"),
    GD_CLI_ROW("run-up-revolutions", GD_CLI_CALL, F(opt.runup_revolutions), "N",
               "its length in turns of the reference shaft at the mean speed (more: a slower "
               "ramp, a sharper peak)",
               .def = "200", .call = parse_revolutions),
    GD_CLI_ROWS_OPERATING(report_args, op),
    GD_CLI_ROW_COUPLING(report_args, coupling),
    GD_CLI_ROW_SET(report_args, sets),
    {0}};
static const gd_cli_command CMD = {
    .name = "report",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "One self-contained HTML file (opens offline; FILE.svg, FILE.png or FILE.pdf give static\n"
        "versions, the PDF one page per section) with the model drawn to scale and summarised,\n"
        "its modes (shapes, 3-D whirl, strain energy), the Campbell diagram (critical speeds,\n"
        "log decrement), the FRFs of the mesh and bearing forces, the unbalance response, the\n"
        "mesh stiffness of every mesh computed from its geometry and, with --run-up, a run-up\n"
        "waterfall; the numbers of each section download as CSV from the page (docs/plots.md).\n"};

int gd_cmd_report(int argc, char **argv)
{
    const char *cmd = "report", *file;
    report_args a = {0};
    gd_report_options_init(&a.opt);
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_report_options opt = a.opt;
    const char *out = a.out, *speeds = a.speeds, *speed = a.speed, *runup = a.runup;
    if (runup) { /* FROM:TO as a two-point range of speeds (FROM takes TO's unit) */
        char buf[200];
        double *r = NULL;
        int n = 0;
        if (strlen(runup) > 150) return gd_cli_usage_error(cmd, "--run-up: value too long");
        snprintf(buf, sizeof buf, "%s:2", runup);
        int rc0 = gd_cli_parse_range(cmd, "--run-up", buf, &r, &n);
        if (rc0) return rc0;
        opt.runup_from = r[0];
        opt.runup_to = r[1];
        free(r);
        if (opt.runup_from == opt.runup_to)
            return gd_cli_usage_error(cmd, "--run-up: FROM equals TO: give a ramp");
    }
    rc = gd_cli_plot_check_as(out, "--out");
    if (rc) return rc;
    double *sp = NULL;
    if (speeds && (rc = gd_cli_parse_range(cmd, "--speeds", speeds, &sp, &opt.nspeeds))) return rc;
    opt.speeds = sp;
    gd_model *m;
    gd_system *s;
    if ((rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s))) {
        free(sp);
        return rc;
    }
    if (speed && gd_cli_parse_speed(cmd, speed, &opt.speed)) {
        rc = GD_EXIT_INPUT;
    } else if ((rc = gd_cli_operating_apply(s, &a.op, opt.speed >= 0 ? opt.speed : m->speed, 1))) {
        /* the laws (rolling, journal bearings) linearised about the static equilibrium,
         * as the analyses' own commands do: at q = 0 a bearing with clearance holds
         * nothing and every mode of the report was rigid-body */
    } else {
        gd_blas_set_threads(1); /* the sweeps are parallel over points instead */
        gd_error err;
        gd_error_clear(&err);
        gd_plot *p = NULL;
        gd_status st = gd_report_build(s, &opt, &p, &err);
        rc = gd_cli_plot_finish_as(st, p, &err, out, "--out");
        if (rc == GD_EXIT_OK) printf("%s\n", out);
    }
    gd_system_free(s);
    gd_model_free(m);
    free(sp);
    return rc;
}
