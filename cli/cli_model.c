#include <string.h>

#include "cli.h"
#include "geardyn/units.h"

int gd_cli_add_set(const char *cmd, gd_cli_sets *sets, const char *arg)
{
    if (sets->nset == GD_CLI_MAX_SET)
        return gd_cli_usage_error(cmd, "--set: at most %d options; edit a copy of the file",
                                  GD_CLI_MAX_SET);
    sets->set[sets->nset++] = arg;
    return 0;
}

gd_load_options gd_cli_load_options(const gd_cli_sets *sets)
{
    gd_load_options lo;
    gd_load_options_init(&lo);
    if (sets) {
        lo.nset = sets->nset;
        lo.set = sets->set;
    }
    return lo;
}

/* "x,y,rz" into a GD_DOF_BIT mask. */
static int parse_dofs(const char *list, unsigned *mask, gd_error *err)
{
    *mask = 0;
    const char *p = list;
    while (*p) {
        size_t len = strcspn(p, ", ");
        int found = -1;
        for (int k = 0; k < GD_NODE_DOFS && len; k++)
            if (strlen(gd_dof_names[k]) == len && !strncmp(p, gd_dof_names[k], len)) found = k;
        if (len && found < 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "--dofs",
                                "list DOFs from x, y, z, rx, ry, rz, e.g. --dofs x,y,rz",
                                "unknown DOF '%.*s'", (int)len, p);
        if (found >= 0) *mask |= GD_DOF_BIT(found);
        p += len;
        p += strspn(p, ", ");
    }
    if (!*mask)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--dofs", "e.g. --dofs x,y,rz",
                            "no DOFs listed");
    return 0;
}

int gd_cli_load(const char *path, const gd_cli_sets *sets, const char *coupling, gd_model **model,
                gd_system **sys)
{
    gd_error err;
    gd_error_clear(&err);
    *model = NULL;
    *sys = NULL;
    int level = -1;
    if (coupling) {
        for (int i = 0; i < 3; i++)
            if (!strcmp(coupling, gd_coupling_names[i])) level = i;
        if (level < 0) {
            gd_error_set(&err, GD_EINPUT, "", 0, 0, "--coupling",
                         "use torsional, lateral-torsional or full", "unknown coupling level '%s'",
                         coupling);
            return gd_cli_report(&err);
        }
    }
    gd_load_options lo = gd_cli_load_options(sets);
    if (gd_model_load_opts(path, &lo, model, &err)) return gd_cli_report(&err);
    if (level >= 0) gd_model_set_coupling(*model, (gd_coupling)level);
    unsigned mask = 0;
    if (sets && sets->dofs &&
        (parse_dofs(sets->dofs, &mask, &err) || gd_model_restrict_dofs(*model, mask, &err))) {
        gd_model_free(*model);
        *model = NULL;
        return gd_cli_report(&err);
    }
    if (gd_system_build(*model, sys, &err)) {
        gd_model_free(*model);
        *model = NULL;
        return gd_cli_report(&err);
    }
    return GD_EXIT_OK;
}

int gd_cli_parse_speed(const char *cmd, const char *text, double *out)
{
    gd_error why;
    if (gd_parse_quantity(text, GD_QTY_ANGULAR_SPEED, out, &why)) {
        gd_cli_usage_error(cmd, "--speed: %s (e.g. --speed 3000rpm or --speed 314.16)",
                           why.message);
        return 1;
    }
    if (*out < 0) {
        gd_cli_usage_error(cmd, "--speed: give a speed of zero or more");
        return 1;
    }
    return 0;
}
