/* Poincare samples of `geardyn transient`: the source (shaft revolution or tooth-mesh
 * cycle), the sample times, the periodicity test and the JSON block. */
#include "transient_poincare.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/cycles.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int list_names(const char *cmd, const gd_model *m, const char *text)
{
    char shafts[400] = "", meshes[400] = "";
    for (int i = 0; i < m->nshafts; i++)
        snprintf(shafts + strlen(shafts), sizeof shafts - strlen(shafts), "%s%s", i ? ", " : "",
                 m->shafts[i].name);
    for (int i = 0; i < m->nmeshes; i++)
        snprintf(meshes + strlen(meshes), sizeof meshes - strlen(meshes), "%s%s", i ? ", " : "",
                 m->meshes[i].name);
    return gd_cli_usage_error(cmd, "--poincare: '%s' is no shaft (%s) or mesh (%s)", text,
                              *shafts ? shafts : "none", *meshes ? meshes : "none");
}

int gd_cli_poincare_parse(const char *cmd, const gd_model *m, const char *text, gd_cli_poincare *p)
{
    const char *name = text;
    int want = 0; /* 1 shaft, 2 mesh */
    if (!strncmp(text, "shaft:", 6)) {
        want = 1;
        name = text + 6;
    } else if (!strncmp(text, "mesh:", 5)) {
        want = 2;
        name = text + 5;
    }
    int s = want == 2 ? -1 : gd_model_find_shaft(m, name);
    int g = want == 1 ? -1 : gd_model_find_mesh(m, name);
    if (s >= 0 && g >= 0)
        return gd_cli_usage_error(cmd,
                                  "--poincare: '%s' is a shaft and a mesh: write shaft:%s or "
                                  "mesh:%s",
                                  name, name, name);
    if (s >= 0) {
        double r = fabs(m->shafts[s].speed_ratio);
        if (!(r > 0))
            return gd_cli_usage_error(cmd, "--poincare: shaft '%s' does not turn (speed ratio 0)",
                                      name);
        snprintf(p->name, sizeof p->name, "shaft:%s", name);
        p->angle = 2 * M_PI / r;
        return 0;
    }
    if (g >= 0) {
        const gd_mesh *gm = &m->meshes[g];
        double r = fabs(m->shafts[m->nodes[gm->driver].shaft].speed_ratio);
        if (gm->teeth[0] <= 0)
            return gd_cli_usage_error(cmd,
                                      "--poincare: mesh '%s' has no tooth numbers (teeth: [z1, "
                                      "z2]): its tooth-mesh period is undefined",
                                      name);
        if (!(r > 0))
            return gd_cli_usage_error(cmd, "--poincare: the driver of mesh '%s' does not turn",
                                      name);
        snprintf(p->name, sizeof p->name, "mesh:%s", name);
        p->angle = 2 * M_PI / (r * gm->teeth[0]);
        return 0;
    }
    return list_names(cmd, m, name);
}

int gd_cli_poincare_times(const gd_cli_poincare *p, double speed, double from, double t_end,
                          double **times)
{
    *times = NULL;
    double P = p->angle / speed;
    if (!(P > 0) || !isfinite(P)) return 0;
    double k0 = ceil(from / P - 1e-9), k1 = floor(t_end / P + 1e-9);
    if (k1 < k0 || k1 - k0 > 1e7) return 0;
    int n = (int)(k1 - k0) + 1;
    double *t = malloc((size_t)n * sizeof *t);
    if (!t) return 0;
    for (int k = 0; k < n; k++)
        t[k] = fmin(fmax((k0 + k) * P, from), t_end);
    *times = t;
    return n;
}

void gd_cli_poincare_classify(const double *values, int nrec, int n, const double *scale,
                              int *period, int *distinct, char *verdict, int vsize)
{
    if (verdict && vsize > 0) snprintf(verdict, (size_t)vsize, "irregular");
    gd_poincare_options o;
    gd_poincare_options_init(&o);
    o.tol = GD_CLI_POINCARE_TOL;
    gd_poincare_verdict v;
    gd_error err;
    *period = *distinct = 0;
    if (gd_poincare_classify(values, nrec, n, scale, &o, &v, &err)) return;
    *period = v.period;
    *distinct = v.distinct;
    if (verdict) gd_poincare_verdict_name(&v, verdict, vsize);
}

void gd_cli_poincare_class_name(int period, char *buf, size_t size)
{
    if (period > 0)
        snprintf(buf, size, "period-%d", period);
    else
        snprintf(buf, size, "many");
}

cJSON *gd_cli_poincare_json(const gd_cli_poincare *p, double period_s, const gd_cli_records *recs,
                            const double *t, const double *values, int n, int period, int distinct)
{
    char cls[32];
    gd_cli_poincare_class_name(period, cls, sizeof cls);
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "source", p->name);
    cJSON_AddNumberToObject(o, "period_s", period_s);
    cJSON_AddNumberToObject(o, "points", n);
    cJSON_AddNumberToObject(o, "period", period);
    cJSON_AddNumberToObject(o, "distinct_points", distinct);
    cJSON_AddStringToObject(o, "class", cls);
    cJSON_AddNumberToObject(o, "tolerance", GD_CLI_POINCARE_TOL);
    cJSON *ta = cJSON_AddArrayToObject(o, "times_s");
    for (int k = 0; k < n; k++)
        cJSON_AddItemToArray(ta, cJSON_CreateNumber(t[k]));
    cJSON *ra = cJSON_AddArrayToObject(o, "records");
    for (int r = 0; r < recs->n; r++) {
        cJSON *e = cJSON_CreateObject();
        cJSON_AddStringToObject(e, "name", recs->r[r].name);
        cJSON *va = cJSON_AddArrayToObject(e, "values");
        for (int k = 0; k < n; k++)
            cJSON_AddItemToArray(va, gd_cli_json_number(values[(size_t)r * n + k]));
        cJSON_AddItemToArray(ra, e);
    }
    return o;
}
