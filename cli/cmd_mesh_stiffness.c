/* geardyn mesh-stiffness FILE: contact ratios and time-varying mesh stiffness of a
 * gear pair described by its geometry (docs/mesh-stiffness.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "mesh_contact.h"
#include "options.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/model_file.h"
#include "geardyn/units.h"

/* --load-range: torques in N m, 0 = no --load-range */
typedef struct ms_range {
    double from, to;
    long count;
} ms_range;

typedef struct ms_args {
    const char *file, *mesh, *out, *plot, *compare;
    int json, method;           /* method: -1 = the file's */
    int points, cycles, slices; /* 0 = not given */
    int has_helix, has_load, has_misalignment;
    double helix, load, misalignment; /* rad, N m, m */
    ms_range range;
    gd_cli_sets sets;
} ms_args;

static int parse_method(const char *cmd, const char *text, void *method)
{
    gd_tvms_method m;
    if (gd_tvms_method_parse(text, &m, NULL))
        return gd_cli_usage_error(
            cmd, "--method: unknown method '%s' (use energy, iso6336, single-pair-law or square)",
            text);
    *(int *)method = (int)m;
    return 0;
}

/* FROM:TO:COUNT, torques with units, 2 <= COUNT <= 1000, 0 < FROM < TO. */
static int parse_range(const char *cmd, const char *text, void *range)
{
    ms_range *r = range;
    char buf[200];
    snprintf(buf, sizeof buf, "%s", text);
    char *c1 = strchr(buf, ':'), *c2 = c1 ? strchr(c1 + 1, ':') : NULL;
    if (!c2)
        return gd_cli_usage_error(cmd, "--load-range: write FROM:TO:COUNT, e.g. 50Nm:500Nm:20");
    *c1 = *c2 = '\0';
    gd_error why;
    if (gd_parse_quantity(buf, GD_QTY_TORQUE, &r->from, &why) ||
        gd_parse_quantity(c1 + 1, GD_QTY_TORQUE, &r->to, &why))
        return gd_cli_usage_error(cmd, "--load-range: %s (e.g. 50Nm:500Nm:20)", why.message);
    if (gd_cli_parse_count(c2 + 1, 2, 1000, &r->count))
        return gd_cli_usage_error(
            cmd, "--load-range: count '%s' is not a whole number from 2 to 1000", c2 + 1);
    if (!(r->from > 0 && r->to > r->from))
        return gd_cli_usage_error(cmd, "--load-range: give 0 < FROM < TO (driver torques)");
    return 0;
}

#define F(m) offsetof(ms_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("mesh", GD_CLI_STRING, F(mesh), "NAME", "the mesh to use",
               .def = "the first with a geometry"),
    GD_CLI_ROW("method", GD_CLI_CALL, F(method), "M", "energy | iso6336 | single-pair-law | square",
               .def = "energy", .call = parse_method),
    GD_CLI_ROW("points", GD_CLI_INT, F(points), "N", "samples per mesh cycle",
               .def = "360, or the file's", .lo = 8, .hi = 1000000),
    GD_CLI_ROW("cycles", GD_CLI_INT, F(cycles), "N", "mesh cycles sampled", .def = "1", .lo = 1,
               .hi = 10000),
    GD_CLI_ROW("slices", GD_CLI_INT, F(slices), "N", "face-width slices of a helical pair",
               .def = "50", .lo = 1, .hi = 100000),
    GD_CLI_ROW("helix-angle", GD_CLI_QUANTITY, F(helix), "VALUE",
               "override the helix angle, e.g. \"15 deg\" (plain numbers are rad)",
               .qty = GD_QTY_ANGLE, .example = "\"15 deg\"", .aux = F(has_helix)),
    GD_CLI_ROW("set", GD_CLI_SETS, F(sets), "PATH=VALUE",
               "change a value of the file first, e.g. --set "
               "meshes.pair1.geometry.face_width=30mm (repeatable; docs/model-format.md, "
               "\"Overrides (--set)\")"),
    GD_CLI_ROW("json", GD_CLI_FLAG, F(json), NULL, "print everything as one JSON object"),
    GD_CLI_ROW_OUT(ms_args, out, "write DIR/mesh_stiffness.csv and DIR/summary.json"),
    GD_CLI_ROW("plot", GD_CLI_STRING, F(plot), "FILE",
               "TVMS with single/double contact zones, pair stiffnesses and harmonics: FILE.svg "
               "or FILE.html (docs/plots.md)"),
    GD_CLI_ROW("compare-helix", GD_CLI_STRING, F(compare), "LIST",
               "the plot also compares these helix angles, e.g. 0,10deg,20deg"),
    GD_CLI_ROW("load", GD_CLI_QUANTITY, F(load), "TORQUE",
               "loaded tooth contact analysis at this driver torque, e.g. \"200 N m\": loaded "
               "transmission error, stiffness at that load, load per tooth pair and across the "
               "face, face load factor (the tooth modifications of the file count)",
               .def = "the file's `stiffness: {from: contact_analysis, load: ...}`",
               .lo = GD_CLI_ABOVE_ZERO, .qty = GD_QTY_TORQUE, .example = "\"200 N m\"",
               .aux = F(has_load)),
    GD_CLI_ROW("load-range", GD_CLI_CALL, F(range), "F:T:N",
               "Harris map: peak-to-peak transmission error at N driver torques from F to T, "
               "e.g. 50Nm:500Nm:20",
               .call = parse_range),
    GD_CLI_ROW("misalignment", GD_CLI_QUANTITY, F(misalignment), "L",
               "relative tilt in the plane of action as the separation at the back face minus "
               "the front face, e.g. \"10 um\"",
               .qty = GD_QTY_LENGTH, .example = "\"10 um\"", .aux = F(has_misalignment)),
    {0}};
static const gd_cli_command CMD = {
    .name = "mesh-stiffness",
    .args = "FILE",
    .missing = "give exactly one FILE",
    .opts = OPTS,
    .about =
        "Computes, from the geometry of a gear pair (a mesh entry with a `geometry:` map, in a\n"
        "model file or a stand-alone file with `meshes:`), the transverse, face and total\n"
        "contact ratios, base pitch, mesh period and the time-varying mesh stiffness k(angle)\n"
        "over the driver's rotation angle: pairs in contact, load shares, mean, max, min,\n"
        "peak-to-peak and Fourier harmonics. k acts along the contact normal (normal plane).\n",
    .footer = "Exit status: 0 ok, 2 bad input or usage, 1 numerical failure.\n"};

static int parse_args(int argc, char **argv, ms_args *a)
{
    const char *cmd = "mesh-stiffness";
    int rc = gd_cli_parse(&CMD, argc, argv, a, &a->file);
    if (rc) return rc;
    if (a->compare && !a->plot) return gd_cli_usage_error(cmd, "--compare-helix goes with --plot");
    if (a->has_load && a->range.count)
        return gd_cli_usage_error(cmd, "give --load or --load-range, not both");
    if (a->plot && (a->has_load || a->range.count))
        return gd_cli_usage_error(cmd, "--plot draws the unloaded TVMS: leave out --load and "
                                       "--load-range");
    return 0;
}

static cJSON *numbers(const double *x, size_t n)
{
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n && a; i++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(x[i]));
    return a;
}

static cJSON *make_json(const gd_tvms_result *r, const gd_gear_pair_geometry *g, const char *file,
                        const char *mesh, int arrays)
{
    const gd_gear_pair_derived *d = &r->geom;
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "file", file);
    cJSON_AddStringToObject(o, "mesh", mesh);
    cJSON_AddStringToObject(o, "method", gd_tvms_method_name(r->method));
    cJSON_AddNumberToObject(o, "slices", r->slices);
    cJSON_AddStringToObject(o, "stiffness_convention",
                            "N/m along the contact normal (normal plane): k in K = k a a^T; "
                            "transverse k_t = k cos^2(beta_b)");
    cJSON_AddStringToObject(o, "angle",
                            "driver rotation in rad from the start of contact of a tooth pair");
    int teeth[2] = {g->gear[0].teeth, g->gear[1].teeth};
    cJSON_AddItemToObject(o, "teeth", cJSON_CreateIntArray(teeth, 2));
    cJSON_AddBoolToObject(o, "internal", d->internal);
    if (d->internal) cJSON_AddNumberToObject(o, "trochoid_margin_rad", d->trochoid_margin);
    cJSON_AddNumberToObject(o, "contact_ratio_transverse", d->contact_ratio_transverse);
    cJSON_AddNumberToObject(o, "contact_ratio_face", d->contact_ratio_face);
    cJSON_AddNumberToObject(o, "contact_ratio_total", d->contact_ratio_total);
    cJSON_AddNumberToObject(o, "base_pitch_transverse_m", d->base_pitch_transverse);
    cJSON_AddNumberToObject(o, "base_pitch_normal_m", d->base_pitch_normal);
    cJSON_AddNumberToObject(o, "mesh_period_rad", r->mesh_period_rad);
    cJSON_AddNumberToObject(o, "center_distance_m", d->center_distance);
    cJSON_AddNumberToObject(o, "path_of_contact_m", d->contact_length);
    cJSON_AddNumberToObject(o, "pitch_point_m", d->pitch_point);
    cJSON_AddNumberToObject(o, "transverse_pressure_angle_rad", d->transverse_pressure_angle);
    cJSON_AddNumberToObject(o, "working_pressure_angle_rad", d->working_pressure_angle);
    cJSON_AddNumberToObject(o, "base_helix_angle_rad", d->base_helix_angle);
    cJSON_AddItemToObject(o, "pitch_radius_m", cJSON_CreateDoubleArray(d->pitch_radius, 2));
    cJSON_AddItemToObject(o, "base_radius_m", cJSON_CreateDoubleArray(d->base_radius, 2));
    cJSON_AddItemToObject(o, "tip_radius_m", cJSON_CreateDoubleArray(d->tip_radius, 2));
    cJSON_AddItemToObject(o, "root_radius_m", cJSON_CreateDoubleArray(d->root_radius, 2));
    cJSON_AddItemToObject(o, "bore_radius_m", cJSON_CreateDoubleArray(d->bore_radius, 2));
    cJSON_AddNumberToObject(o, "stiffness_mean", r->mean);
    cJSON_AddNumberToObject(o, "stiffness_max", r->max);
    cJSON_AddNumberToObject(o, "stiffness_min", r->min);
    cJSON_AddNumberToObject(o, "stiffness_peak_to_peak", r->peak_to_peak);
    cJSON_AddNumberToObject(o, "stiffness_transverse_mean", r->mean * r->transverse_factor);
    cJSON_AddNumberToObject(o, "iso6336_single_stiffness", r->iso_single_stiffness);
    cJSON_AddNumberToObject(o, "iso6336_mesh_stiffness_alpha", r->iso_mesh_stiffness_alpha);
    cJSON_AddNumberToObject(o, "iso6336_mesh_stiffness_beta", r->iso_mesh_stiffness_beta);
    cJSON_AddNumberToObject(o, "body_stiffness", r->body_stiffness);
    cJSON *h = cJSON_AddArrayToObject(o, "harmonics");
    for (int i = 0; i < r->harmonics; i++) {
        cJSON *j = cJSON_CreateObject();
        cJSON_AddNumberToObject(j, "order", i + 1);
        cJSON_AddNumberToObject(j, "amplitude", r->harmonic_amplitude[i]);
        cJSON_AddNumberToObject(j, "phase_rad", r->harmonic_phase[i]);
        cJSON_AddItemToArray(h, j);
    }
    if (arrays) {
        cJSON_AddItemToObject(o, "angle_rad", numbers(r->angle_rad, r->n));
        cJSON_AddItemToObject(o, "stiffness", numbers(r->stiffness, r->n));
        cJSON_AddItemToObject(o, "pairs_in_contact",
                              cJSON_CreateIntArray(r->pairs_in_contact, (int)r->n));
        cJSON *ls = cJSON_AddArrayToObject(o, "load_share");
        for (size_t i = 0; i < r->n; i++)
            cJSON_AddItemToArray(
                ls, numbers(r->load_share + i * (size_t)r->max_pairs, (size_t)r->max_pairs));
    }
    return o;
}

static void write_csv(FILE *f, const gd_tvms_result *r)
{
    fprintf(f, "angle_rad,stiffness_N_per_m,pairs_in_contact");
    for (int j = 0; j < r->max_pairs; j++)
        fprintf(f, ",load_share_%d", j);
    fputc('\n', f);
    for (size_t i = 0; i < r->n; i++) {
        fprintf(f, "%.10g,%.10g,%d", r->angle_rad[i], r->stiffness[i], r->pairs_in_contact[i]);
        for (int j = 0; j < r->max_pairs; j++)
            fprintf(f, ",%.6g", r->load_share[i * (size_t)r->max_pairs + j]);
        fputc('\n', f);
    }
}

static void print_text(const gd_tvms_result *r, const gd_gear_pair_geometry *g, const char *file,
                       const char *mesh, int csv)
{
    const gd_gear_pair_derived *d = &r->geom;
    printf("mesh             %s (%s)\n", mesh, file);
    printf("method           %s, %d slice%s\n", gd_tvms_method_name(r->method), r->slices,
           r->slices == 1 ? "" : "s");
    printf("teeth            %d / %d%s, normal module %g mm, helix %g deg\n", g->gear[0].teeth,
           g->gear[1].teeth, d->internal ? " (internal: the driven gear is a ring)" : "",
           g->normal_module * 1e3, g->helix_angle * 180 / M_PI);
    if (d->internal)
        printf("internal pair    centre distance %.6g mm, working pressure angle %.6g deg, "
               "trochoid margin %.4g rad\n",
               d->center_distance * 1e3, d->working_pressure_angle * 180 / M_PI,
               d->trochoid_margin);
    printf("contact ratio    transverse %.4f  face %.4f  total %.4f\n", d->contact_ratio_transverse,
           d->contact_ratio_face, d->contact_ratio_total);
    printf("base pitch       transverse %.6g mm, normal %.6g mm\n", d->base_pitch_transverse * 1e3,
           d->base_pitch_normal * 1e3);
    printf("mesh period      %.6g rad of driver rotation (2 pi / %d)\n", r->mesh_period_rad,
           g->gear[0].teeth);
    printf("stiffness (N/m)  mean %.5g  max %.5g  min %.5g  peak-to-peak %.5g\n", r->mean, r->max,
           r->min, r->peak_to_peak);
    printf("                 along the contact normal; transverse mean %.5g\n",
           r->mean * r->transverse_factor);
    printf("ISO 6336-1       c'b %.5g  c_gamma_alpha b %.5g  c_gamma_beta b %.5g N/m\n",
           r->iso_single_stiffness, r->iso_mesh_stiffness_alpha, r->iso_mesh_stiffness_beta);
    if (r->body_stiffness > 0) printf("gear bodies      %.5g N/m in series\n", r->body_stiffness);
    if (r->harmonics) {
        printf("harmonics        order  amplitude(N/m)  phase(rad)\n");
        for (int i = 0; i < r->harmonics; i++)
            printf("                 %5d  %14.5g  %10.4f\n", i + 1, r->harmonic_amplitude[i],
                   r->harmonic_phase[i]);
    }
    if (csv) {
        printf("\n");
        write_csv(stdout, r);
    }
}

static int write_out(const char *dir, const gd_tvms_result *r, cJSON *summary)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    FILE *f = gd_outdir_open(&od, "mesh_stiffness.csv", &err);
    if (!f) goto fail;
    write_csv(f, r);
    if (gd_outdir_close(&od, f, "mesh_stiffness.csv", &err)) goto fail;
    f = gd_outdir_open(&od, "summary.json", &err);
    if (!f) goto fail;
    gd_cli_print_json(f, summary);
    if (gd_outdir_close(&od, f, "summary.json", &err)) goto fail;
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

enum { MAX_COMPARE = 8 };

/* The figure, with the pair recomputed at the --compare-helix angles. */
static int plot_tvms(const ms_args *a, const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                     const gd_tvms_result *res, const char *mesh)
{
    const gd_tvms_result *rs[MAX_COMPARE + 1] = {res};
    gd_tvms_result *own[MAX_COMPARE + 1] = {NULL};
    char label[MAX_COMPARE + 1][48];
    const char *labels[MAX_COMPARE + 1];
    int n = 1, rc = GD_EXIT_OK;
    gd_error err;
    gd_error_clear(&err);
    snprintf(label[0], sizeof label[0], "helix %.4g deg", g->helix_angle * 180 / M_PI);
    labels[0] = label[0];
    char buf[512];
    snprintf(buf, sizeof buf, "%s", a->compare ? a->compare : "");
    for (char *save = NULL, *tok = strtok_r(buf, ",", &save); tok && rc == GD_EXIT_OK;
         tok = strtok_r(NULL, ",", &save)) {
        gd_gear_pair_geometry h = *g;
        gd_error why;
        gd_tvms_result *r = NULL;
        if (n > MAX_COMPARE)
            rc = gd_cli_usage_error("mesh-stiffness", "--compare-helix: at most %d angles",
                                    MAX_COMPARE);
        else if (gd_parse_quantity(tok, GD_QTY_ANGLE, &h.helix_angle, &why))
            rc = gd_cli_usage_error("mesh-stiffness", "--compare-helix: %s (e.g. 0,10deg,20deg)",
                                    why.message);
        else if (gd_tvms_compute(&h, opt, &r, &err)) {
            snprintf(err.field, sizeof err.field, "--compare-helix");
            rc = gd_cli_report(&err);
        } else {
            snprintf(label[n], sizeof label[n], "helix %.4g deg", h.helix_angle * 180 / M_PI);
            labels[n] = label[n];
            own[n] = r;
            rs[n++] = r;
        }
    }
    if (rc == GD_EXIT_OK) {
        gd_plot *p = NULL;
        gd_status st = gd_plot_tvms(rs, labels, n, mesh, &p, &err);
        rc = gd_cli_plot_finish(st, p, &err, a->plot);
    }
    for (int k = 1; k < n; k++)
        gd_tvms_free(own[k]);
    return rc;
}

/* --load, --load-range and --misalignment past what the contact analysis can mean gave
 * inf and NaN rows with exit 0 (issue 38 M7): the bounds the model reader puts on the
 * file's load and misalignment (mesh_geometry_read.c): the normal force
 * T / (r_b1 cos beta_b) at most E b m_n (a tooth section b x m_n strained by 1), the
 * misalignment at most the normal module. */
static int check_loading(const ms_args *a, const gd_gear_pair_geometry *g,
                         const gd_tvms_options *opt)
{
    gd_gear_pair_derived d;
    gd_error err;
    gd_error_clear(&err);
    if (gd_gear_pair_derive(g, &d, &err)) return 0; /* the analysis reports the geometry */
    const double E = fmin(g->gear[0].E, g->gear[1].E), mn = g->normal_module;
    const double fmax_n = E * g->face_width * mn;
    const double per_torque = 1.0 / (d.base_radius[0] * cos(d.base_helix_angle));
    const double t = a->range.count ? a->range.to : opt->load_torque;
    if ((a->range.count || a->has_load) && !(fabs(t) * per_torque <= fmax_n))
        return gd_cli_usage_error("mesh-stiffness",
                                  "%s: a driver torque of %g N m is a normal load of %g N, over "
                                  "E b m_n = %.4g N (a tooth section strained by 1): give at "
                                  "most %.4g N m",
                                  a->range.count ? "--load-range" : "--load", t,
                                  fabs(t) * per_torque, fmax_n, fmax_n / per_torque);
    if (a->has_misalignment && !(fabs(opt->misalignment) <= mn))
        return gd_cli_usage_error("mesh-stiffness",
                                  "--misalignment: %g m is over the normal module (%g m): "
                                  "flanks parting by more across the face do not mesh",
                                  opt->misalignment, mn);
    return 0;
}

int gd_cmd_mesh_stiffness(int argc, char **argv)
{
    ms_args a = {.method = -1};
    int rc = parse_args(argc, argv, &a);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;

    gd_error err;
    gd_error_clear(&err);
    gd_gear_pair_geometry g;
    gd_tvms_options opt;
    gd_tvms_result *res = NULL;
    char mesh_name[GD_NODE_NAME_MAX];
    gd_load_options lo = gd_cli_load_options(&a.sets);
    if (a.plot && (rc = gd_cli_plot_check(a.plot))) return rc;
    if (gd_gear_pair_load(a.file, a.mesh, &lo, &g, &opt, mesh_name, sizeof mesh_name, &err))
        return gd_cli_report(&err);
    if (a.method >= 0) opt.method = (gd_tvms_method)a.method;
    if (a.points) opt.points = (int)a.points;
    if (a.cycles) opt.cycles = (int)a.cycles;
    if (a.slices) opt.slices = (int)a.slices;
    if (a.has_helix) g.helix_angle = a.helix;
    if (a.has_misalignment && !a.has_load && !a.range.count && !opt.contact_analysis)
        return gd_cli_usage_error("mesh-stiffness",
                                  "--misalignment goes with --load or --load-range (the unloaded "
                                  "TVMS does not depend on it)");
    if (a.has_misalignment) opt.misalignment = a.misalignment;
    if (a.has_load) opt.load_torque = a.load;
    if ((rc = check_loading(&a, &g, &opt))) return rc;
    if (a.has_load || a.range.count || (opt.contact_analysis && !a.plot)) {
        /* the loaded contact analysis (the file's load unless --load) or the Harris map */
        double *loads = NULL;
        int nl = (int)a.range.count;
        if (nl) {
            loads = malloc((size_t)nl * sizeof *loads);
            if (!loads) return gd_cli_usage_error("mesh-stiffness", "out of memory");
            for (int l = 0; l < nl; l++)
                loads[l] = a.range.from + (a.range.to - a.range.from) * l / (nl - 1);
        }
        rc = gd_cli_mesh_contact(a.file, mesh_name, &g, &opt, loads, nl, a.json, a.out);
        free(loads);
        return rc;
    }
    if (gd_tvms_compute(&g, &opt, &res, &err)) {
        /* the file's geometry and options were checked when loading: what fails now
         * comes from the options given here */
        if (a.has_helix && !strcmp(err.field, "helix_angle"))
            snprintf(err.field, sizeof err.field, "--helix-angle");
        if (!err.file[0]) snprintf(err.file, sizeof err.file, "%s", a.file);
        return gd_cli_report(&err);
    }
    rc = GD_EXIT_OK;
    if (a.plot && (rc = plot_tvms(&a, &g, &opt, res, mesh_name))) {
        gd_tvms_free(res);
        return rc;
    }
    if (a.out) {
        cJSON *summary = make_json(res, &g, a.file, mesh_name, 0);
        rc = write_out(a.out, res, summary);
        cJSON_Delete(summary);
    }
    if (rc == GD_EXIT_OK) {
        if (a.json) {
            cJSON *o = make_json(res, &g, a.file, mesh_name, 1);
            gd_cli_print_json(stdout, o);
            cJSON_Delete(o);
        } else {
            print_text(res, &g, a.file, mesh_name, !a.out);
        }
    }
    gd_tvms_free(res);
    return rc;
}
