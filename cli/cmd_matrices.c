/* geardyn matrices MODEL --out DIR: the system's M, K, C and G at a speed, in Matrix
 * Market files or one JSON file, with the list of DOFs, to check a model against
 * another code. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "options.h"

typedef struct mx_args {
    const char *out, *file, *coupling;
    double speed;
    int json;
    gd_cli_sets sets;
} mx_args;

#define F(m) offsetof(mx_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW_OUT(mx_args, out,
                   "the folder for M.mtx, K.mtx, C.mtx, G.mtx (Matrix Market, coordinate real "
                   "general, 1-based) and dofs.csv",
                   .required = 1),
    GD_CLI_ROW_SPEED(mx_args, speed, 0, "reference speed W, e.g. 3000rpm or 314 (rad/s)",
                     .def = "0"),
    GD_CLI_ROW("format", GD_CLI_CHOICE, F(json), "F",
               "mtx or json: DIR/matrices.json (the DOFs and each matrix as 1-based rows, cols, "
               "values) in place of the .mtx files",
               .def = "mtx", .word = "mtx|json"),
    GD_CLI_ROW_MODEL(mx_args, coupling, sets),
    {0}};
static const gd_cli_command CMD = {
    .name = "matrices",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "Writes the matrices of the equation of motion at reference speed W over the active\n"
        "DOFs,  M q'' + (C(W) + W G) q' + K(W) q = f:  the mass M, the stiffness\n"
        "K(W) = K + K_b(W) and the damping C(W) = C + C_b(W) with the speed-table bearings at\n"
        "W, and the gyroscopic matrix G per unit reference speed. SI units: DOFs in m and rad,\n"
        "forces in N, moments in N*m.\n",
    .footer = "Exit status: 0 ok, 2 bad input or usage, 1 numerical failure.\n"};

static const char UNITS[] = "SI units: DOFs in m and rad, forces in N, moments in N*m";

/* The four matrices, in file order, with what each is. */
typedef struct mx_set {
    gd_csc m[4];
} mx_set;
static const char *const NAMES[4] = {"M", "K", "C", "G"};
static const char *const WHAT[4] = {
    "M, mass", "K + K_b(W), stiffness with the speed-table bearings at W",
    ("C + C_b(W), damping with the speed-table bearings at W, without the gyroscopic term "
     "(damping at W: C + W G)"),
    "G, gyroscopic per unit reference speed (damping at W: C + W G)"};

static void write_mtx(FILE *f, const gd_csc *a, int which, const char *model, double speed)
{
    fprintf(f, "%%%%MatrixMarket matrix coordinate real general\n");
    fprintf(f,
            "%% geardyn matrices: model %s; %s; W = %.17g rad/s (%.6g rpm); %s; DOFs in "
            "dofs.csv\n",
            model, WHAT[which], speed, speed * 30 / M_PI, UNITS);
    fprintf(f, "%d %d %d\n", a->n, a->n, a->colptr[a->n]);
    for (int j = 0; j < a->n; j++)
        for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++)
            fprintf(f, "%d %d %.17g\n", a->rowind[k] + 1, j + 1, a->values[k]);
}

static const char *shaft_of(const gd_system *s, int i)
{
    const gd_model *m = s->model;
    return m->shafts[m->nodes[s->dof_node[i]].shaft].name;
}

static void write_dofs(FILE *f, const gd_system *s)
{
    fprintf(f, "index,node,dof,shaft,massless\n");
    for (int i = 0; i < s->ndof; i++)
        fprintf(f, "%d,%s,%s,%s,%d\n", i + 1, s->model->nodes[s->dof_node[i]].name,
                gd_dof_names[s->dof_type[i]], shaft_of(s, i), s->massless[i]);
}

/* %.17g: cJSON's own printing may drop the last bit, and the values are for checking. */
static cJSON *exact_number(double v)
{
    char buf[32];
    snprintf(buf, sizeof buf, "%.17g", v);
    return cJSON_CreateRaw(buf);
}

static cJSON *matrix_json(const gd_csc *a, int which)
{
    cJSON *o = cJSON_CreateObject(), *rows = cJSON_CreateArray(), *cols = cJSON_CreateArray(),
          *vals = cJSON_CreateArray();
    for (int j = 0; j < a->n; j++)
        for (int k = a->colptr[j]; k < a->colptr[j + 1]; k++) {
            cJSON_AddItemToArray(rows, cJSON_CreateNumber(a->rowind[k] + 1));
            cJSON_AddItemToArray(cols, cJSON_CreateNumber(j + 1));
            cJSON_AddItemToArray(vals, exact_number(a->values[k]));
        }
    cJSON_AddStringToObject(o, "matrix", WHAT[which]);
    cJSON_AddNumberToObject(o, "size", a->n);
    cJSON_AddNumberToObject(o, "nnz", a->colptr[a->n]);
    cJSON_AddItemToObject(o, "rows", rows);
    cJSON_AddItemToObject(o, "cols", cols);
    cJSON_AddItemToObject(o, "values", vals);
    return o;
}

static cJSON *all_json(const gd_system *s, const mx_set *mx, double speed)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", s->model->file);
    cJSON_AddItemToObject(o, "speed_rad_s", exact_number(speed));
    cJSON_AddStringToObject(o, "units", UNITS);
    cJSON_AddStringToObject(o, "indexing", "rows and cols are 1-based indices into dofs");
    cJSON *dofs = cJSON_AddArrayToObject(o, "dofs");
    for (int i = 0; i < s->ndof; i++) {
        cJSON *d = cJSON_CreateObject();
        cJSON_AddNumberToObject(d, "index", i + 1);
        cJSON_AddStringToObject(d, "node", s->model->nodes[s->dof_node[i]].name);
        cJSON_AddStringToObject(d, "dof", gd_dof_names[s->dof_type[i]]);
        cJSON_AddStringToObject(d, "shaft", shaft_of(s, i));
        cJSON_AddBoolToObject(d, "massless", s->massless[i]);
        cJSON_AddItemToArray(dofs, d);
    }
    for (int k = 0; k < 4; k++)
        cJSON_AddItemToObject(o, NAMES[k], matrix_json(&mx->m[k], k));
    return o;
}

/* Writes the files of one format through the staging folder: all or nothing. */
static int write_all(const mx_args *a, const gd_system *s, const mx_set *mx, double speed)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, a->out, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "dofs.csv", &err);
    if (!f) goto fail;
    write_dofs(f, s);
    if (gd_outdir_close(&od, f, "dofs.csv", &err)) goto fail;
    for (int k = 0; k < (a->json ? 1 : 4); k++) {
        char name[32];
        snprintf(name, sizeof name, a->json ? "matrices.json" : "%s.mtx", NAMES[k]);
        if (!(f = gd_outdir_open(&od, name, &err))) goto fail;
        if (a->json) {
            cJSON *o = all_json(s, mx, speed);
            gd_cli_print_json(f, o);
            cJSON_Delete(o);
        } else {
            write_mtx(f, &mx->m[k], k, s->model->file, speed);
        }
        if (gd_outdir_close(&od, f, name, &err)) goto fail;
    }
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

static int run(const mx_args *a, double speed)
{
    gd_model *m;
    gd_system *s;
    int rc = gd_cli_load(a->file, &a->sets, a->coupling, &m, &s);
    if (rc) return rc;
    mx_set mx;
    gd_error err;
    gd_error_clear(&err);
    if (gd_system_matrices(s, speed, &mx.m[0], &mx.m[1], &mx.m[2], &mx.m[3], &err)) {
        rc = gd_cli_report(&err);
    } else {
        rc = write_all(a, s, &mx, speed);
        if (rc == GD_EXIT_OK)
            printf("%s: %d DOFs at %g rad/s: wrote %s to %s\n", a->file, s->ndof, speed,
                   a->json ? "dofs.csv, matrices.json" : "dofs.csv, M.mtx, K.mtx, C.mtx, G.mtx",
                   a->out);
        for (int k = 0; k < 4; k++)
            gd_csc_free(&mx.m[k]);
    }
    gd_system_free(s);
    gd_model_free(m);
    return rc;
}

int gd_cmd_matrices(int argc, char **argv)
{
    mx_args a = {0};
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &a.file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_error err;
    gd_error_clear(&err);
    if (gd_outdir_check_writable(a.out, &err)) return gd_cli_report(&err);
    return run(&a, a.speed);
}
