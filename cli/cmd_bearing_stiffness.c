/* geardyn bearing-stiffness TABLE.yaml: a rolling bearing of the user's table at a load,
 * its displacement and its 5 x 5 stiffness (geardyn/bearing_geometry.h,
 * geardyn/bearing_table.h; docs/bearings.md). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli.h"
#include "geardyn/bearing_geometry.h"
#include "geardyn/bearing_table.h"
#include "geardyn/units.h"
#include "options.h"

typedef struct bearing_args {
    const char *bearing, *load;
    int json;
} bearing_args;

#define F(m) offsetof(bearing_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("bearing", GD_CLI_STRING, F(bearing), "NAME", "the bearing of the table",
               .def = "the first"),
    GD_CLI_ROW("load", GD_CLI_STRING, F(load), "FX,FY,FZ,MX,MY",
               "the load on the inner ring: forces (N) and moments (N m), units allowed "
               "(e.g. 0,2kN,500N,0,0); fewer values: the rest 0",
               .def = "0"),
    GD_CLI_ROW_JSON(bearing_args, json),
    {0}};
static const gd_cli_command CMD = {
    .name = "bearing-stiffness",
    .args = "TABLE.yaml",
    .opts = OPTS,
    .about =
        "A rolling bearing from its geometry (a table of the user's own bearings) at a "
        "load:\nthe inner ring's displacement, the elements in contact and the 5 x 5 "
        "stiffness\n(x, y, z, rx, ry) from the Hertz contact of every element ([LimSingh1990], "
        "docs/bearings.md).\n"};

static const char *const NAMES[5] = {"x", "y", "z", "rx", "ry"};

static int parse_load(const char *text, double L[5])
{
    memset(L, 0, 5 * sizeof *L);
    if (!text) return 0;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", text);
    int k = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ","), k++) {
        if (k == 5)
            return gd_cli_usage_error(CMD.name, "--load: at most five values FX,FY,FZ,MX,MY");
        gd_error why;
        while (*tok == ' ')
            tok++;
        if (gd_parse_quantity(tok, k < 3 ? GD_QTY_FORCE : GD_QTY_TORQUE, &L[k], &why) ||
            !isfinite(L[k]))
            return gd_cli_usage_error(CMD.name, "--load: value %d '%s': %s (e.g. 2kN or 50N*m)",
                                      k + 1, tok, why.message);
    }
    return 0;
}

int gd_cmd_bearing_stiffness(int argc, char **argv)
{
    bearing_args a = {0};
    const char *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    double L[5], d[5], K[25], F[5], kn, n;
    if ((rc = parse_load(a.load, L))) return rc;
    gd_bearing_geometry g;
    char name[128];
    gd_error err;
    gd_error_clear(&err);
    int loaded = 0;
    if (gd_bearing_table_load(file, a.bearing, &g, name, sizeof name, &err) ||
        gd_bearing_contact_constant(&g, &kn, &n, &err) || gd_bearing_at_load(&g, L, d, K, &err) ||
        gd_bearing_forces(&g, d, F, NULL, &loaded, &err)) {
        if (!err.file[0]) snprintf(err.file, sizeof err.file, "%s", file);
        return gd_cli_report(&err);
    }
    const char *type = g.kind == GD_BEARING_BALL ? "ball" : "roller";
    if (a.json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "file", file);
        cJSON_AddStringToObject(o, "bearing", name);
        cJSON_AddStringToObject(o, "type", type);
        cJSON_AddNumberToObject(o, "elements", g.elements);
        cJSON_AddNumberToObject(o, "contact_constant", kn);
        cJSON_AddNumberToObject(o, "exponent", n);
        cJSON_AddItemToObject(o, "load", cJSON_CreateDoubleArray(L, 5));
        cJSON_AddItemToObject(o, "displacement", cJSON_CreateDoubleArray(d, 5));
        cJSON_AddNumberToObject(o, "loaded", loaded);
        cJSON *k = cJSON_AddArrayToObject(o, "stiffness");
        for (int i = 0; i < 5; i++) {
            double row[5];
            for (int j = 0; j < 5; j++)
                row[j] = K[i + 5 * j];
            cJSON_AddItemToArray(k, cJSON_CreateDoubleArray(row, 5));
        }
        gd_cli_print_json(stdout, o);
        cJSON_Delete(o);
        return GD_EXIT_OK;
    }
    printf("%s: bearing '%s' (%s, %d elements), contact constant %.6g N/m^%.4g\n\n", file, name,
           type, g.elements, kn, n);
    printf("load          Fx %g N, Fy %g N, Fz %g N, Mx %g N m, My %g N m\n", L[0], L[1], L[2],
           L[3], L[4]);
    printf("displacement  x %.6g um, y %.6g um, z %.6g um, rx %.6g mrad, ry %.6g mrad\n",
           d[0] * 1e6, d[1] * 1e6, d[2] * 1e6, d[3] * 1e3, d[4] * 1e3);
    printf("in contact    %d of %d elements\n\n", loaded, g.elements);
    printf("stiffness (N/m, N/rad, N m/rad)\n%4s", "");
    for (int j = 0; j < 5; j++)
        printf(" %13s", NAMES[j]);
    printf("\n");
    for (int i = 0; i < 5; i++) {
        printf("%4s", NAMES[i]);
        for (int j = 0; j < 5; j++)
            printf(" %13.6g", K[i + 5 * j]);
        printf("\n");
    }
    return GD_EXIT_OK;
}
