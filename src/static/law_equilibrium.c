/* The static state of the laws that carry load (docs/bearings.md): the nonlinear
 * equilibrium K q = f + f_law(q) with the static analysis's holds, the located error
 * when there is none, and the operating point the linear analyses linearise about
 * (gd_static_operating_point: the same loads and holds handed to the system).
 *
 * The error names the law that cannot hold the load and the fix for its kind: a
 * journal bearing at rest carries nothing (give a speed), a journal bearing at its
 * eccentricity cap carries less than the load (Ocvirk's capacity grows without bound
 * only as eps -> 1), a rolling bearing carries radial load only and nothing inside its
 * clearance. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"

/* The model's law behind system law l (the system keeps the laws with a linearisation),
 * its index in m->laws or -1. */
static int model_law(const gd_system *sys, int l)
{
    const gd_model *m = sys->model;
    for (int i = 0; i < m->nlaws; i++)
        if (!strcmp(m->laws[i].name, sys->laws[l].name)) return i;
    return -1;
}

static gd_status at_law(const gd_system *sys, int l, const char *hint, gd_error *err,
                        const char *fmt, double a, double b)
{
    const gd_model *m = sys->model;
    int i = model_law(sys, l);
    char field[GD_NAME_MAX + 16];
    snprintf(field, sizeof field, "laws[%d]", i);
    gd_loc loc = i >= 0 ? m->laws[i].loc : (gd_loc){0, 0};
    return gd_error_set(err, GD_EINPUT, m->file, loc.line, loc.column, i >= 0 ? field : "laws",
                        hint, fmt, sys->laws[l].name, a, b);
}

gd_status gd_st_no_equilibrium(const gd_system *sys, double speed, const double *q, double res,
                               gd_error *err)
{
    int journal = -1, rolling = -1, capped = -1;
    double ecc_capped = 0;
    for (int l = 0; l < sys->nlaws; l++) {
        const gd_law *L = &sys->laws[l];
        if (L->type == &gd_law_journal_bearing) {
            if (journal < 0) journal = l;
            double rec[GD_STATIC_LAW_RECORDS];
            int nr = gd_system_law_records(sys, l, speed, q, rec, GD_STATIC_LAW_RECORDS);
            int k = gd_law_record_index(L->type, "ecc");
            int c = gd_law_param_index(L->type, "max_eccentricity");
            double cap = c >= 0 && L->value[c] > 0 ? L->value[c] : 0.995;
            if (k >= 0 && k < nr && rec[k] >= 0.99 * cap && capped < 0)
                capped = l, ecc_capped = cap;
        } else if ((L->type == &gd_law_rolling_bearing ||
                    L->type == &gd_law_rolling_bearing_5dof) &&
                   rolling < 0) {
            rolling = l;
        }
    }
    if (journal >= 0 && speed == 0)
        return at_law(sys, journal,
                      "a journal bearing carries load only while the shaft turns: give a speed "
                      "(--speed) or a bearing that holds the shaft at rest",
                      err,
                      "journal bearing '%s' carries nothing at %g rad/s: the laws find no static "
                      "equilibrium (relative residual %.3g)",
                      speed, res);
    if (capped >= 0)
        return at_law(sys, capped,
                      "the film cannot carry the static load at this speed: raise the speed, the "
                      "viscosity or the bearing length, or lower the load",
                      err,
                      "journal bearing '%s' reaches its eccentricity cap %.4g and still carries "
                      "less than its load at %g rad/s",
                      ecc_capped, speed);
    if (rolling >= 0)
        return at_law(sys, rolling,
                      sys->laws[rolling].type == &gd_law_rolling_bearing
                          ? "a rolling bearing carries radial (x, y) load only and nothing inside "
                            "its clearance: check the loads' directions, the bearings' "
                            "contact_stiffness and clearance, and that every load path ends in a "
                            "bearing"
                          : "a rolling bearing carries nothing inside its clearance, and a "
                            "radial bearing (contact angle 0) little axial or tilt load: check "
                            "the loads' directions, the bearings' geometry and clearance, and "
                            "that every load path ends in a bearing",
                      err,
                      "the laws find no static equilibrium with rolling bearing '%s' "
                      "(relative residual %.3g at %g rad/s)",
                      res, speed);
    return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "laws",
                        "check that the laws can carry the loads (their directions and stiffness)",
                        "the laws find no static equilibrium at %g rad/s (relative residual "
                        "%.3g after Newton's iterations)",
                        speed, res);
}

gd_status gd_st_solve_with_laws(const gd_system *sys, const double *K, const double *f,
                                const int *held, double speed, double *q, gd_error *err)
{
    gd_error quiet = {0};
    if (gd_st_solve_linear(sys, K, f, held, q, &quiet)) memset(q, 0, (size_t)sys->ndof * sizeof *q);
    double res = 0;
    if (gd_system_law_equilibrium(sys, speed, K, f, held, q, &res)) return GD_OK;
    double *q0 = calloc((size_t)(sys->ndof > 0 ? sys->ndof : 1), sizeof *q0);
    if (!q0) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    double res0 = 0;
    int found = gd_system_law_equilibrium(sys, speed, K, f, held, q0, &res0);
    if (found || res0 < res) memcpy(q, q0, (size_t)sys->ndof * sizeof *q);
    free(q0);
    if (found) return GD_OK;
    return gd_st_no_equilibrium(sys, speed, q, fmin(res, res0), err);
}

gd_status gd_st_equilibrium(const gd_system *sys, const gd_static_options *opt, double speed,
                            const double *f, int solve, int *held, double *q, gd_error *err)
{
    size_t n1 = (size_t)(sys->ndof > 0 ? sys->ndof : 1);
    double *K = malloc(n1 * n1 * sizeof *K), *Kd = malloc(n1 * n1 * sizeof *Kd);
    gd_status st = GD_OK;
    if (!K || !Kd) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto out;
    }
    gd_system_dense_linear(sys, speed, NULL, NULL, K);
    gd_st_supported_stiffness(sys, K, Kd);
    if ((st = gd_st_holds(sys, Kd, opt, held, err))) goto out;
    if (solve) st = gd_st_solve_with_laws(sys, K, f, held, speed, q, err);
out:
    free(K);
    free(Kd);
    return st;
}

gd_status gd_static_operating_point(gd_system *sys, const gd_static_options *opt, int check,
                                    gd_error *err)
{
    gd_static_options def;
    if (!opt) {
        gd_static_options_init(&def);
        opt = &def;
    }
    const gd_model *m = sys->model;
    if (!sys->nlaws) return GD_OK; /* nothing to linearise */
    gd_status st = gd_st_check_options(m, opt, err);
    if (st) return st;
    const int n = sys->ndof;
    size_t n1 = (size_t)(n > 0 ? n : 1);
    double *f = malloc(n1 * sizeof *f), *q = malloc(n1 * sizeof *q);
    int *held = malloc(n1 * sizeof *held);
    double speed = opt->speed >= 0 ? opt->speed : m->speed;
    if (!f || !q || !held) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto out;
    }
    if ((st = gd_st_loads(sys, opt, f, err))) goto out;
    /* (the operating point only records f and the holds: set after the solve, which does
       not read it) */
    if ((st = gd_st_equilibrium(sys, opt, speed, f, check, held, q, err))) goto out;
    if ((st = gd_system_set_operating_point(sys, GD_OPERATING_STATIC, f, held, err))) goto out;
    /* the state the analyses will linearise about (from rest, not from the linear
       solution static starts from): never silently q = 0 where static found a state */
    if (check && !st && !gd_system_law_state(sys, speed, q))
        st = gd_error_set(err, GD_ENUMERIC, m->file, 0, 0, "laws",
                          "use --operating-point zero to linearise at q = 0, and report the "
                          "model: static finds its equilibrium",
                          "the linear analyses' equilibrium iteration did not converge at %g "
                          "rad/s",
                          speed);
out:
    free(f);
    free(q);
    free(held);
    return st;
}
