/* The reference shaft's speed profile of a run-up (gd_speed_profile): its speed, angle
 * (the speed's integral from t = 0, so that a constant speed W gives phi = W t as the
 * constant-speed path) and acceleration, exactly for the piecewise-linear speed; and
 * setting a problem up to follow one. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/system.h"
#include "transient/transient_impl.h"

gd_status gd_speed_profile_check(const gd_speed_profile *p, gd_error *err)
{
    if (p->kind == GD_SPEED_RAMP) {
        if (!isfinite(p->from) || !isfinite(p->to) || p->from * p->to < 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.from",
                                "give finite speeds of one sign (a run-down: FROM > TO)",
                                "ramp speeds %g -> %g rad/s change sign or are not finite", p->from,
                                p->to);
        if (!(p->t1 > p->t0) || !isfinite(p->t0) || !isfinite(p->t1))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.t1", "give t1 > t0",
                                "ramp times %g -> %g s", p->t0, p->t1);
        return GD_OK;
    }
    if (p->kind != GD_SPEED_TABLE)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.kind", "ramp or table",
                            "unknown speed profile kind %d", (int)p->kind);
    if (p->n < 2 || !p->t || !p->speed)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.table",
                            "give at least two rows of time, speed", "speed table has %d rows",
                            p->n);
    int pos = 0, neg = 0;
    for (int k = 0; k < p->n; k++) {
        if (!isfinite(p->t[k]) || !isfinite(p->speed[k]) || (k && !(p->t[k] > p->t[k - 1])))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.table",
                                "times must increase and every value be finite",
                                "speed table row %d (t %g s, speed %g rad/s)", k + 1, p->t[k],
                                p->speed[k]);
        pos |= p->speed[k] > 0;
        neg |= p->speed[k] < 0;
    }
    if (pos && neg)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "profile.table",
                            "keep the speeds of one sign",
                            "the speed table changes the sense of rotation");
    return GD_OK;
}

/* integral of the ramp's speed from 0 to t (F(0) = 0 when t0 >= 0) */
static double ramp_integral(const gd_speed_profile *p, double t)
{
    double a = (p->to - p->from) / (p->t1 - p->t0);
    if (t <= p->t0) return p->from * t;
    double F0 = p->from * p->t0;
    if (t <= p->t1) return F0 + p->from * (t - p->t0) + 0.5 * a * (t - p->t0) * (t - p->t0);
    return F0 + 0.5 * (p->from + p->to) * (p->t1 - p->t0) + p->to * (t - p->t1);
}

/* table: segment k with t[k] <= t < t[k+1] (-1 before the first row, n-1 after the
 * last), the speed and its slope there */
static void table_at(const gd_speed_profile *p, double t, int *seg, double *w, double *a)
{
    if (t <= p->t[0]) {
        *seg = -1;
        *w = p->speed[0];
        *a = 0;
        return;
    }
    if (t >= p->t[p->n - 1]) {
        *seg = p->n - 1;
        *w = p->speed[p->n - 1];
        *a = 0;
        return;
    }
    int lo = 0, hi = p->n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (p->t[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    *seg = lo;
    *a = (p->speed[lo + 1] - p->speed[lo]) / (p->t[lo + 1] - p->t[lo]);
    *w = p->speed[lo] + *a * (t - p->t[lo]);
}

/* integral of the table's speed from t[0] to t; cum[k] = integral to t[k] (NULL: summed
 * here) */
static double table_integral(const gd_speed_profile *p, const double *cum, double t)
{
    int seg;
    double w, a;
    table_at(p, t, &seg, &w, &a);
    if (seg < 0) return p->speed[0] * (t - p->t[0]);
    double c = 0;
    if (cum)
        c = cum[seg];
    else
        for (int k = 0; k < seg; k++)
            c += 0.5 * (p->speed[k] + p->speed[k + 1]) * (p->t[k + 1] - p->t[k]);
    return c + 0.5 * (p->speed[seg] + w) * (t - p->t[seg]);
}

void gd_tr_profile_eval(const gd_speed_profile *p, const double *cum, double t, double *angle,
                        double *speed, double *accel)
{
    double w, a, phi;
    if (p->kind == GD_SPEED_RAMP) {
        double r = (p->to - p->from) / (p->t1 - p->t0);
        w = t <= p->t0 ? p->from : t >= p->t1 ? p->to : p->from + r * (t - p->t0);
        a = t > p->t0 && t < p->t1 ? r : 0.0;
        phi = ramp_integral(p, t) - ramp_integral(p, 0.0);
    } else {
        int seg;
        table_at(p, t, &seg, &w, &a);
        phi = table_integral(p, cum, t) - table_integral(p, cum, 0.0);
    }
    if (angle) *angle = phi;
    if (speed) *speed = w;
    if (accel) *accel = a;
}

void gd_speed_profile_eval(const gd_speed_profile *p, double t, double *angle, double *speed,
                           double *accel)
{
    gd_tr_profile_eval(p, NULL, t, angle, speed, accel);
}

static void bearings_free(gd_transient *tr)
{
    for (int j = 0; j < tr->nsd; j++) {
        cs_spfree(tr->sd_K[j]);
        cs_spfree(tr->sd_C[j]);
    }
    free(tr->sd_K);
    free(tr->sd_C);
    tr->sd_K = tr->sd_C = NULL;
    tr->nsd = 0;
}

int gd_tr_profile_bearings(gd_transient *tr)
{
    bearings_free(tr);
    if (!tr->prof || !tr->sys->has_speed_dependent) return 0;
    const gd_speed_profile *p = tr->prof;
    double lo = p->kind == GD_SPEED_RAMP ? fmin(p->from, p->to) : p->speed[0], hi = lo;
    if (p->kind == GD_SPEED_RAMP) hi = fmax(p->from, p->to);
    for (int k = 0; p->kind == GD_SPEED_TABLE && k < p->n; k++) {
        lo = fmin(lo, p->speed[k]);
        hi = fmax(hi, p->speed[k]);
    }
    const int n = hi > lo ? GD_TR_SD_SPEEDS : 1;
    tr->sd_K = calloc((size_t)n, sizeof *tr->sd_K);
    tr->sd_C = calloc((size_t)n, sizeof *tr->sd_C);
    if (!tr->sd_K || !tr->sd_C) return 1;
    tr->nsd = n;
    tr->sd_w0 = lo;
    tr->sd_dw = n > 1 ? (hi - lo) / (n - 1) : 1.0;
    /* C(W) - C(W_ref): tr->D holds C + W_ref G, the system's C its C + C_b(W_ref) */
    gd_csc C0 = {0};
    if (gd_system_matrices(tr->sys, tr->speed, NULL, NULL, &C0, NULL, NULL)) return 1;
    cs c0 = gd_tr_cs_view(&C0);
    int bad = 0;
    for (int j = 0; j < n && !bad; j++) {
        gd_csc Ks = {0}, Cs = {0};
        if (gd_system_matrices(tr->sys, lo + j * tr->sd_dw, NULL, &Ks, &Cs, NULL, NULL)) {
            bad = 1;
            break;
        }
        cs kv = gd_tr_cs_view(&Ks), cv = gd_tr_cs_view(&Cs);
        tr->sd_K[j] = cs_add(&kv, tr->K, 1.0, -1.0);
        tr->sd_C[j] = cs_add(&cv, &c0, 1.0, -1.0);
        bad = !tr->sd_K[j] || !tr->sd_C[j] || cs_dropzeros(tr->sd_K[j]) < 0 ||
              cs_dropzeros(tr->sd_C[j]) < 0;
        gd_csc_free(&Ks);
        gd_csc_free(&Cs);
    }
    gd_csc_free(&C0);
    return bad;
}

/* r -= f A x */
static void sub_scaled(const cs *A, double f, const double *x, double *r)
{
    if (f == 0.0) return;
    for (int j = 0; j < A->n; j++) {
        double xj = f * x[j];
        if (xj == 0.0) continue;
        for (int p = A->p[j]; p < A->p[j + 1]; p++)
            r[A->i[p]] -= A->x[p] * xj;
    }
}

void gd_tr_profile_bearing_forces(const gd_transient *tr, double w, const double *q,
                                  const double *v, double *r)
{
    if (!tr->nsd) return;
    double u = (w - tr->sd_w0) / tr->sd_dw;
    int j = (int)floor(u);
    if (j < 0) j = 0;
    if (j > tr->nsd - 2) j = tr->nsd > 1 ? tr->nsd - 2 : 0;
    double f = tr->nsd > 1 ? fmin(fmax(u - j, 0.0), 1.0) : 0.0;
    sub_scaled(tr->sd_K[j], 1.0 - f, q, r);
    sub_scaled(tr->sd_C[j], 1.0 - f, v, r);
    if (tr->nsd > 1) {
        sub_scaled(tr->sd_K[j + 1], f, q, r);
        sub_scaled(tr->sd_C[j + 1], f, v, r);
    }
}

/* The profile's angle and speed at t (a mesh law's nominal driver motion). */
static void profile_nominal(const void *ctx, double t, double *angle, double *speed)
{
    const gd_transient *tr = ctx;
    gd_tr_profile_eval(tr->prof, tr->prof_cum, t, angle, speed, NULL);
}

/* The mesh laws read their driver's angle from the profile (on) or at the reference
 * speed. The problem owns their data (gd_transient_spec_laws' block). */
static void set_mesh_nominal(gd_transient *tr, int on)
{
    for (int i = 0; i < tr->nmesh; i++) {
        gd_mesh_law_data *m = (gd_mesh_law_data *)(uintptr_t)tr->law[i].data;
        m->nominal = on ? profile_nominal : NULL;
        m->nominal_ctx = on ? tr : NULL;
    }
}

int gd_tr_profile_set(gd_transient *tr, const gd_speed_profile *p)
{
    const int had = tr->prof != NULL;
    bearings_free(tr);
    free(tr->prof_cum);
    tr->prof_cum = NULL;
    tr->prof = p;
    set_mesh_nominal(tr, 0);
    /* the laws' rates and spins back at the reference speed after a run-up */
    const int stride = GD_LAW_MAX_DOFS + 2;
    for (int i = 0; had && i < tr->nlaw && tr->law_ratio; i++) {
        const double *r = tr->law_ratio + (size_t)i * stride;
        for (int j = 0; j < tr->law[i].ndofs; j++)
            tr->law[i].rate[j] = r[j] * tr->speed;
        tr->law[i].spin[0] = r[GD_LAW_MAX_DOFS] * tr->speed;
        tr->law[i].spin[1] = r[GD_LAW_MAX_DOFS + 1] * tr->speed;
    }
    if (!p) return 0;
    tr->prof_sign = 1;
    if (p->kind == GD_SPEED_TABLE) {
        tr->prof_cum = malloc((size_t)p->n * sizeof *tr->prof_cum);
        if (!tr->prof_cum) {
            tr->prof = NULL;
            return 1;
        }
        tr->prof_cum[0] = 0;
        for (int k = 0; k + 1 < p->n; k++)
            tr->prof_cum[k + 1] =
                tr->prof_cum[k] + 0.5 * (p->speed[k] + p->speed[k + 1]) * (p->t[k + 1] - p->t[k]);
        for (int k = 0; k < p->n; k++)
            if (p->speed[k] < 0) tr->prof_sign = -1;
    } else if (p->from < 0 || p->to < 0) {
        tr->prof_sign = -1;
    }
    set_mesh_nominal(tr, 1);
    if (gd_tr_profile_bearings(tr)) {
        gd_tr_profile_set(tr, NULL);
        return 1;
    }
    return 0;
}

/* rate t is each DOF's nominal angle (ratio phi), spin its shaft's speed (ratio W) */
void gd_tr_profile_laws(gd_transient *tr, double t, double phi, double w)
{
    const int stride = GD_LAW_MAX_DOFS + 2;
    double per_t = t != 0.0 ? phi / t : w;
    for (int i = 0; i < tr->nlaw; i++) {
        const double *r = tr->law_ratio + (size_t)i * stride;
        for (int j = 0; j < tr->law[i].ndofs; j++)
            tr->law[i].rate[j] = r[j] * per_t;
        tr->law[i].spin[0] = r[GD_LAW_MAX_DOFS] * w;
        tr->law[i].spin[1] = r[GD_LAW_MAX_DOFS + 1] * w;
    }
}
