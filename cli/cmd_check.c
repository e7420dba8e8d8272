/* geardyn check MODEL: validate a model and summarise it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/planetary.h"
#include "options.h"

typedef struct check_args {
    const char *coupling;
    int json;
    gd_cli_sets sets;
} check_args;

static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW_MODEL(check_args, coupling, sets), GD_CLI_ROW_JSON(check_args, json), {0}};
static const gd_cli_command CMD = {
    .name = "check",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about = "Validates a model and prints a summary: nodes, DOFs, elements, meshes, and the mass\n"
             "and polar inertia of each shaft with everything on it.\n"};

/* The input member's speed ratio to the reference shaft (0 for a differential). */
static double input_ratio(const gd_model *m, const gd_planetary *g,
                          const gd_planetary_kinematics *k)
{
    return k->input < 0 ? 0 : m->shafts[m->nodes[g->member[k->input].node].shaft].speed_ratio;
}

/* +1 when the sun turns counterclockwise relative to the carrier at the model's speeds
 * (the sense [ParkerLin2004]'s phases take), -1 clockwise; +1 when it does not turn. */
static int sun_direction(const gd_model *m, const gd_planetary *g)
{
    double rel = m->shafts[m->nodes[g->member[GD_PLANETARY_SUN].node].shaft].speed_ratio -
                 m->shafts[m->nodes[g->member[GD_PLANETARY_CARRIER].node].shaft].speed_ratio;
    return rel < 0 ? -1 : 1;
}

/* Each mesh kind's contact ratio (tooth geometry), stiffness, law and each planet's
 * phase (docs/planetary.md, "Meshes from geometry", "Meshes as laws"). */
static void print_planetary_meshes(const gd_model *m, const gd_planetary *g)
{
    static const char *const KIND[2] = {"sun-planet ", "ring-planet"};
    for (int k = 0; k < 2; k++) {
        const gd_planetary_mesh_law *l = &g->mesh_law[k];
        printf("  %s k %.6g N/m", KIND[k], g->mesh_stiffness[k]);
        if (g->contact_ratio[k] > 0) printf(", contact ratio %.4f", g->contact_ratio[k]);
        if (l->active)
            printf(", law: %s%s", l->tvms ? "TVMS" : "constant k", l->backlash ? ", backlash" : "");
        if (g->teeth[0] > 0) {
            printf(", phases");
            for (int n = 0; n < g->nplanets; n++)
                printf(" %.4f", gd_planetary_mesh_phase(g, k, n, sun_direction(m, g)));
        }
        printf("\n");
    }
}

/* Each planetary set: members, spacing, ratios, mesh frequency, assembly
 * (docs/planetary.md). */
static void print_planetary(const gd_model *m)
{
    for (int i = 0; i < m->nplanetary; i++) {
        const gd_planetary *g = &m->planetary[i];
        gd_planetary_kinematics k;
        gd_planetary_kinematics_of(g, &k);
        printf("\nplanetary set '%s': %d planets, %s, %s held\n", g->name, g->nplanets,
               g->equally_spaced ? "equally spaced" : "spaced as given",
               g->held < 0 ? "no member" : gd_planetary_member_names[g->held]);
        printf("  members    sun '%s', ring '%s', carrier '%s'\n", m->nodes[g->member[0].node].name,
               m->nodes[g->member[1].node].name, m->nodes[g->member[2].node].name);
        printf("  angles     ");
        for (int n = 0; n < g->nplanets; n++)
            printf("%s%.6g", n ? ", " : "", g->planet_angle[n] * 180 / M_PI);
        printf(" deg\n");
        if (k.input < 0) {
            printf("  ratios     differential (no member held): Z_r / Z_s = %.6g%s\n",
                   k.teeth_ratio, k.has_teeth ? "" : " (pitch radii)");
        } else {
            printf("  ratios     per unit %s speed: sun %.6g, ring %.6g, carrier %.6g, planets "
                   "%.6g (Z_r / Z_s = %.6g%s)\n",
                   gd_planetary_member_names[k.input], k.speed[0], k.speed[1], k.speed[2],
                   k.planet_speed, k.teeth_ratio, k.has_teeth ? "" : ", from pitch radii");
            if (k.has_teeth) {
                double order = k.mesh_order * fabs(input_ratio(m, g, &k));
                printf("  mesh       %.6g per %s revolution, order %.6g of the reference shaft: "
                       "%.6g Hz at %g rpm\n",
                       k.mesh_order, gd_planetary_member_names[k.input], order,
                       order * m->speed / (2 * M_PI), m->speed * 30 / M_PI);
            }
        }
        if (!k.has_teeth) {
            printf("  assembly   not checked: give the teeth (`teeth: {sun, ring, planet}`)\n");
        } else {
            printf("  assembly   (Z_s + Z_r) psi_n / 360 deg =");
            for (int n = 0; n < g->nplanets; n++)
                printf(" %.6g", k.assembly[n]);
            printf(": %s", k.assembles ? "whole numbers, the set assembles" : "NOT whole numbers");
            if (g->equally_spaced) printf("; Z_s / N = %.6g", k.sun_teeth_per_planet);
            printf("\n");
        }
        print_planetary_meshes(m, g);
    }
}

static cJSON *planetary_json(const gd_model *m)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < m->nplanetary; i++) {
        const gd_planetary *g = &m->planetary[i];
        gd_planetary_kinematics k;
        gd_planetary_kinematics_of(g, &k);
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", g->name);
        cJSON_AddNumberToObject(j, "planets", g->nplanets);
        cJSON_AddBoolToObject(j, "equally_spaced", g->equally_spaced);
        cJSON *ang = cJSON_AddArrayToObject(j, "angles_deg");
        for (int n = 0; n < g->nplanets; n++)
            cJSON_AddItemToArray(ang, cJSON_CreateNumber(g->planet_angle[n] * 180 / M_PI));
        if (g->held >= 0)
            cJSON_AddStringToObject(j, "held", gd_planetary_member_names[g->held]);
        else
            cJSON_AddNullToObject(j, "held");
        cJSON *w = cJSON_AddObjectToObject(j, "speed_per_input");
        for (int q = 0; q < GD_PLANETARY_NMEMBERS; q++)
            cJSON_AddItemToObject(w, gd_planetary_member_names[q], gd_cli_json_number(k.speed[q]));
        cJSON_AddItemToObject(w, "planets", gd_cli_json_number(k.planet_speed));
        cJSON_AddItemToObject(j, "teeth_ratio", gd_cli_json_number(k.teeth_ratio));
        double order = k.mesh_order * fabs(input_ratio(m, g, &k));
        cJSON_AddItemToObject(j, "mesh_order", gd_cli_json_number(order));
        cJSON_AddItemToObject(j, "mesh_frequency_hz",
                              gd_cli_json_number(order * m->speed / (2 * M_PI)));
        cJSON *as = cJSON_AddArrayToObject(j, "assembly");
        for (int n = 0; n < g->nplanets; n++)
            cJSON_AddItemToArray(as, gd_cli_json_number(k.assembly[n]));
        if (k.assembles < 0)
            cJSON_AddNullToObject(j, "assembles");
        else
            cJSON_AddBoolToObject(j, "assembles", k.assembles);
        cJSON *ms = cJSON_AddArrayToObject(j, "meshes");
        for (int q = 0; q < 2; q++) {
            cJSON *e = cJSON_CreateObject();
            cJSON_AddStringToObject(e, "kind", q ? "ring-planet" : "sun-planet");
            cJSON_AddItemToObject(e, "stiffness", gd_cli_json_number(g->mesh_stiffness[q]));
            if (g->contact_ratio[q] > 0)
                cJSON_AddItemToObject(e, "contact_ratio", gd_cli_json_number(g->contact_ratio[q]));
            else
                cJSON_AddNullToObject(e, "contact_ratio");
            cJSON_AddBoolToObject(e, "law", g->mesh_law[q].active);
            cJSON *ph = cJSON_AddArrayToObject(e, "phases");
            for (int n = 0; n < g->nplanets && g->teeth[0] > 0; n++)
                cJSON_AddItemToArray(
                    ph, gd_cli_json_number(gd_planetary_mesh_phase(g, q, n, sun_direction(m, g))));
            cJSON_AddItemToArray(ms, e);
        }
        cJSON_AddItemToArray(a, j);
    }
    return a;
}

/* The idlers: carrying node, synchroniser, engaged or idling (docs/model-format.md). */
static void print_idlers(const gd_model *m)
{
    if (!m->nidlers) return;
    printf("\n%-12s %-12s %-12s %-8s %s\n", "idler", "on", "synchro", "state", "order");
    for (int i = 0; i < m->nidlers; i++) {
        const gd_idler *id = &m->idlers[i];
        char label[128];
        gd_model_shaft_order_label(m, m->nodes[id->node].shaft, label, (int)sizeof label);
        printf("%-12s %-12s %-12s %-8s %s\n", id->name, m->nodes[id->carrier].name,
               id->synchroniser >= 0 ? m->synchronisers[id->synchroniser].name : "-",
               id->engaged ? "engaged" : "idling", label);
    }
    if (m->gear) printf("gear      %d selected\n", m->gear);
}

static cJSON *idlers_json(const gd_model *m)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < m->nidlers; i++) {
        const gd_idler *id = &m->idlers[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", id->name);
        cJSON_AddStringToObject(j, "on", m->nodes[id->carrier].name);
        if (id->synchroniser >= 0)
            cJSON_AddStringToObject(j, "synchroniser", m->synchronisers[id->synchroniser].name);
        cJSON_AddBoolToObject(j, "engaged", id->engaged);
        cJSON_AddItemToArray(a, j);
    }
    return a;
}

static void print_text(const gd_model *m, const gd_system *s)
{
    printf("model     %s\n", m->file);
    printf("nodes     %d\n", m->nnodes);
    printf("DOFs      %d active (", s->ndof);
    for (int d = 0, first = 1; d < GD_NODE_DOFS; d++)
        if (m->dof_mask & GD_DOF_BIT(d)) {
            printf("%s%s", first ? "" : " ", gd_dof_names[d]);
            first = 0;
        }
    printf(" per node where used), %d massless\n", s->nmassless);
    printf("elements  %d shaft elements, %d disks, %d bearings, %d springs, %d meshes\n",
           m->nelements, m->ndisks, m->nbearings, m->nsprings, m->nmeshes);
    printf("speed     %g rad/s (%g rpm) on shaft '%s'\n\n", m->speed, m->speed * 30 / M_PI,
           m->shafts[m->reference_shaft].name);
    printf("%-16s %6s %8s %10s %10s %14s %11s\n", "shaft", "nodes", "elements", "length(m)",
           "mass(kg)", "Ip(kg*m^2)", "speed ratio");
    for (int i = 0; i < m->nshafts; i++) {
        gd_shaft_summary ss;
        gd_model_shaft_summary(m, i, &ss);
        printf("%-16s %6d %8d %10.4g %10.4g %14.5g %11.5g\n", m->shafts[i].name, ss.nnodes,
               ss.nelements, ss.length, ss.mass, ss.polar_inertia, m->shafts[i].speed_ratio);
    }
    if (m->nmeshes) {
        printf("\n%-12s %-24s %8s %10s %10s %10s %10s %s\n", "mesh", "driver -> driven", "ratio",
               "rb1(m)", "rb2(m)", "k(N/m)", "c(N*s/m)", "coupling");
        for (int i = 0; i < m->nmeshes; i++) {
            const gd_mesh *g = &m->meshes[i];
            char pair[64];
            snprintf(pair, sizeof pair, "%.11s -> %.11s", m->nodes[g->driver].name,
                     m->nodes[g->driven].name);
            printf("%-12s %-24s %8.5g %10.5g %10.5g %10.4g %10.4g %s\n", g->name, pair,
                   g->base_radius[1] / g->base_radius[0], g->base_radius[0], g->base_radius[1],
                   g->stiffness, g->damping, gd_coupling_names[g->coupling]);
        }
    }
    print_planetary(m);
    print_idlers(m);
    if (m->nlaws) {
        /* laws of the registry: type, where, and the parameters that are not zero */
        printf("\n%-16s %-18s %-24s %s\n", "law", "type", "node -> to", "parameters (SI)");
        for (int i = 0; i < m->nlaws; i++) {
            const gd_model_law *L = &m->laws[i];
            char where[64], par[256] = "";
            snprintf(where, sizeof where, "%.11s%s%s -> %.11s", m->nodes[L->node].name,
                     L->type->ndirs ? "" : ".", L->type->ndirs ? "" : gd_dof_names[L->dof],
                     L->node2 >= 0 ? m->nodes[L->node2].name : "ground");
            size_t len = 0;
            for (int k = 0; k < L->type->nparams && len + 40 < sizeof par; k++)
                if (L->value[k] != 0.0) {
                    int w = snprintf(par + len, sizeof par - len, "%s%s %.4g", len ? ", " : "",
                                     L->type->params[k].name, L->value[k]);
                    if (w > 0) len += (size_t)w;
                }
            printf("%-16s %-18s %-24s %s\n", L->name, L->type->name, where, par);
        }
    }
}

static cJSON *summary_json(const gd_model *m, const gd_system *s)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", m->file);
    cJSON_AddNumberToObject(o, "nodes", m->nnodes);
    cJSON_AddNumberToObject(o, "dofs", s->ndof);
    cJSON_AddNumberToObject(o, "massless_dofs", s->nmassless);
    cJSON_AddNumberToObject(o, "shaft_elements", m->nelements);
    cJSON_AddNumberToObject(o, "disks", m->ndisks);
    cJSON_AddNumberToObject(o, "bearings", m->nbearings);
    cJSON_AddNumberToObject(o, "springs", m->nsprings);
    cJSON_AddNumberToObject(o, "speed_rad_s", m->speed);
    cJSON *shafts = cJSON_AddArrayToObject(o, "shafts");
    for (int i = 0; i < m->nshafts; i++) {
        gd_shaft_summary ss;
        gd_model_shaft_summary(m, i, &ss);
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", m->shafts[i].name);
        cJSON_AddNumberToObject(j, "nodes", ss.nnodes);
        cJSON_AddNumberToObject(j, "elements", ss.nelements);
        cJSON_AddNumberToObject(j, "length_m", ss.length);
        cJSON_AddNumberToObject(j, "mass_kg", ss.mass);
        cJSON_AddNumberToObject(j, "polar_inertia_kg_m2", ss.polar_inertia);
        cJSON_AddNumberToObject(j, "speed_ratio", m->shafts[i].speed_ratio);
        cJSON_AddItemToArray(shafts, j);
    }
    cJSON *meshes = cJSON_AddArrayToObject(o, "meshes");
    for (int i = 0; i < m->nmeshes; i++) {
        const gd_mesh *g = &m->meshes[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", g->name);
        cJSON_AddStringToObject(j, "driver", m->nodes[g->driver].name);
        cJSON_AddStringToObject(j, "driven", m->nodes[g->driven].name);
        cJSON_AddNumberToObject(j, "stiffness_N_per_m", g->stiffness);
        cJSON_AddNumberToObject(j, "damping_N_s_per_m", g->damping);
        cJSON_AddStringToObject(j, "coupling", gd_coupling_names[g->coupling]);
        cJSON_AddItemToArray(meshes, j);
    }
    if (m->nplanetary) cJSON_AddItemToObject(o, "planetary_sets", planetary_json(m));
    if (m->nidlers) {
        cJSON_AddItemToObject(o, "idlers", idlers_json(m));
        cJSON_AddNumberToObject(o, "gear", m->gear);
    }
    cJSON *laws = cJSON_AddArrayToObject(o, "laws");
    for (int i = 0; i < m->nlaws; i++) {
        const gd_model_law *L = &m->laws[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", L->name);
        cJSON_AddStringToObject(j, "type", L->type->name);
        cJSON_AddStringToObject(j, "node", m->nodes[L->node].name);
        if (L->node2 >= 0) cJSON_AddStringToObject(j, "to", m->nodes[L->node2].name);
        if (!L->type->ndirs) cJSON_AddStringToObject(j, "dof", gd_dof_names[L->dof]);
        cJSON *p = cJSON_AddObjectToObject(j, "parameters");
        for (int k = 0; k < L->type->nparams; k++)
            cJSON_AddNumberToObject(p, L->type->params[k].name, L->value[k]);
        cJSON_AddItemToArray(laws, j);
    }
    return o;
}

int gd_cmd_check(int argc, char **argv)
{
    check_args a = {0};
    const char *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_model *m;
    gd_system *s;
    rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s);
    if (rc) return rc;
    if (a.json) {
        cJSON *o = summary_json(m, s);
        gd_cli_print_json(stdout, o);
        cJSON_Delete(o);
    } else {
        print_text(m, s);
    }
    gd_system_free(s);
    gd_model_free(m);
    return GD_EXIT_OK;
}
