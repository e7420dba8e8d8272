/* The fundamental frequency of a problem's excitations: every frequency the laws impose
 * (shaft speeds through the gear ratios for unbalances; each law of the registry's
 * own, gd_law_type.frequencies: tooth-mesh frequencies of TVMS and STE tables, cams,
 * loads; prescribed harmonic motions) must be a whole multiple of it. Found by Euclid's algorithm
 * on the real frequencies with a relative tolerance. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geardyn/periodic.h"

#define MAXF 256
#define TWO_PI 6.28318530717958647692

static const char NO_EXCITATION[] = "give the model a periodic excitation (unbalance, TVMS, "
                                    "load) and a non-zero speed";

static gd_status undefined_hint(gd_error *err, const char *field, const char *hint, const char *msg)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, "the period is undefined: %s", msg);
}

static gd_status undefined(gd_error *err, const char *field, const char *msg)
{
    return undefined_hint(err, field, NO_EXCITATION, msg);
}

static double shaft_rate(const gd_system *sys, int node, double speed)
{
    const gd_model *m = sys->model;
    return fabs(m->shafts[m->nodes[node].shaft].speed_ratio * speed);
}

static void push(double *f, int *n, double v)
{
    if (v > 0 && isfinite(v) && *n < MAXF) f[(*n)++] = v;
}

/* gcd of two positive reals to relative tolerance tol of the larger scale */
static double real_gcd(double a, double b, double tol)
{
    while (b > tol) {
        double r = fmod(a, b);
        if (r > b - tol) r = 0.0;
        a = b;
        b = r;
    }
    return a;
}

gd_status gd_periodic_fundamental(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                  double *w0, int *max_order, gd_error *err)
{
    if (max_order) *max_order = 0;
    const gd_model *m = sys->model;
    double f[MAXF];
    int n = 0;
    *w0 = 0.0;
    if (!isfinite(speed)) return undefined(err, "speed", "the speed is not finite");
    if (spec->unbalances)
        for (int i = 0; i < m->nunbalances; i++)
            push(f, &n, shaft_rate(sys, m->unbalances[i].node, speed));
    /* every law of the registry (the meshes' TVMS and STE first) names its own excitation
     * frequencies */
    gd_law *laws = NULL;
    int nlaws = 0;
    gd_status st = gd_transient_spec_laws(sys, spec, speed, &laws, &nlaws, err);
    if (st) return st;
    for (int i = 0; i < nlaws; i++) {
        const gd_law *L = &laws[i];
        if (!L->type->frequencies) continue;
        double w[16];
        char msg[200] = "";
        int nw = L->type->frequencies(L, w, 16, msg, sizeof msg);
        if (nw < 0) {
            char field[GD_LAW_NAME_MAX + 8];
            snprintf(field, sizeof field, "%s", L->name);
            free(laws);
            return undefined(err, field, msg);
        }
        for (int k = 0; k < nw; k++)
            push(f, &n, w[k]);
    }
    free(laws);
    /* the prescribed motions, from the problem's table of them */
    for (int i = 0; i < spec->nprescribed; i++) {
        const int d = spec->prescribed[i].dof;
        double r = sys->dof_type[d] == GD_RZ
                       ? m->shafts[m->nodes[sys->dof_node[d]].shaft].speed_ratio * speed
                       : 0.0,
               w[4];
        char msg[200] = "";
        int nw = gd_prescribed_frequencies(&spec->prescribed[i].law, r, w, 4, msg, sizeof msg);
        if (nw < 0) return undefined(err, "prescribed", msg);
        for (int k = 0; k < nw; k++)
            push(f, &n, w[k]);
    }
    if (n == 0)
        return undefined(err, "speed",
                         speed == 0.0 ? "no excitation turns at speed 0"
                                      : "the model has no periodic excitation");
    double fmax = 0.0;
    for (int i = 0; i < n; i++)
        fmax = fmax > f[i] ? fmax : f[i];
    double tol = 1e-9 * fmax, g = f[0];
    for (int i = 1; i < n; i++)
        g = real_gcd(g > f[i] ? g : f[i], g > f[i] ? f[i] : g, tol);
    if (!(g > 0) || fmax / g > 10000.5) {
        char msg[160];
        snprintf(msg, sizeof msg,
                 "the excitation frequencies have no common period (highest %.6g rad/s is "
                 "not a whole multiple of a fundamental above %.3g rad/s)",
                 fmax, fmax / 10000);
        /* the excitations exist but are incommensurate (gear ratios with no small common
           multiple beside unbalances): the response is quasi-periodic, not periodic */
        return undefined_hint(err, "speed",
                              "the response is quasi-periodic: integrate it over a given time "
                              "(`geardyn transient --duration T`, not --periods); `periodic "
                              "--method multifreq` takes up to 3 independent base frequencies "
                              "of meshes and loads, without unbalances",
                              msg);
    }
    *w0 = g;
    if (max_order) *max_order = (int)lround(fmax / g);
    return GD_OK;
}
