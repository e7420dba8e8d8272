/* `geardyn transient --rattle` (transient_rattle.h): the contact-event log of the run cut
 * per backlash mesh and handed to gd_rattle_metrics_eval with the mesh's effective mass
 * (gd_transient_mesh_mass), then printed as a table and as JSON. */
#include "transient_rattle.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

void gd_cli_rattle_free(gd_cli_rattle *r)
{
    free(r->mesh);
    free(r->mass);
    free(r->metrics);
    memset(r, 0, sizeof *r);
}

int gd_cli_rattle_analyse(gd_transient *tr, const gd_transient_model *tm,
                          const gd_transient_result *res, double from, double t_end, int batches,
                          double target, gd_cli_rattle *r)
{
    memset(r, 0, sizeof *r);
    r->target = target;
    int nm = tm->spec.nmeshes;
    r->mesh = calloc((size_t)(nm > 0 ? nm : 1), sizeof *r->mesh);
    r->mass = calloc((size_t)(nm > 0 ? nm : 1), sizeof *r->mass);
    r->metrics = calloc((size_t)(nm > 0 ? nm : 1), sizeof *r->metrics);
    gd_rattle_event *ev =
        malloc((size_t)(res->ncontact_events > 0 ? res->ncontact_events : 1) * sizeof *ev);
    if (!r->mesh || !r->mass || !r->metrics || !ev) {
        free(ev);
        fprintf(stderr, "geardyn: error: out of memory\n");
        return GD_EXIT_FAIL;
    }
    for (int i = 0; i < nm; i++) {
        if (!tm->meshes[i].backlash) continue;
        int n = 0;
        for (int k = 0; k < res->ncontact_events; k++) {
            const gd_tr_contact_event *e = &res->contact_events[k];
            if (e->mesh != i) continue;
            ev[n++] = (gd_rattle_event){e->t, e->from, e->to, e->velocity};
        }
        /* with no change in the window, the state it held throughout */
        const gd_tr_contact_stats *c = &res->contacts[i];
        gd_rattle_options o;
        gd_rattle_options_init(&o);
        o.t0 = from;
        o.t1 = t_end;
        o.batches = batches;
        o.target = target;
        o.state0 = c->drive_time > 0 ? 1 : (c->coast_time > 0 ? -1 : 0);
        gd_error err;
        gd_error_clear(&err);
        double mass = 0.0;
        if (gd_transient_mesh_mass(tr, i, &mass, &err)) mass = 0.0; /* reduced: m^2/s^3 */
        o.mass = mass;
        int j = r->n;
        if (gd_rattle_metrics_eval(ev, n, &o, &r->metrics[j], &err)) {
            free(ev);
            return gd_cli_report(&err);
        }
        r->mesh[j] = i;
        r->mass[j] = mass;
        r->n++;
    }
    free(ev);
    return 0;
}

static cJSON *estimate_json(const gd_rattle_estimate *e)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddItemToObject(o, "mean", gd_cli_json_number(e->mean));
    cJSON_AddItemToObject(o, "half_width", gd_cli_json_number(e->half_width));
    return o;
}

static cJSON *int_array(const int *x, int n)
{
    cJSON *a = cJSON_CreateArray();
    for (int k = 0; k < n; k++)
        cJSON_AddItemToArray(a, cJSON_CreateNumber(x[k]));
    return a;
}

cJSON *gd_cli_rattle_json(const gd_cli_rattle *r, const gd_model *m, const gd_transient_model *tm)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddNumberToObject(o, "target_relative_half_width", r->target);
    cJSON *a = cJSON_AddArrayToObject(o, "meshes");
    for (int j = 0; j < r->n; j++) {
        const gd_rattle_metrics *x = &r->metrics[j];
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "name", gd_model_mesh_name(m, tm->meshes[r->mesh[j]].mesh));
        cJSON_AddNumberToObject(e, "window_s", x->duration);
        cJSON_AddNumberToObject(e, "batches", x->batches);
        cJSON_AddNumberToObject(e, "confidence", x->confidence);
        cJSON_AddNumberToObject(e, "effective_mass_kg", r->mass[j]);
        cJSON_AddItemToObject(e, "separated_fraction", estimate_json(&x->separated));
        cJSON_AddItemToObject(e, "drive_impacts_per_s", estimate_json(&x->drive_rate));
        cJSON_AddItemToObject(e, "coast_impacts_per_s", estimate_json(&x->coast_rate));
        cJSON_AddItemToObject(e, r->mass[j] > 0 ? "intensity_w" : "intensity_m2_s3",
                              estimate_json(&x->intensity));
        cJSON_AddNumberToObject(e, "drive_impacts", x->drive_impacts);
        cJSON_AddNumberToObject(e, "coast_impacts", x->coast_impacts);
        cJSON_AddNumberToObject(e, "impact_speed_mean_m_s", x->v_mean);
        cJSON_AddNumberToObject(e, "impact_speed_rms_m_s", x->v_rms);
        cJSON_AddNumberToObject(e, "impact_speed_max_m_s", x->v_max);
        cJSON *h = cJSON_AddObjectToObject(e, "impact_speed_histogram");
        cJSON_AddNumberToObject(h, "bin_width_m_s", x->bin_width);
        cJSON_AddItemToObject(h, "drive", int_array(x->hist_drive, GD_RATTLE_BINS));
        cJSON_AddItemToObject(h, "coast", int_array(x->hist_coast, GD_RATTLE_BINS));
        cJSON_AddNumberToObject(e, "relative_half_width", x->precision);
        cJSON_AddBoolToObject(e, "converged", x->converged);
        cJSON_AddNumberToObject(e, "suggested_window_s", x->suggested_duration);
        cJSON_AddItemToArray(a, e);
    }
    return o;
}

void gd_cli_rattle_print(const gd_cli_rattle *r, const gd_model *m, const gd_transient_model *tm)
{
    if (!r->n) {
        printf("\nrattle: no mesh with backlash\n");
        return;
    }
    const gd_rattle_metrics *x0 = &r->metrics[0];
    printf("\nrattle over %g s (%d batches, %g %% confidence: mean +- half-width)\n", x0->duration,
           x0->batches, 100 * x0->confidence);
    printf("%-16s %17s %17s %17s %21s %9s %9s\n", "mesh", "separated", "drive_impacts/s",
           "coast_impacts/s", "intensity", "v_rms_m/s", "v_max_m/s");
    for (int j = 0; j < r->n; j++) {
        const gd_rattle_metrics *x = &r->metrics[j];
        printf("%-16.16s %8.4g+-%-7.2g %8.4g+-%-7.2g %8.4g+-%-7.2g %8.4g+-%-7.2g%-3s %9.3g %9.3g\n",
               gd_model_mesh_name(m, tm->meshes[r->mesh[j]].mesh), x->separated.mean,
               x->separated.half_width, x->drive_rate.mean, x->drive_rate.half_width,
               x->coast_rate.mean, x->coast_rate.half_width, x->intensity.mean,
               x->intensity.half_width, r->mass[j] > 0 ? " W" : " *", x->v_rms, x->v_max);
    }
    for (int j = 0; j < r->n; j++) {
        const gd_rattle_metrics *x = &r->metrics[j];
        if (!x->converged)
            printf("%s: relative half-width %.3g > %g: about %.3g s of window needed\n",
                   gd_model_mesh_name(m, tm->meshes[r->mesh[j]].mesh), x->precision, r->target,
                   x->suggested_duration);
    }
    for (int j = 0; j < r->n; j++)
        if (r->mass[j] == 0) {
            printf("(* intensity as sum v^2 per second, m^2/s^3: no effective mass)\n");
            break;
        }
}
