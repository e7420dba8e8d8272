/* Output of the loaded tooth contact analysis and the Harris map (mesh_contact.h). */
#include "mesh_contact.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static cJSON *numbers(const double *x, size_t n)
{
    cJSON *a = cJSON_CreateArray();
    for (size_t i = 0; i < n && a; i++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(x[i]));
    return a;
}

static void describe_flags(const gd_ltca_result *r, char *buf, size_t size)
{
    int part = 0, edge = 0;
    for (size_t i = 0; i < r->points; i++) {
        part += (r->flags[i] & GD_LTCA_PARTIAL_FACE) != 0;
        edge += (r->flags[i] & GD_LTCA_EDGE_CONTACT) != 0;
    }
    snprintf(buf, size, "%d of %zu positions: partial face contact %d, edge contact %d", r->flagged,
             r->points, part, edge);
}

static cJSON *ltca_json(const gd_ltca_result *r, const char *file, const char *mesh, int arrays)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "file", file);
    cJSON_AddStringToObject(o, "mesh", mesh);
    cJSON_AddStringToObject(o, "analysis", "contact_analysis");
    cJSON_AddStringToObject(o, "method", gd_tvms_method_name(r->method));
    cJSON_AddNumberToObject(o, "slices", r->slices);
    cJSON_AddNumberToObject(o, "torque_N_m", r->torque);
    cJSON_AddNumberToObject(o, "normal_force_N", r->force);
    cJSON_AddNumberToObject(o, "misalignment_m", r->misalignment);
    cJSON_AddNumberToObject(o, "mesh_period_rad", r->mesh_period_rad);
    cJSON_AddStringToObject(o, "ste_convention",
                            "approach of the gears along the contact normal, m; the driver "
                            "lags by ste / (r_b1 cos beta_b) rad");
    cJSON_AddNumberToObject(o, "ste_mean", r->ste_mean);
    cJSON_AddNumberToObject(o, "ste_peak_to_peak", r->ste_peak_to_peak);
    cJSON_AddNumberToObject(o, "stiffness_mean", r->stiffness_mean);
    cJSON_AddNumberToObject(o, "stiffness_min", r->stiffness_min);
    cJSON_AddNumberToObject(o, "stiffness_max", r->stiffness_max);
    cJSON_AddNumberToObject(o, "face_load_factor", r->face_load_factor_cycle);
    cJSON_AddNumberToObject(o, "body_stiffness", r->body_stiffness);
    cJSON_AddNumberToObject(o, "flagged_positions", r->flagged);
    cJSON_AddNumberToObject(o, "slice_width_m", r->slice_width);
    cJSON_AddItemToObject(o, "line_load_mean", numbers(r->line_load_mean, (size_t)r->slices));
    if (arrays) {
        cJSON_AddItemToObject(o, "angle_rad", numbers(r->angle_rad, r->n));
        cJSON_AddItemToObject(o, "ste", numbers(r->ste, r->n));
        cJSON_AddItemToObject(o, "ste_unloaded", numbers(r->ste_unloaded, r->n));
        cJSON_AddItemToObject(o, "stiffness", numbers(r->stiffness, r->n));
        cJSON_AddItemToObject(o, "pairs_in_contact",
                              cJSON_CreateIntArray(r->pairs_in_contact, (int)r->n));
        cJSON_AddItemToObject(o, "face_load_factor_at", numbers(r->face_load_factor, r->n));
        cJSON_AddItemToObject(o, "flags", cJSON_CreateIntArray(r->flags, (int)r->n));
        cJSON *pl = cJSON_AddArrayToObject(o, "pair_load");
        cJSON *ll = cJSON_AddArrayToObject(o, "line_load");
        for (size_t i = 0; i < r->n; i++) {
            cJSON_AddItemToArray(
                pl, numbers(r->pair_load + i * (size_t)r->max_pairs, (size_t)r->max_pairs));
            cJSON_AddItemToArray(ll,
                                 numbers(r->line_load + i * (size_t)r->slices, (size_t)r->slices));
        }
    }
    return o;
}

static void ltca_csv(FILE *f, const gd_ltca_result *r)
{
    fprintf(f, "angle_rad,ste_m,ste_unloaded_m,stiffness_N_per_m,pairs_in_contact,"
               "face_load_factor,flags");
    for (int j = 0; j < r->max_pairs; j++)
        fprintf(f, ",pair_load_%d_N", j);
    fputc('\n', f);
    for (size_t i = 0; i < r->n; i++) {
        fprintf(f, "%.10g,%.10g,%.10g,%.10g,%d,%.6g,%d", r->angle_rad[i], r->ste[i],
                r->ste_unloaded[i], r->stiffness[i], r->pairs_in_contact[i], r->face_load_factor[i],
                r->flags[i]);
        for (int j = 0; j < r->max_pairs; j++)
            fprintf(f, ",%.6g", r->pair_load[i * (size_t)r->max_pairs + j]);
        fputc('\n', f);
    }
}

static void line_load_csv(FILE *f, const gd_ltca_result *r)
{
    fprintf(f, "angle_rad");
    for (int j = 0; j < r->slices; j++)
        fprintf(f, ",y_%.6g_mm", (j + 0.5) * r->slice_width * 1e3);
    fputc('\n', f);
    for (size_t i = 0; i < r->n; i++) {
        fprintf(f, "%.10g", r->angle_rad[i]);
        for (int j = 0; j < r->slices; j++)
            fprintf(f, ",%.6g", r->line_load[i * (size_t)r->slices + j]);
        fputc('\n', f);
    }
}

static void ltca_text(const gd_ltca_result *r, const char *file, const char *mesh, int csv)
{
    char flags[160];
    describe_flags(r, flags, sizeof flags);
    printf("mesh             %s (%s)\n", mesh, file);
    printf("contact analysis %s, %d slice%s, driver torque %g N m, normal load %.6g N\n",
           gd_tvms_method_name(r->method), r->slices, r->slices == 1 ? "" : "s", r->torque,
           r->force);
    printf("misalignment     %g um (back face minus front face)\n", r->misalignment * 1e6);
    printf("loaded TE (um)   mean %.5g  peak-to-peak %.5g  (along the contact normal)\n",
           r->ste_mean * 1e6, r->ste_peak_to_peak * 1e6);
    printf("stiffness (N/m)  mean %.5g  max %.5g  min %.5g  at this load\n", r->stiffness_mean,
           r->stiffness_max, r->stiffness_min);
    printf("face load factor K_Hbeta %.4f (line load averaged over a mesh cycle)\n",
           r->face_load_factor_cycle);
    printf("flags            %s\n", flags);
    if (csv) {
        printf("\n");
        ltca_csv(stdout, r);
    }
}

static cJSON *map_json(const gd_ltca_map *m, const char *file, const char *mesh, int arrays)
{
    cJSON *o = cJSON_CreateObject();
    const size_t L = (size_t)m->nloads;
    cJSON_AddStringToObject(o, "file", file);
    cJSON_AddStringToObject(o, "mesh", mesh);
    cJSON_AddStringToObject(o, "analysis", "harris_map");
    cJSON_AddItemToObject(o, "torque_N_m", numbers(m->torque, L));
    cJSON_AddItemToObject(o, "ste_peak_to_peak", numbers(m->ste_peak_to_peak, L));
    cJSON_AddItemToObject(o, "ste_mean", numbers(m->ste_mean, L));
    cJSON_AddItemToObject(o, "stiffness_mean", numbers(m->stiffness_mean, L));
    cJSON_AddItemToObject(o, "face_load_factor", numbers(m->face_load_factor_cycle, L));
    cJSON_AddItemToObject(o, "flagged_positions", cJSON_CreateIntArray(m->flagged, m->nloads));
    if (arrays) {
        cJSON_AddItemToObject(o, "ste_unloaded", numbers(m->ste_unloaded, m->points));
        cJSON *a = cJSON_AddArrayToObject(o, "ste");
        for (size_t l = 0; l < L; l++)
            cJSON_AddItemToArray(a, numbers(m->ste + l * m->points, m->points));
    }
    return o;
}

static void map_csv(FILE *f, const gd_ltca_map *m)
{
    fprintf(f, "torque_N_m,ste_peak_to_peak_m,ste_mean_m,stiffness_mean_N_per_m,"
               "face_load_factor,flagged_positions\n");
    for (int l = 0; l < m->nloads; l++)
        fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.6g,%d\n", m->torque[l], m->ste_peak_to_peak[l],
                m->ste_mean[l], m->stiffness_mean[l], m->face_load_factor_cycle[l], m->flagged[l]);
}

static void map_text(const gd_ltca_map *m, const char *file, const char *mesh, int csv)
{
    int best = 0;
    for (int l = 1; l < m->nloads; l++)
        if (m->ste_peak_to_peak[l] < m->ste_peak_to_peak[best]) best = l;
    printf("mesh             %s (%s)\n", mesh, file);
    printf("Harris map       %d driver torques from %g to %g N m\n", m->nloads, m->torque[0],
           m->torque[m->nloads - 1]);
    printf("smallest p-p TE  %.5g um at %g N m\n", m->ste_peak_to_peak[best] * 1e6,
           m->torque[best]);
    if (csv) {
        printf("\n");
        map_csv(stdout, m);
    }
}

typedef void (*csv_fn)(FILE *f, const void *r);

/* Writes the named CSV files and summary.json into dir, all or nothing. */
static int write_dir(const char *dir, const char *const *names, const csv_fn *fns, int nf,
                     const void *r, cJSON *summary)
{
    gd_error err;
    gd_error_clear(&err);
    gd_outdir od;
    if (gd_outdir_begin(&od, dir, &err)) return gd_cli_report(&err);
    for (int i = 0; i <= nf; i++) {
        const char *name = i < nf ? names[i] : "summary.json";
        FILE *f = gd_outdir_open(&od, name, &err);
        if (!f) goto fail;
        if (i < nf)
            fns[i](f, r);
        else
            gd_cli_print_json(f, summary);
        if (gd_outdir_close(&od, f, name, &err)) goto fail;
    }
    if (gd_outdir_commit(&od, &err)) return gd_cli_report(&err);
    return GD_EXIT_OK;
fail:
    gd_outdir_abort(&od);
    return gd_cli_report(&err);
}

static void ltca_csv_v(FILE *f, const void *r)
{
    ltca_csv(f, r);
}
static void line_load_csv_v(FILE *f, const void *r)
{
    line_load_csv(f, r);
}
static void map_csv_v(FILE *f, const void *r)
{
    map_csv(f, r);
}

int gd_cli_mesh_contact(const char *file, const char *mesh, const gd_gear_pair_geometry *g,
                        const gd_tvms_options *opt, const double *loads, int nloads, int json,
                        const char *out)
{
    gd_error err;
    gd_error_clear(&err);
    int rc = GD_EXIT_OK;
    if (nloads == 0) {
        gd_ltca_result *r = NULL;
        if (gd_ltca_compute(g, opt, &r, &err)) {
            if (!err.file[0]) snprintf(err.file, sizeof err.file, "%s", file);
            return gd_cli_report(&err);
        }
        if (out) {
            static const char *const names[2] = {"contact_analysis.csv", "line_load.csv"};
            static const csv_fn fns[2] = {ltca_csv_v, line_load_csv_v};
            cJSON *summary = ltca_json(r, file, mesh, 0);
            rc = write_dir(out, names, fns, 2, r, summary);
            cJSON_Delete(summary);
        }
        if (rc == GD_EXIT_OK) {
            if (json) {
                cJSON *o = ltca_json(r, file, mesh, 1);
                gd_cli_print_json(stdout, o);
                cJSON_Delete(o);
            } else {
                ltca_text(r, file, mesh, !out);
            }
        }
        gd_ltca_free(r);
        return rc;
    }
    gd_ltca_map *m = NULL;
    if (gd_ltca_map_compute(g, opt, loads, nloads, &m, &err)) {
        if (!err.file[0]) snprintf(err.file, sizeof err.file, "%s", file);
        return gd_cli_report(&err);
    }
    if (out) {
        static const char *const names[1] = {"harris_map.csv"};
        static const csv_fn fns[1] = {map_csv_v};
        cJSON *summary = map_json(m, file, mesh, 0);
        rc = write_dir(out, names, fns, 1, m, summary);
        cJSON_Delete(summary);
    }
    if (rc == GD_EXIT_OK) {
        if (json) {
            cJSON *o = map_json(m, file, mesh, 1);
            gd_cli_print_json(stdout, o);
            cJSON_Delete(o);
        } else {
            map_text(m, file, mesh, !out);
        }
    }
    gd_ltca_map_free(m);
    return rc;
}
