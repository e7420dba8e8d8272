/* geardyn report MODEL --out report.html: the whole study in one file. */
#include <cblas.h>
#include <getopt.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/report.h"

static const char USAGE[] =
    "usage: geardyn report MODEL.yaml --out FILE.html [--speeds FROM:TO:COUNT] [--speed VALUE]\n"
    "                      [--modes N] [--freq-points N] [--threads N] [--coupling LEVEL]\n"
    "                      [--run-up FROM:TO [--run-up-revolutions N]] [--set PATH=VALUE]...\n\n"
    "One self-contained HTML file (opens offline; FILE.svg, FILE.png or FILE.pdf give static\n"
    "versions, the PDF one page per section) with the\n"
    "model drawn to scale and summarised, its modes (shapes, 3-D whirl, strain energy), the\n"
    "Campbell diagram (critical speeds, log decrement), the FRFs of the mesh and bearing\n"
    "forces, the unbalance response, the mesh stiffness of every mesh computed from its\n"
    "geometry and, with --run-up, a run-up waterfall; the numbers of each section download as CSV "
    "from the page (docs/plots.md).\n\n"
    "  --out FILE              the report, FILE.html, FILE.svg, FILE.png or FILE.pdf (required)\n"
    "  --speeds FROM:TO:COUNT  Campbell and unbalance speeds (default 41 from 0 to twice the\n"
    "                          model's speed, or to 10000 rpm)\n"
    "  --speed VALUE           reference speed of the modes and FRFs (default: the model's)\n"
    "  --modes N               modes tracked in the Campbell diagram (default 8)\n"
    "  --freq-points N         FRF frequencies (default 400)\n"
    "  --threads N             parallel threads of the sweeps (default: all cores)\n"
    "  --run-up FROM:TO        a run-up through this ramp (e.g. 0:6000rpm): a transient\n"
    "                          forced by the unbalances, transmission errors and laws,\n"
    "                          order-tracked into a waterfall and order cuts\n"
    "  --run-up-revolutions N  its length in turns of the reference shaft at the mean\n"
    "                          speed (default 200; more: a slower ramp, a sharper peak)\n"
    "  --coupling LEVEL        torsional | lateral-torsional | full\n"
    "  --set PATH=VALUE        change a value of the model file (repeatable;\n"
    "                          docs/model-format.md)\n";

int gd_cmd_report(int argc, char **argv)
{
    static const struct option opts[] = {{"out", required_argument, 0, 'o'},
                                         {"speeds", required_argument, 0, 's'},
                                         {"speed", required_argument, 0, 'S'},
                                         {"modes", required_argument, 0, 'n'},
                                         {"freq-points", required_argument, 0, 'F'},
                                         {"threads", required_argument, 0, 't'},
                                         {"coupling", required_argument, 0, 'c'},
                                         {"run-up", required_argument, 0, 'R'},
                                         {"run-up-revolutions", required_argument, 0, 'N'},
                                         GD_CLI_SET_OPTION,
                                         {"help", no_argument, 0, 'h'},
                                         {0, 0, 0, 0}};
    const char *cmd = "report", *out = NULL, *speeds = NULL, *speed = NULL, *coupling = NULL,
               *runup = NULL;
    gd_cli_sets sets = {0};
    gd_report_options opt;
    gd_report_options_init(&opt);
    long v;
    int c;
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        switch (c) {
        case 'o':
            out = optarg;
            break;
        case 's':
            speeds = optarg;
            break;
        case 'S':
            speed = optarg;
            break;
        case 'n':
            if (gd_cli_parse_count(optarg, 1, 1000, &v))
                return gd_cli_usage_error(cmd, "--modes: '%s' is not a whole number from 1 to 1000",
                                          optarg);
            opt.nmodes = (int)v;
            break;
        case 'F':
            if (gd_cli_parse_count(optarg, 2, 100000, &v))
                return gd_cli_usage_error(
                    cmd, "--freq-points: '%s' is not a whole number from 2 to 100000", optarg);
            opt.nfreq = (int)v;
            break;
        case 't':
            if (gd_cli_parse_threads(cmd, optarg, &opt.nthreads)) return GD_EXIT_INPUT;
            break;
        case 'c':
            coupling = optarg;
            break;
        case 'R':
            runup = optarg;
            break;
        case 'N': {
            char *end;
            opt.runup_revolutions = strtod(optarg, &end);
            if (end == optarg || *end || !(opt.runup_revolutions >= 16) ||
                !(opt.runup_revolutions <= 1e5))
                return gd_cli_usage_error(cmd,
                                          "--run-up-revolutions: '%s' is not a number from 16 "
                                          "(two blocks of 8 turns) to 1e5",
                                          optarg);
            break;
        }
        case GD_CLI_OPT_SET:
            if (gd_cli_add_set(cmd, &sets, optarg)) return GD_EXIT_INPUT;
            break;
        case 'h':
            fputs(USAGE, stdout);
            return GD_EXIT_OK;
        default:
            return gd_cli_option_error(cmd, c, argv, optind);
        }
    }
    if (optind != argc - 1) return gd_cli_usage_error(cmd, "give exactly one model file");
    if (!out) return gd_cli_usage_error(cmd, "--out FILE.html is required");
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
    int rc = gd_cli_plot_check_as(out, "--out");
    if (rc) return rc;
    double *sp = NULL;
    if (speeds && (rc = gd_cli_parse_range(cmd, "--speeds", speeds, &sp, &opt.nspeeds))) return rc;
    opt.speeds = sp;
    gd_model *m;
    gd_system *s;
    if ((rc = gd_cli_load(argv[optind], &sets, coupling, &m, &s))) {
        free(sp);
        return rc;
    }
    if (speed && gd_cli_parse_speed(cmd, speed, &opt.speed)) {
        rc = GD_EXIT_INPUT;
    } else {
        openblas_set_num_threads(1); /* the sweeps are parallel over points instead */
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
