/* The law registry (include/geardyn/law_type.h): the built-in types, look-up, instance
 * defaults and the checks every instance passes before a problem is built from it. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/law_type.h"

const gd_law_type *const gd_law_types[] = {&gd_law_sfd,
                                           &gd_law_load,
                                           &gd_law_polynomial_spring,
                                           &gd_law_friction,
                                           &gd_law_rolling_bearing,
                                           &gd_law_rolling_bearing_5dof,
                                           &gd_law_journal_bearing,
                                           &gd_law_unilateral_spring,
                                           &gd_law_churning_drag,
                                           &gd_law_bearing_drag,
                                           &gd_law_synchro_cone,
                                           &gd_law_gear_release};
const int gd_nlaw_types = (int)(sizeof gd_law_types / sizeof gd_law_types[0]);

const gd_law_type *gd_law_type_find(const char *name)
{
    for (int i = 0; name && i < gd_nlaw_types; i++)
        if (!strcmp(gd_law_types[i]->name, name)) return gd_law_types[i];
    return NULL;
}

static int local_dofs(const gd_law_type *type)
{
    int per_node = type->ndirs > 0 ? type->ndirs : 1;
    return type->two_nodes ? 2 * per_node : per_node;
}

void gd_law_init(gd_law *law, const gd_law_type *type, const char *name)
{
    memset(law, 0, sizeof *law);
    law->type = type;
    snprintf(law->name, sizeof law->name, "%s", name ? name : (type ? type->name : ""));
    for (int j = 0; j < GD_LAW_MAX_DOFS; j++)
        law->dof[j] = -1;
    if (!type) return;
    int n = local_dofs(type);
    law->ndofs = n <= GD_LAW_MAX_DOFS ? n : GD_LAW_MAX_DOFS;
    for (int k = 0; k < type->nparams && k < GD_LAW_MAX_PARAMS; k++)
        law->value[k] = type->params[k].def;
}

int gd_law_param_index(const gd_law_type *type, const char *name)
{
    for (int k = 0; type && name && k < type->nparams; k++)
        if (!strcmp(type->params[k].name, name)) return k;
    return -1;
}

int gd_law_record_index(const gd_law_type *type, const char *name)
{
    for (int k = 0; type && name && k < type->nrecords; k++)
        if (!strcmp(type->records[k].name, name)) return k;
    return -1;
}

gd_status gd_law_type_validate(const gd_law_type *t, gd_error *err)
{
    const char *what = NULL;
    if (!t || !t->name || !t->name[0])
        what = "a law type needs a name";
    else if (!t->force)
        what = "a law type needs a force function";
    else if (t->nparams < 0 || t->nparams > GD_LAW_MAX_PARAMS || (t->nparams && !t->params))
        what = "a law type has at most GD_LAW_MAX_PARAMS parameters, listed in params";
    else if (t->ndirs < 0 || local_dofs(t) > GD_LAW_MAX_DOFS || (t->ndirs && !t->dirs))
        what = "a law type acts on at most GD_LAW_MAX_DOFS local DOFs, listed in dirs";
    else if (t->nterms < 0 || t->nterms > GD_LAW_MAX_TERMS || (t->nterms && !t->term))
        what = "a law type has at most GD_LAW_MAX_TERMS Jacobian terms, given by term";
    else if (t->nrecords < 0 || (t->nrecords && (!t->records || !t->record)))
        what = "a law type's records need names and a record function";
    else if (t->nswitches < 0 || t->nswitches > GD_LAW_MAX_SWITCHES ||
             (t->nswitches && (!t->switches || !t->mode_at || !t->mode_after || !t->switch_of)))
        what = "a law type has at most GD_LAW_MAX_SWITCHES switches, with switches, mode_at, "
               "mode_after and switch_of";
    for (int k = 0; !what && k < t->ndirs; k++)
        if (t->dirs[k] < 0 || t->dirs[k] > 5) what = "a law type's directions are 0 (x) to 5 (rz)";
    for (int k = 0; !what && k < t->nparams; k++)
        if (!t->params[k].name) what = "every parameter of a law type needs a name";
    if (!what) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "law type",
                        "fill the gd_law_type as include/geardyn/law_type.h describes", "%s%s%s",
                        what, t && t->name ? ": " : "", t && t->name ? t->name : "");
}

gd_status gd_law_check(const gd_law *law, gd_error *err)
{
    gd_status st = gd_law_type_validate(law ? law->type : NULL, err);
    if (st) return st;
    const gd_law_type *t = law->type;
    if (t->var_dofs ? (law->ndofs < 1 || law->ndofs > GD_LAW_MAX_DOFS)
                    : law->ndofs != local_dofs(t))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, law->name, "start from gd_law_init",
                            "law '%s' (%s) acts on %d local DOFs, not %d", law->name, t->name,
                            local_dofs(t), law->ndofs);
    for (int k = 0; k < t->nparams; k++) {
        const gd_law_param *p = &t->params[k];
        double v = law->value[k];
        const char *bad = NULL;
        if (isnan(v) && isnan(p->def))
            bad = "is required";
        else if (!isfinite(v))
            bad = "must be finite";
        else if (p->bound == GD_LAW_NONNEG && v < 0)
            bad = "must be >= 0";
        else if (p->bound == GD_LAW_POSITIVE && !(v > 0))
            bad = "must be > 0";
        if (bad)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, p->name, p->help ? p->help : "",
                                "law '%s' (%s): %s %s (got %g)", law->name, t->name, p->name, bad,
                                v);
    }
    if (t->check) {
        const char *field = "";
        char msg[256] = "";
        if (t->check(law, &field, msg, sizeof msg))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, field ? field : "",
                                "see the law's parameters in docs/laws.md", "law '%s' (%s): %s",
                                law->name, t->name, msg);
    }
    return GD_OK;
}

unsigned gd_law_flags(const gd_law *law)
{
    return law->type->instance_flags ? law->type->instance_flags(law) : law->type->flags;
}

int gd_law_nswitches(const gd_law *law)
{
    const gd_law_type *t = law->type;
    if (t->nswitches <= 0 || !t->switches) return 0;
    return (gd_law_flags(law) & GD_LAW_SMOOTH) ? 0 : t->nswitches;
}
