/* --plot FILE.svg|FILE.html: checked before computing, written after. */
#include "cli.h"

int gd_cli_plot_check(const char *path)
{
    gd_error err;
    gd_error_clear(&err);
    if (gd_plot_check_path(path, NULL, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
}

int gd_cli_plot_finish(gd_status st, gd_plot *p, gd_error *err, const char *path)
{
    if (!st) st = gd_plot_write(p, path, NULL, err);
    gd_plot_free(p);
    return st ? gd_cli_report(err) : GD_EXIT_OK;
}
