/* --plot FILE.svg|FILE.html: checked before computing, written after. */
#include <stdio.h>
#include <string.h>

#include "cli.h"

/* The library names the file's option --plot; `report` takes it as --out. */
static int report_as(gd_error *err, const char *opt)
{
    if (!strcmp(err->field, "--plot")) snprintf(err->field, sizeof err->field, "%s", opt);
    return gd_cli_report(err);
}

int gd_cli_plot_check_as(const char *path, const char *opt)
{
    gd_error err;
    gd_error_clear(&err);
    if (gd_plot_check_path(path, NULL, &err)) return report_as(&err, opt);
    return GD_EXIT_OK;
}

int gd_cli_plot_check(const char *path)
{
    return gd_cli_plot_check_as(path, "--plot");
}

int gd_cli_plot_finish_as(gd_status st, gd_plot *p, gd_error *err, const char *path,
                          const char *opt)
{
    if (!st) {
        /* SIGINT/SIGTERM/SIGHUP, whichever thread takes them, wait until the file is
         * written and renamed (a few MB at most), so no FILE.tmp-PID-XXXXXX is left
         * behind (signals.c) */
        gd_cli_commit_begin();
        st = gd_plot_write(p, path, NULL, err);
        gd_cli_commit_end();
    }
    gd_plot_free(p);
    return st ? report_as(err, opt) : GD_EXIT_OK;
}

int gd_cli_plot_finish(gd_status st, gd_plot *p, gd_error *err, const char *path)
{
    return gd_cli_plot_finish_as(st, p, err, path, "--plot");
}
