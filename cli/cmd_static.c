/* geardyn static MODEL: equilibrium under the mean loads and gravity (docs/static.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "options.h"
#include "geardyn/static.h"
#include "geardyn/units.h"

typedef struct static_args {
    gd_static_options opt;
    const char *coupling, *out, *plot, *input, *hold;
    gd_cli_sets sets;
    int json;
} static_args;

#define F(m) offsetof(static_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("torque", GD_CLI_QUANTITY, F(opt.input_torque), "VALUE",
               "input torque, N m (units allowed: 20N*m), in the input shaft's sense of rotation",
               .def = "none", .qty = GD_QTY_TORQUE, .example = "20N*m"),
    GD_CLI_ROW("input", GD_CLI_STRING, F(input), "NODE", "node the input torque acts on",
               .def = "the reference shaft's first node"),
    GD_CLI_ROW("hold", GD_CLI_STRING, F(hold), "NODE",
               "hold the torsion of NODE's train there (default: the output, the last node of "
               "the last shaft, with --torque; the input without)"),
    GD_CLI_ROW_SPEED(static_args, opt.speed, 0,
                     "reference speed for bearing speed tables (default: model's)"),
    GD_CLI_ROW("no-gravity", GD_CLI_CLEAR, F(opt.gravity), NULL, "leave out the model's gravity"),
    GD_CLI_ROW("no-loads", GD_CLI_CLEAR, F(opt.loads), NULL,
               "leave out the model's excitation loads"),
    GD_CLI_ROW_MODEL(static_args, coupling, sets),
    GD_CLI_ROW_JSON(static_args, json),
    GD_CLI_ROW_OUT(static_args, out,
                   "write DIR/static_nodes.csv, static_bearings.csv, static_meshes.csv, "
                   "static_holds.csv and, with laws, static_laws.csv"),
    GD_CLI_ROW_PLOT(static_args, plot),
    {0}};
static const gd_cli_command CMD = {
    .name = "static",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "Static equilibrium K q = f under the model's mean loads (excitation loads at their\n"
        "mean), an input torque and gravity (`gravity:`): deflection and slope along every\n"
        "shaft, bearing reactions, the force of every mesh and its misalignment (relative tilt\n"
        "in and out of the plane of action, ISO 6336-1 f_sh = b x tilt). Prescribed DOFs are\n"
        "held; a gear train free to turn is held at one torsion DOF (the torque balance).\n"};

/* no "-0" in the tables */
static double nz(double v)
{
    return v == 0 ? 0.0 : v;
}

static const char *node_name(const gd_model *m, int node)
{
    return m->nodes[node].name;
}

static void print_tables(const gd_system *s, const gd_static_result *r, double torque)
{
    const gd_model *m = s->model;
    printf("%s: %d DOFs, speed %g rad/s; %d held DOF%s\n", m->file, r->ndof, r->speed, r->nholds,
           r->nholds == 1 ? "" : "s");
    /* --torque adds to the model's own loads at that node: the total, said */
    if (r->input_node >= 0) {
        double own = r->input_torque_total - torque;
        printf("input torque at %s: %.6g N m", node_name(m, r->input_node), r->input_torque_total);
        if (fabs(own) > 1e-12 * fabs(torque))
            printf(" = --torque %.6g N m + the model's own loads there %.6g N m\n", torque, own);
        else
            printf(" (--torque)\n");
        /* and the model's loads elsewhere (mean excitation loads, gravity) */
        int in = gd_system_dof(s, r->input_node, GD_RZ), other = 0;
        for (int i = 0; i < r->ndof; i++)
            other += i != in && r->f[i] != 0;
        if (other)
            printf("the model's own mean loads and gravity act too, on %d more DOF%s (--no-loads "
                   "and --no-gravity leave them out)\n",
                   other, other == 1 ? "" : "s");
    }
    if (r->nholds) {
        printf("\nheld DOFs (reaction applied to hold them)\n%-20s %4s %-10s %14s\n", "node", "dof",
               "kind", "reaction");
        for (int h = 0; h < r->nholds; h++) {
            const gd_static_hold *ho = &r->holds[h];
            printf("%-20s %4s %-10s %14.6g %s\n", node_name(m, ho->node), gd_dof_names[ho->dof],
                   ho->prescribed ? "prescribed" : "torque", ho->reaction,
                   ho->dof >= GD_RX ? "N m" : "N");
        }
    }
    if (m->nmeshes) {
        printf("\nmeshes (force on the drive flank; tilt driver - driven; f_sh = b x tilt in "
               "plane)\n%-12s %12s %12s %12s %12s %12s %12s %8s %10s %10s\n",
               "mesh", "F(N)", "Ft(N)", "Fr(N)", "Fa(N)", "tilt_in(ur)", "tilt_out(ur)", "b(mm)",
               "f_sh(um)", "Fbx(um)");
        for (int k = 0; k < m->nmeshes; k++) {
            const gd_static_mesh *g = &r->meshes[k];
            printf("%-12.12s %12.6g %12.6g %12.6g %12.6g %12.5g %12.5g", m->meshes[k].name,
                   g->force, g->tangential, g->radial, g->axial, g->tilt_in_plane * 1e6,
                   g->tilt_out_of_plane * 1e6);
            if (isfinite(g->f_sh))
                printf(" %8.4g %10.4g %10.4g\n", g->face_width * 1e3, g->f_sh * 1e6,
                       g->f_beta_x * 1e6);
            else
                printf(" %8s %10s %10s\n", "-", "-", "-");
        }
    }
    for (int k = 0; k < m->nplanetary; k++) {
        gd_static_planetary_loads pl;
        if (gd_static_planetary(s, r, k, &pl, NULL)) continue;
        printf("\nplanetary set '%s': load-sharing factor K_gamma %.6g\n%-8s %14s %14s %14s\n",
               m->planetary[k].name, pl.load_sharing, "planet", "F_sun(N)", "F_ring(N)",
               "F_bearing(N)");
        for (int n = 0; n < pl.nplanets; n++)
            printf("%-8d %14.6g %14.6g %14.6g\n", n + 1, pl.sun_force[n], pl.ring_force[n],
                   pl.bearing_force[n]);
    }
    if (m->nbearings) {
        printf("\nbearing reactions (force and moment on the shaft)\n%-12s %-14s %12s %12s %12s "
               "%12s %12s %12s\n",
               "bearing", "node", "Fx(N)", "Fy(N)", "Fz(N)", "Mx(N m)", "My(N m)", "Mz(N m)");
        for (int b = 0; b < m->nbearings; b++) {
            const gd_static_reaction *re = &r->bearings[b];
            printf("%-12.12s %-14.14s %12.6g %12.6g %12.6g %12.6g %12.6g %12.6g\n",
                   m->bearings[b].name, node_name(m, m->bearings[b].node), nz(re->force[0]),
                   nz(re->force[1]), nz(re->force[2]), nz(re->moment[0]), nz(re->moment[1]),
                   nz(re->moment[2]));
        }
    }
    if (m->nsprings) {
        printf("\nsprings (force or torque on node1 along the DOF)\n");
        for (int k = 0; k < m->nsprings; k++)
            printf("%-12.12s %-4s %14.6g\n", m->springs[k].name, gd_dof_names[m->springs[k].dof],
                   r->springs[k]);
    }
    if (r->nlaws) {
        printf("\nlaws (records at the static state)\n");
        for (int l = 0; l < r->nlaws; l++) {
            const gd_static_law *L = &r->laws[l];
            printf("%-16.16s %-16.16s", L->name, L->type);
            for (int k = 0; k < L->nrecords; k++)
                printf(" %s %.6g %s%s", L->record_names[k], L->records[k], L->record_units[k],
                       k + 1 < L->nrecords ? "," : "");
            printf("\n");
        }
    }
    printf("\nnodes (displacement um, rotation mrad)\n%-12s %-16s %9s %11s %11s %11s %10s %10s "
           "%10s\n",
           "shaft", "node", "z(m)", "x", "y", "axial", "rx", "ry", "rz");
    for (int sh = 0; sh < m->nshafts; sh++)
        for (int i = 0; i < m->shafts[sh].nnodes; i++) {
            int node = m->shafts[sh].first_node + i;
            const double *u = r->u + (size_t)node * GD_NODE_DOFS;
            printf("%-12.12s %-16.16s %9.4g %11.5g %11.5g %11.5g %10.5g %10.5g %10.5g\n",
                   m->shafts[sh].name, node_name(m, node), m->nodes[node].position, u[0] * 1e6,
                   u[1] * 1e6, u[2] * 1e6, u[3] * 1e3, u[4] * 1e3, u[5] * 1e3);
        }
}

static void add_num(cJSON *o, const char *k, double v)
{
    cJSON_AddItemToObject(o, k, gd_cli_json_number(v));
}

static cJSON *num_array(const double *v, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int i = 0; i < n; i++)
        cJSON_AddItemToArray(a, gd_cli_json_number(v[i]));
    return a;
}

static cJSON *result_json(const gd_system *s, const gd_static_result *r)
{
    const gd_model *m = s->model;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", m->file);
    cJSON_AddNumberToObject(o, "dofs", r->ndof);
    cJSON_AddNumberToObject(o, "speed_rad_s", r->speed);
    if (r->input_node >= 0) {
        cJSON_AddStringToObject(o, "input_node", node_name(s->model, r->input_node));
        cJSON_AddNumberToObject(o, "input_torque_total_n_m", r->input_torque_total);
    }
    cJSON *hs = cJSON_AddArrayToObject(o, "holds");
    for (int h = 0; h < r->nholds; h++) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "node", node_name(m, r->holds[h].node));
        cJSON_AddStringToObject(j, "dof", gd_dof_names[r->holds[h].dof]);
        cJSON_AddStringToObject(j, "kind", r->holds[h].prescribed ? "prescribed" : "torque");
        add_num(j, "reaction", r->holds[h].reaction);
        cJSON_AddItemToArray(hs, j);
    }
    cJSON *ms = cJSON_AddArrayToObject(o, "meshes");
    for (int k = 0; k < m->nmeshes; k++) {
        const gd_static_mesh *g = &r->meshes[k];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", m->meshes[k].name);
        add_num(j, "force_N", g->force);
        add_num(j, "tangential_N", g->tangential);
        add_num(j, "radial_N", g->radial);
        add_num(j, "axial_N", g->axial);
        cJSON_AddItemToObject(j, "on_driver", num_array(g->on_driver, 6));
        cJSON_AddItemToObject(j, "on_driven", num_array(g->on_driven, 6));
        add_num(j, "tilt_in_plane_rad", g->tilt_in_plane);
        add_num(j, "tilt_out_of_plane_rad", g->tilt_out_of_plane);
        add_num(j, "face_width_m", g->face_width);
        add_num(j, "f_sh_m", g->f_sh);
        add_num(j, "F_beta_x_m", g->f_beta_x);
        cJSON_AddItemToArray(ms, j);
    }
    if (m->nplanetary) {
        cJSON *ps = cJSON_AddArrayToObject(o, "planetary_sets");
        for (int k = 0; k < m->nplanetary; k++) {
            gd_static_planetary_loads pl;
            if (gd_static_planetary(s, r, k, &pl, NULL)) continue;
            cJSON *j = cJSON_CreateObject();
            cJSON_AddStringToObject(j, "name", m->planetary[k].name);
            add_num(j, "load_sharing_factor", pl.load_sharing);
            cJSON_AddItemToObject(j, "sun_mesh_force_N", num_array(pl.sun_force, pl.nplanets));
            cJSON_AddItemToObject(j, "ring_mesh_force_N", num_array(pl.ring_force, pl.nplanets));
            cJSON_AddItemToObject(j, "bearing_force_N", num_array(pl.bearing_force, pl.nplanets));
            cJSON_AddItemToArray(ps, j);
        }
    }
    cJSON *bs = cJSON_AddArrayToObject(o, "bearings");
    for (int b = 0; b < m->nbearings; b++) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", m->bearings[b].name);
        cJSON_AddStringToObject(j, "node", node_name(m, m->bearings[b].node));
        cJSON_AddItemToObject(j, "force_N", num_array(r->bearings[b].force, 3));
        cJSON_AddItemToObject(j, "moment_N_m", num_array(r->bearings[b].moment, 3));
        cJSON_AddItemToArray(bs, j);
    }
    cJSON *ss = cJSON_AddArrayToObject(o, "springs");
    for (int k = 0; k < m->nsprings; k++) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddStringToObject(j, "name", m->springs[k].name);
        cJSON_AddStringToObject(j, "dof", gd_dof_names[m->springs[k].dof]);
        add_num(j, "force", r->springs[k]);
        cJSON_AddItemToArray(ss, j);
    }
    if (r->nlaws) {
        cJSON *ls = cJSON_AddArrayToObject(o, "laws");
        for (int l = 0; l < r->nlaws; l++) {
            const gd_static_law *L = &r->laws[l];
            cJSON *j = cJSON_CreateObject();
            cJSON_AddStringToObject(j, "name", L->name);
            cJSON_AddStringToObject(j, "type", L->type);
            cJSON *rec = cJSON_AddObjectToObject(j, "records");
            for (int k = 0; k < L->nrecords; k++)
                add_num(rec, L->record_names[k], L->records[k]);
            cJSON_AddItemToArray(ls, j);
        }
    }
    cJSON *ns = cJSON_AddArrayToObject(o, "nodes");
    for (int sh = 0; sh < m->nshafts; sh++)
        for (int i = 0; i < m->shafts[sh].nnodes; i++) {
            int node = m->shafts[sh].first_node + i;
            cJSON *j = cJSON_CreateObject();
            cJSON_AddStringToObject(j, "shaft", m->shafts[sh].name);
            cJSON_AddStringToObject(j, "node", node_name(m, node));
            add_num(j, "position_m", m->nodes[node].position);
            const double *u = r->u + (size_t)node * GD_NODE_DOFS;
            for (int d = 0; d < GD_NODE_DOFS; d++)
                add_num(j, gd_dof_names[d], u[d]);
            cJSON_AddItemToArray(ns, j);
        }
    return o;
}

static int write_csv(const gd_system *s, const gd_static_result *r, const char *dir)
{
    const gd_model *m = s->model;
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "static_nodes.csv", &err);
    if (!f) goto fail;
    fprintf(f, "shaft,node,position_m,x_m,y_m,z_m,rx_rad,ry_rad,rz_rad\n");
    for (int sh = 0; sh < m->nshafts; sh++)
        for (int i = 0; i < m->shafts[sh].nnodes; i++) {
            int node = m->shafts[sh].first_node + i;
            const double *u = r->u + (size_t)node * GD_NODE_DOFS;
            fprintf(f, "%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", m->shafts[sh].name,
                    node_name(m, node), m->nodes[node].position, u[0], u[1], u[2], u[3], u[4],
                    u[5]);
        }
    if (gd_outdir_close(&od, f, "static_nodes.csv", &err)) goto fail;
    if (!(f = gd_outdir_open(&od, "static_bearings.csv", &err))) goto fail;
    fprintf(f, "bearing,node,Fx_N,Fy_N,Fz_N,Mx_N_m,My_N_m,Mz_N_m\n");
    for (int b = 0; b < m->nbearings; b++) {
        const gd_static_reaction *re = &r->bearings[b];
        fprintf(f, "%s,%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", m->bearings[b].name,
                node_name(m, m->bearings[b].node), re->force[0], re->force[1], re->force[2],
                re->moment[0], re->moment[1], re->moment[2]);
    }
    if (gd_outdir_close(&od, f, "static_bearings.csv", &err)) goto fail;
    if (!(f = gd_outdir_open(&od, "static_meshes.csv", &err))) goto fail;
    fprintf(f, "mesh,force_N,tangential_N,radial_N,axial_N,tilt_in_plane_rad,"
               "tilt_out_of_plane_rad,face_width_m,f_sh_m,F_beta_x_m\n");
    for (int k = 0; k < m->nmeshes; k++) {
        const gd_static_mesh *g = &r->meshes[k];
        fprintf(f, "%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", m->meshes[k].name,
                g->force, g->tangential, g->radial, g->axial, g->tilt_in_plane,
                g->tilt_out_of_plane, g->face_width, g->f_sh, g->f_beta_x);
    }
    if (gd_outdir_close(&od, f, "static_meshes.csv", &err)) goto fail;
    if (!(f = gd_outdir_open(&od, "static_holds.csv", &err))) goto fail;
    fprintf(f, "node,dof,kind,reaction\n");
    for (int h = 0; h < r->nholds; h++)
        fprintf(f, "%s,%s,%s,%.10g\n", node_name(m, r->holds[h].node),
                gd_dof_names[r->holds[h].dof], r->holds[h].prescribed ? "prescribed" : "torque",
                r->holds[h].reaction);
    if (gd_outdir_close(&od, f, "static_holds.csv", &err)) goto fail;
    if (r->nlaws) {
        if (!(f = gd_outdir_open(&od, "static_laws.csv", &err))) goto fail;
        fprintf(f, "law,type,record,value,unit\n");
        for (int l = 0; l < r->nlaws; l++)
            for (int k = 0; k < r->laws[l].nrecords; k++)
                fprintf(f, "%s,%s,%s,%.10g,%s\n", r->laws[l].name, r->laws[l].type,
                        r->laws[l].record_names[k], r->laws[l].records[k],
                        r->laws[l].record_units[k]);
        if (gd_outdir_close(&od, f, "static_laws.csv", &err)) goto fail;
    }
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

/* 1 when every displacement, reaction and mesh force of r is finite. A torque or a
 * load of 1e308 N m solved to inf and NaN tables with exit 0 (issue 38 M7). */
static int all_finite(const gd_static_result *r)
{
    for (int i = 0; i < r->ndof; i++)
        if (!isfinite(r->q[i]) || !isfinite(r->f[i])) return 0;
    for (int b = 0; b < r->nbearings; b++)
        for (int k = 0; k < 3; k++)
            if (!isfinite(r->bearings[b].force[k]) || !isfinite(r->bearings[b].moment[k])) return 0;
    for (int k = 0; k < r->nmeshes; k++)
        if (!isfinite(r->meshes[k].force)) return 0;
    for (int h = 0; h < r->nholds; h++)
        if (!isfinite(r->holds[h].reaction)) return 0;
    return 1;
}

/* A node by name for --input / --hold; -1 after a usage error. */
static int find_node(const gd_model *m, const char *opt, const char *name)
{
    int node = gd_model_find_node(m, name);
    if (node < 0) gd_cli_usage_error("static", "%s: no node named '%s' in the model", opt, name);
    return node;
}

int gd_cmd_static(int argc, char **argv)
{
    static_args a = {0};
    gd_static_options_init(&a.opt);
    const char *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_static_options opt = a.opt;
    const char *out = a.out, *plot = a.plot, *input = a.input, *hold = a.hold;
    gd_error oerr;
    gd_error_clear(&oerr);
    if (out && gd_outdir_check(out, &oerr)) return gd_cli_report(&oerr);
    if (plot && (rc = gd_cli_plot_check(plot))) return rc;
    gd_model *m;
    gd_system *s;
    rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s);
    if (rc) return rc;
    if ((input && (opt.input_node = find_node(m, "--input", input)) < 0) ||
        (hold && (opt.hold_node = find_node(m, "--hold", hold)) < 0)) {
        gd_system_free(s);
        gd_model_free(m);
        return GD_EXIT_INPUT;
    }
    gd_static_result *r = NULL;
    gd_error err;
    gd_error_clear(&err);
    if (gd_static_run(s, &opt, &r, &err)) {
        rc = gd_cli_report(&err);
    } else if (!all_finite(r)) {
        if (opt.input_torque != 0)
            rc = gd_cli_usage_error("static",
                                    "--torque: %g N m overflows the equilibrium (displacements "
                                    "or forces beyond 1e308): give a torque the model can carry",
                                    opt.input_torque);
        else
            rc = gd_cli_report((gd_error_set(&err, GD_EINPUT, file, 0, 0, "loads",
                                             "check the loads' means, the gravity and the "
                                             "stiffnesses",
                                             "the static equilibrium overflows (displacements "
                                             "or forces beyond 1e308)"),
                                &err));
        gd_static_free(r);
    } else {
        if (plot) {
            gd_plot *p = NULL;
            gd_status pst = gd_plot_static(s, r, &p, &err);
            rc = gd_cli_plot_finish(pst, p, &err, plot);
        }
        if (out && rc == GD_EXIT_OK) rc = write_csv(s, r, out);
        if (rc == GD_EXIT_OK) {
            if (a.json) {
                cJSON *o = result_json(s, r);
                gd_cli_print_json(stdout, o);
                cJSON_Delete(o);
            } else {
                print_tables(s, r, opt.input_torque);
            }
        }
        gd_static_free(r);
    }
    gd_system_free(s);
    gd_model_free(m);
    return rc;
}
