/* geardyn modal MODEL: natural frequencies and modes. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli.h"
#include "geardyn/modal.h"
#include "modal_directional.h"
#include "modal_groups.h"
#include "operating_point.h"
#include "options.h"

typedef struct modal_args {
    gd_modal_options opt;
    const char *coupling, *out, *plot;
    gd_cli_sets sets;
    gd_cli_operating op;
    int json, nmodes, by_shaft, directional;
} modal_args;

static int parse_tol(const char *cmd, const char *text, void *field)
{
    return gd_cli_parse_tolerance(cmd, "--tol", text, field);
}

#define F(m) offsetof(modal_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW_SPEED(modal_args, opt.speed, 0,
                     "reference shaft speed, e.g. 3000rpm, 314 (rad/s); default: model's"),
    GD_CLI_ROW("modes", GD_CLI_INT, F(nmodes), "N|all",
               "number of lowest modes (default: all up to 30 DOFs, else 20)", .lo = 1,
               .hi = 1000000, .word = "all", .ival = 0),
    GD_CLI_ROW("undamped", GD_CLI_VALUE, F(opt.kind), NULL,
               "drop damping and gyroscopic terms (symmetric eigenproblem)",
               .ival = GD_MODAL_UNDAMPED, .excludes = "damped"),
    GD_CLI_ROW("damped", GD_CLI_VALUE, F(opt.kind), NULL,
               "always use the state-space (damped) eigenproblem", .ival = GD_MODAL_DAMPED,
               .excludes = "undamped"),
    GD_CLI_ROW_EIG_METHOD(modal_args, opt.method,
                          "auto: the cheaper of the two by a measured cost model; dense: LAPACK "
                          "(all modes); sparse: shift-invert Krylov-Schur with a sparse LU (the "
                          "lowest N modes, needs mass on every DOF)"),
    GD_CLI_ROWS_OPERATING(modal_args, op),
    GD_CLI_ROW("tol", GD_CLI_CALL, F(opt.tol), "TOL",
               "relative residual of each mode the sparse solver iterates to (the 'resid' "
               "column); LAPACK (dense) is at rounding anyway",
               .def = "1e-9", .call = parse_tol),
    GD_CLI_ROW_MODEL(modal_args, coupling, sets),
    GD_CLI_ROW("group", GD_CLI_CHOICE, F(by_shaft), "shaft",
               "also the strain energy per shaft with its gears, bearings and meshes (half of one "
               "between two shafts), and each shaft's by motion type ([JMSTHelical] Tables 4-7)",
               .def = "by component", .word = "component|shaft"),
    GD_CLI_ROW("directional", GD_CLI_FLAG, F(directional), NULL,
               "also the directional eigenvalues of the complex coordinates r = x + i y "
               "([Kumar2011]): one per mode, Im > 0 forward, < 0 backward"),
    GD_CLI_ROW_JSON(modal_args, json),
    GD_CLI_ROW_OUT(modal_args, out,
                   "write DIR/modes.csv and DIR/mode_shapes.csv (every active DOF of every mode, "
                   "complex)"),
    GD_CLI_ROW_PLOT(modal_args, plot),
    {0}};
static const gd_cli_command CMD = {
    .name = "modal",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about = "Natural frequencies, damping, whirl direction and modal strain energy of each mode.\n"
             "Damped/gyroscopic modes (state space, left and right eigenvectors) are computed "
             "when\nthe model has damping or gyroscopic terms at the speed; otherwise undamped "
             "modes.\n"};

static double share(const gd_mode *md, int k)
{
    return 100.0 * md->energy_share[k];
}

static const char *component_name(const gd_system *s, int c)
{
    int idx;
    const char *name = "";
    if (c >= 0) gd_system_component(s, c, &idx, &name);
    return name;
}

/* The planetary class of mode j (docs/planetary.md): that of the first set that moves in
 * it, "-" when none does. */
static const char *mode_class(const gd_system *s, const gd_modal_result *r, int j)
{
    for (int k = 0; k < s->model->nplanetary; k++) {
        gd_planetary_class c = gd_modal_planetary_class(s, r, j, k);
        if (c != GD_PCLASS_NONE) return gd_planetary_class_names[c];
    }
    return gd_planetary_class_names[GD_PCLASS_NONE];
}

static void print_table(const gd_system *s, const gd_modal_result *r)
{
    int pl = s->model->nplanetary > 0;
    printf("%s: %d DOFs, speed %g rad/s (%g rpm), %s modes (%s solver)\n\n", s->model->file,
           s->ndof, r->speed, r->speed * 30 / M_PI, r->damped ? "damped (state space)" : "undamped",
           r->sparse ? "sparse" : "dense");
    printf("%4s %12s %12s %12s %9s %9s  %-10s %-10s %-14s %5s %5s %5s %5s %8s%s\n", "mode",
           "f_n(Hz)", "w_n(rad/s)", "w_d(rad/s)", "zeta", "logdec", "whirl", "dominant",
           "component", "lat%", "tor%", "ax%", "tilt%", "resid", pl ? "  class" : "");
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body) {
            printf("%4d %12.6g %12.6g %12.6g %9s %9s  %-10s %-10s %-14s %5s %5s %5s %5s %8.1e",
                   j + 1, 0.0, 0.0, 0.0, "-", "-", "none", gd_motion_names[md->dominant_motion],
                   "(rigid body)", "", "", "", "", md->residual);
            if (pl) printf("  %s", mode_class(s, r, j));
            printf("\n");
            continue;
        }
        char ld[16];
        if (isnan(md->log_decrement))
            snprintf(ld, sizeof ld, "-");
        else
            snprintf(ld, sizeof ld, "%.4g", gd_cli_logdec_shown(md->log_decrement));
        printf("%4d %12.6g %12.6g %12.6g %9.4g %9s  %-10s %-10s %-14.14s %5.1f %5.1f %5.1f %5.1f "
               "%8.1e%s%s%s\n",
               j + 1, md->frequency_hz, md->omega_n, md->omega_d,
               gd_cli_zeta_shown(md->damping_ratio), ld, gd_whirl_names[md->whirl],
               gd_motion_names[md->dominant_motion], component_name(s, md->dominant_component),
               share(md, 0), share(md, 1), share(md, 2), share(md, 3), md->residual, pl ? "  " : "",
               pl ? mode_class(s, r, j) : "",
               md->unstable ? "  UNSTABLE" : (md->overdamped ? "  overdamped" : ""));
    }
}

/* A size in bytes or a duration in seconds as a person writes it ("3.2 GB", "14 min"). */
static const char *human(char *b, size_t len, double v, int seconds)
{
    if (seconds)
        snprintf(b, len, "%.2g %s",
                 v < 1      ? v * 1e3
                 : v < 60   ? v
                 : v < 3600 ? v / 60
                            : v / 3600,
                 v < 1      ? "ms"
                 : v < 60   ? "s"
                 : v < 3600 ? "min"
                            : "h");
    else
        snprintf(b, len, "%.2g %s",
                 v >= 1e12  ? v / 1e12
                 : v >= 1e9 ? v / 1e9
                 : v >= 1e6 ? v / 1e6
                            : v / 1e3,
                 v >= 1e12  ? "TB"
                 : v >= 1e9 ? "GB"
                 : v >= 1e6 ? "MB"
                            : "kB");
    return b;
}

/* The modes whose residual is above the precision asked (the sparse solver stops when
 * rounding, not the iteration, is what is left): said on stderr, with that floor. Where
 * the refinement did not converge, what is true for this model: the residual this solve
 * reached, and whether the dense solver is a way out (its memory against this
 * machine's, its time by the cost model; it reaches about its rounding floor, which
 * grows with the model like the sparse one's, not "rounding" of 1e-16). */
static void warn_residuals(const gd_system *s, const gd_modal_result *r, double tol)
{
    int n = 0, first = -1;
    double worst = 0, floor_max = 0;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (md->rigid_body || !(md->residual > tol)) continue;
        if (first < 0) first = j;
        n++;
        worst = fmax(worst, md->residual);
        floor_max = fmax(floor_max, md->residual_floor);
    }
    if (n && worst <= 100 * floor_max) {
        fprintf(stderr,
                "geardyn: warning: %d mode(s) (the first: mode %d) have a relative residual up "
                "to %.1e, above --tol %.1e: the rounding of this model's matrices leaves about "
                "%.1e (eps x (element stiffness / mode stiffness)); a finer tolerance cannot "
                "remove it, a coarser mesh would\n",
                n, first + 1, worst, tol, floor_max);
        return;
    }
    if (!n) return;
    double secs, bytes;
    gd_modal_dense_cost(s, r->damped, &secs, &bytes);
    long pages = sysconf(_SC_PHYS_PAGES), psize = sysconf(_SC_PAGESIZE);
    double phys = pages > 0 && psize > 0 ? (double)pages * (double)psize : 0;
    char b1[32], b2[32], b3[32], dense[400];
    if (phys > 0 && bytes > 0.5 * phys)
        snprintf(dense, sizeof dense,
                 "--method dense is no way out here: LAPACK on all %d DOFs (%s) would need "
                 "about %s of memory, this machine has %s",
                 s->ndof, r->damped ? "state space" : "undamped", human(b1, sizeof b1, bytes, 0),
                 human(b2, sizeof b2, phys, 0));
    else
        snprintf(dense, sizeof dense,
                 "--method dense (LAPACK on all %d DOFs, %s: about %s of memory and %s by the "
                 "cost model) has a rounding floor of its own, not eps: residuals up to 1.4e-11 "
                 "on a 336-DOF and 1.6e-10 on a 366-DOF model, growing with the model",
                 s->ndof, r->damped ? "state space" : "undamped", human(b1, sizeof b1, bytes, 0),
                 human(b3, sizeof b3, secs, 1));
    fprintf(stderr,
            "geardyn: warning: %d mode(s) (the first: mode %d) have a relative residual up to "
            "%.1e, above --tol %.1e and above what rounding leaves (%.1e): the sparse solver's "
            "refinement did not converge (it reached %.1e at this --tol; the default 1e-9 may do "
            "better); %s\n",
            n, first + 1, worst, tol, floor_max, worst, dense);
}

/* a number, or null when not finite (JSON has no NaN) */
static void add_num(cJSON *o, const char *k, double v)
{
    cJSON_AddItemToObject(o, k, gd_cli_json_number(v));
}

static cJSON *result_json(const gd_system *s, const gd_modal_result *r, double tol)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "model", s->model->file);
    cJSON_AddNumberToObject(o, "speed_rad_s", r->speed);
    cJSON_AddBoolToObject(o, "damped", r->damped);
    cJSON_AddStringToObject(o, "method", r->sparse ? "sparse" : "dense");
    cJSON_AddNumberToObject(o, "dofs", s->ndof);
    add_num(o, "tol", tol);
    cJSON *modes = cJSON_AddArrayToObject(o, "modes");
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        cJSON *m = cJSON_CreateObject();
        cJSON_AddNumberToObject(m, "mode", j + 1);
        add_num(m, "omega_n_rad_s", md->omega_n);
        add_num(m, "frequency_hz", md->frequency_hz);
        add_num(m, "omega_d_rad_s", md->omega_d);
        add_num(m, "damped_frequency_hz", md->omega_d / (2 * M_PI));
        add_num(m, "damping_ratio", md->damping_ratio);
        add_num(m, "log_decrement", md->log_decrement);
        add_num(m, "eigenvalue_real", md->lambda_re);
        add_num(m, "eigenvalue_imag", md->lambda_im);
        cJSON_AddStringToObject(m, "whirl", gd_whirl_names[md->whirl]);
        cJSON_AddStringToObject(m, "dominant_motion", gd_motion_names[md->dominant_motion]);
        if (md->dominant_component >= 0)
            cJSON_AddStringToObject(m, "dominant_component",
                                    component_name(s, md->dominant_component));
        else
            cJSON_AddNullToObject(m, "dominant_component");
        cJSON_AddBoolToObject(m, "rigid_body", md->rigid_body);
        cJSON_AddBoolToObject(m, "overdamped", md->overdamped);
        cJSON_AddBoolToObject(m, "unstable", md->unstable);
        if (s->model->nplanetary > 0) {
            cJSON_AddStringToObject(m, "class", mode_class(s, r, j));
            cJSON *pc = cJSON_AddObjectToObject(m, "planetary_classes");
            for (int k = 0; k < s->model->nplanetary; k++)
                cJSON_AddStringToObject(
                    pc, s->model->planetary[k].name,
                    gd_planetary_class_names[gd_modal_planetary_class(s, r, j, k)]);
        }
        add_num(m, "residual", md->residual);
        add_num(m, "residual_floor", md->residual_floor);
        cJSON *es = cJSON_AddObjectToObject(m, "energy_share");
        for (int k = 0; k < GD_NMOTIONS; k++)
            add_num(es, gd_motion_names[k], md->energy_share[k]);
        cJSON *ec = cJSON_AddObjectToObject(m, "energy_by_component");
        for (int c = 0; c < s->ncomponents; c++)
            add_num(ec, component_name(s, c),
                    r->energy_by_component[c + (size_t)j * s->ncomponents]);
        cJSON_AddItemToArray(modes, m);
    }
    return o;
}

static int write_csv(const gd_system *s, const gd_modal_result *r, const char *dir)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "modes.csv", &err);
    if (!f) goto fail;
    fprintf(f, "mode,omega_n_rad_s,frequency_hz,omega_d_rad_s,damping_ratio,log_decrement,"
               "whirl,dominant_motion,dominant_component,rigid_body,energy_lateral,"
               "energy_torsional,energy_axial,energy_tilt,residual\n");
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        fprintf(f, "%d,%.10g,%.10g,%.10g,%.10g,%.10g,%s,%s,%s,%d,%.6g,%.6g,%.6g,%.6g,%.3g\n", j + 1,
                md->omega_n, md->frequency_hz, md->omega_d, md->damping_ratio, md->log_decrement,
                gd_whirl_names[md->whirl], gd_motion_names[md->dominant_motion],
                component_name(s, md->dominant_component), md->rigid_body, md->energy_share[0],
                md->energy_share[1], md->energy_share[2], md->energy_share[3], md->residual);
    }
    if (gd_outdir_close(&od, f, "modes.csv", &err)) goto fail;
    f = gd_outdir_open(&od, "mode_shapes.csv", &err);
    if (!f) goto fail;
    fprintf(f, "mode,node,dof,real,imag,magnitude,phase_deg\n");
    for (int j = 0; j < r->nmodes; j++)
        for (int i = 0; i < s->ndof; i++) {
            double re = r->shape_re[i + (size_t)j * s->ndof],
                   im = r->shape_im[i + (size_t)j * s->ndof];
            fprintf(f, "%d,%s,%s,%.10g,%.10g,%.10g,%.6g\n", j + 1,
                    s->model->nodes[s->dof_node[i]].name, gd_dof_names[s->dof_type[i]], re, im,
                    hypot(re, im), atan2(im, re) * 180 / M_PI);
        }
    if (gd_outdir_close(&od, f, "mode_shapes.csv", &err)) goto fail;
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

int gd_cmd_modal(int argc, char **argv)
{
    modal_args a = {.nmodes = -1};
    gd_modal_options_init(&a.opt);
    a.opt.want_left = 0;
    a.opt.speed = -1; /* the model's */
    const char *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_modal_options opt = a.opt;
    const char *out = a.out, *plot = a.plot;
    int json = a.json, by_shaft = a.by_shaft, directional = a.directional;
    gd_error oerr;
    gd_error_clear(&oerr);
    if (out && gd_outdir_check(out, &oerr)) return gd_cli_report(&oerr);
    if (plot && (rc = gd_cli_plot_check(plot))) return rc;
    gd_model *m;
    gd_system *s;
    rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s);
    if (rc) return rc;
    if (opt.speed < 0) opt.speed = m->speed;
    if ((rc = gd_cli_operating_apply(s, &a.op, opt.speed, 1))) {
        gd_system_free(s);
        gd_model_free(m);
        return rc;
    }
    opt.nmodes = a.nmodes >= 0 ? a.nmodes : (s->ndof <= 30 ? 0 : 20);
    gd_modal_result *r = NULL;
    gd_error err;
    gd_error_clear(&err);
    gd_directional_result *dr = NULL;
    if (gd_modal_solve(s, &opt, &r, &err) ||
        (directional && gd_modal_directional(s, &opt, &dr, &err))) {
        if (r) gd_modal_free(r);
        rc = gd_cli_report(&err);
    } else {
        double tol = opt.tol > 0 ? opt.tol : GD_MODAL_TOL_DEFAULT;
        if (r->sparse) warn_residuals(s, r, tol);
        if (plot) {
            gd_plot *p = NULL;
            gd_status pst = gd_plot_modal(s, r, &p, &err);
            rc = gd_cli_plot_finish(pst, p, &err, plot);
        }
        if (out && rc == GD_EXIT_OK) rc = write_csv(s, r, out);
        if (rc == GD_EXIT_OK) {
            if (json) {
                cJSON *o = result_json(s, r, tol);
                if (by_shaft)
                    rc = gd_cli_shaft_json(cJSON_GetObjectItemCaseSensitive(o, "modes"), s, r);
                if (dr) cJSON_AddItemToObject(o, "directional", gd_cli_directional_json(dr));
                gd_cli_operating_json(o, s, &a.op, NULL, NULL, 0);
                if (!rc) gd_cli_print_json(stdout, o);
                cJSON_Delete(o);
            } else {
                print_table(s, r);
                if (by_shaft) rc = gd_cli_print_shaft_tables(stdout, s, r);
                if (dr) gd_cli_print_directional(stdout, dr);
                gd_cli_operating_print(s, &a.op, 0);
            }
        }
        gd_modal_free(r);
    }
    gd_directional_free(dr);
    gd_system_free(s);
    gd_model_free(m);
    return rc;
}
