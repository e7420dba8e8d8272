/* geardyn: command-line front end. Each subcommand lives in its own cmd_*.c. */
#include <errno.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "geardyn/version.h"

typedef struct command {
    const char *name;
    int (*run)(int argc, char **argv);
    const char *summary;
} command;

static int cmd_version(int argc, char **argv)
{
    (void)argc;
    (void)argv;
    printf("geardyn %s\n", gd_version());
    return GD_EXIT_OK;
}

static const command COMMANDS[] = {
    /* {name, function, one-line summary}: keep in the order shown by --help */
    {"check", gd_cmd_check, "validate a model and summarise it"},
    {"modal", gd_cmd_modal, "natural frequencies, damping, whirl and energy of the modes"},
    {"static", gd_cmd_static, "static deflection, bearing reactions, mesh forces and misalignment"},
    {"campbell", gd_cmd_campbell, "Campbell diagram: modes over speed, critical speeds, stability"},
    {"frf", gd_cmd_frf,
     "frequency response (direct or modal), mesh and bearing forces, directional"},
    {"unbalance", gd_cmd_unbalance, "steady response to the model's unbalances over speed"},
    {"matrices", gd_cmd_matrices,
     "write the system matrices M, K, C, G at a speed (Matrix Market)"},
    {"transient", gd_cmd_transient,
     "time integration: TVMS, backlash, dampers, cams; records, contact losses, spectra"},
    {"periodic", gd_cmd_periodic,
     "periodic steady state: harmonic balance, continuation, Floquet stability, bifurcations"},
    {"mesh-stiffness", gd_cmd_mesh_stiffness,
     "contact ratios and time-varying mesh stiffness from gear geometry"},
    {"bearing-stiffness", gd_cmd_bearing_stiffness,
     "a rolling bearing of a table at a load: displacement, 5 x 5 stiffness (Hertz, per element)"},
    {"report", gd_cmd_report,
     "one self-contained HTML report: model drawing, modes, Campbell, FRFs, unbalance, TVMS"},
    {"study", gd_cmd_study, "parameter study: many cases, OpenMP, MPI, shards; CSV and HDF5 table"},
    {"testmodal", gd_cmd_testmodal,
     "modes from measured FRFs (UFF 58/58b, CSV): LSCF, peak picking"},
    {"correlate", gd_cmd_correlate,
     "model against measured modes and FRFs; model updating to measured frequencies"},
    {"version", cmd_version, "print the version"},
};

static void usage(FILE *f)
{
    fprintf(f, "usage: geardyn COMMAND [ARGS]\n\n"
               "Dynamics of geared rotor systems. Commands:\n");
    for (size_t i = 0; i < sizeof COMMANDS / sizeof COMMANDS[0]; i++)
        fprintf(f, "  %-16s %s\n", COMMANDS[i].name, COMMANDS[i].summary);
    fprintf(f, "\nRun 'geardyn COMMAND --help' for the options of a command.\n"
               "Model format: docs/model-format.md\n");
}

/* Every command prints through stdio: a failed write to stdout (a full disk, a closed
 * pipe's reader gone, /dev/full) leaves the stream's error flag set, and the last bytes
 * only leave at the flush, so the exit code is decided here (issue 38 M6). */
static int checked_exit(int code)
{
    errno = 0;
    if (fflush(stdout) == 0 && !ferror(stdout)) return code;
    int e = errno;
    fprintf(stderr,
            "geardyn: error: writing to the standard output failed%s%s: the output is "
            "incomplete (check the free space, or give --out FOLDER)\n",
            e ? ": " : "", e ? strerror(e) : "");
    return code == GD_EXIT_OK ? GD_EXIT_INPUT : code;
}

int main(int argc, char **argv)
{
    gd_cli_signals_install(); /* before OpenMP's or any other thread (signals.c) */
    if (argc < 2) {
        usage(stderr);
        return GD_EXIT_INPUT;
    }
    if (!strcmp(argv[1], "--help") || !strcmp(argv[1], "-h") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return checked_exit(GD_EXIT_OK);
    }
    if (!strcmp(argv[1], "--version")) return checked_exit(cmd_version(argc, argv));
    for (size_t i = 0; i < sizeof COMMANDS / sizeof COMMANDS[0]; i++)
        if (!strcmp(argv[1], COMMANDS[i].name))
            return checked_exit(COMMANDS[i].run(argc - 1, argv + 1));
    fprintf(stderr, "geardyn: unknown command '%s'\n", argv[1]);
    usage(stderr);
    return GD_EXIT_INPUT;
}
