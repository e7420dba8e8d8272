/* A program using the installed geardyn as any other would: the umbrella header and
 * the flags from pkg-config or find_package, nothing from the source tree.
 * usage: consumer MODEL.yaml
 * prints "version <gd_version()>" and "omega2 <second natural frequency, rad/s>". */
#include <stdio.h>
#include <string.h>

#include <geardyn/geardyn.h>

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s MODEL.yaml\n", argv[0]);
        return 2;
    }
    /* the headers and the library linked are the same version */
    if (strcmp(gd_version(), GD_VERSION_STRING) != 0 ||
        GD_VERSION_NUMBER != GD_VERSION_MAJOR * 10000 + GD_VERSION_MINOR * 100 + GD_VERSION_PATCH) {
        fprintf(stderr, "headers %s, library %s\n", GD_VERSION_STRING, gd_version());
        return 1;
    }

    gd_error err;
    gd_model *model = NULL;
    gd_system *sys = NULL;
    gd_modal_result *modes = NULL;
    gd_modal_options opt;
    gd_modal_options_init(&opt);
    int rc = 1;
    if (gd_model_load(argv[1], &model, &err) != GD_OK ||
        gd_system_build(model, &sys, &err) != GD_OK ||
        gd_modal_solve(sys, &opt, &modes, &err) != GD_OK) {
        char msg[2048];
        gd_error_format(&err, msg, sizeof msg);
        fprintf(stderr, "%s", msg);
        goto done;
    }
    if (modes->nmodes < 2) {
        fprintf(stderr, "%d modes, expected at least 2\n", modes->nmodes);
        goto done;
    }
    printf("version %s\n", gd_version());
    printf("omega2 %.4f\n", modes->modes[1].omega_n);
    rc = 0;
done:
    gd_modal_free(modes);
    gd_system_free(sys);
    gd_model_free(model);
    return rc;
}
