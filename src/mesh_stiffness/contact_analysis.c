/* Loaded tooth contact analysis (docs/mesh-stiffness.md, "Loaded contact analysis").
 *
 * At each driver angle the slices in contact (slicing.c, the same slices and law as
 * the TVMS) are springs k_i along the contact normal (k_t / cos^2 beta_b) with initial
 * separations e_i (micro_geometry.c). Under the normal load F the approach delta solves
 *   f(delta) = sum_i k_i max(0, delta - e_i) = F,
 * convex, piecewise linear and increasing. With the springs sorted by e, the force that
 * brings delta to e_j is f(e_j) = K_j e_j - S_j (K_j, S_j: sums of k and k e over the
 * springs before j), nondecreasing in j; a bisection on j finds the active set and
 * delta = (F + S_a) / K_a exactly. The tangent stiffness is K_a; gear bodies add
 * F / k_body in series. The slice set is built once and solved for any number of
 * loads (Harris map). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

typedef struct spring {
    double e, k;
    int slot, slice;
} spring;

/* The springs of one mesh cycle, sorted by separation within each position. */
typedef struct ltca_set {
    gd_gear_pair_derived d;
    size_t points;
    int slices, max_pairs;
    double b, force_per_torque, kbody;
    size_t *off; /* points + 1 */
    spring *sp;
    double *K, *S; /* inclusive prefix sums per position */
    size_t count, cap;
    int *geo_slices; /* scratch: slices with a contact, per position (slices) */
} ltca_set;

static void set_free(ltca_set *s)
{
    free(s->off);
    free(s->sp);
    free(s->K);
    free(s->S);
    free(s->geo_slices);
}

static int by_separation(const void *a, const void *b)
{
    double x = ((const spring *)a)->e, y = ((const spring *)b)->e;
    return x < y ? -1 : x > y;
}

static gd_status oom(gd_error *err)
{
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce points or slices", "out of memory");
}

static gd_status check(const gd_tvms_options *o, gd_error *err)
{
    gd_status st = gd_ms_check_options(o, err);
    if (st) return st;
    if (o->method == GD_TVMS_ISO6336)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "method",
                            "use energy (default), single-pair-law or square",
                            "the contact analysis needs a stiffness law along the contact "
                            "(iso6336 gives one constant)");
    if (!isfinite(o->misalignment))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "misalignment",
                            "give a length, e.g. \"10 um\"", "misalignment is not a number");
    return GD_OK;
}

static gd_status check_torque(double T, gd_error *err)
{
    if (isfinite(T) && T > 0) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "load",
                        "give the driver torque, e.g. \"200 N m\" (the drive flank carries it)",
                        "load torque %g N m is not positive", T);
}

static gd_status build(const gd_gear_pair_geometry *g, const gd_tvms_options *o, ltca_set *s,
                       gd_error *err)
{
    memset(s, 0, sizeof *s);
    gd_status st = check(o, err);
    if (st || (st = gd_gear_pair_derive(g, &s->d, err))) return st;
    const gd_gear_pair_derived *d = &s->d;
    s->points = (size_t)o->points;
    s->slices = o->slices;
    s->b = g->face_width;
    s->max_pairs = (int)ceil(d->contact_ratio_total - 1e-12);
    if (s->max_pairs < 1) s->max_pairs = 1;
    double cb = cos(d->base_helix_angle), cb2 = cb * cb;
    s->force_per_torque = 1 / (d->base_radius[0] * cb);
    s->kbody = o->body_compliance ? gd_ms_body_stiffness(g, d) : 0;

    gd_ms_pair_law law;
    if (gd_ms_pair_law_init(&law, g, d, o->method, o->quad_tol)) return oom(err);
    gd_ms_slicing sl = {d, s->b, s->slices, law.fn, law.ctx, s->max_pairs};
    gd_ms_mods mods;
    gd_ms_mods_init(&mods, g, d, o->misalignment);
    int cap = gd_ms_slicing_capacity(&sl);
    gd_ms_contact *c = malloc((size_t)cap * sizeof *c);
    s->off = malloc((s->points + 1) * sizeof *s->off);
    s->geo_slices = malloc((size_t)s->slices * sizeof *s->geo_slices);
    if (!c || !s->off || !s->geo_slices) goto fail;
    s->off[0] = 0;
    for (size_t p = 0; p < s->points; p++) {
        int nc = 0;
        gd_ms_slicing_contacts(&sl, d->mesh_period * (double)p / (double)s->points, c, &nc, NULL,
                               NULL);
        if (s->count + (size_t)nc > s->cap) {
            size_t ncap = 2 * s->cap + (size_t)cap;
            spring *sp = realloc(s->sp, ncap * sizeof *sp);
            if (!sp) goto fail;
            s->sp = sp;
            s->cap = ncap;
        }
        spring *row = s->sp + s->count;
        for (int j = 0; j < nc; j++)
            row[j] = (spring){gd_ms_mods_separation(&mods, c[j].s, c[j].y), c[j].k / cb2, c[j].slot,
                              c[j].slice};
        qsort(row, (size_t)nc, sizeof *row, by_separation);
        s->count += (size_t)nc;
        s->off[p + 1] = s->count;
    }
    s->K = malloc((s->count + 1) * sizeof *s->K);
    s->S = malloc((s->count + 1) * sizeof *s->S);
    if (!s->K || !s->S) goto fail;
    for (size_t p = 0; p < s->points; p++) {
        double K = 0, S = 0;
        for (size_t j = s->off[p]; j < s->off[p + 1]; j++) {
            K += s->sp[j].k;
            S += s->sp[j].k * s->sp[j].e;
            s->K[j] = K;
            s->S[j] = S;
        }
    }
    free(c);
    gd_ms_pair_law_free(&law);
    return GD_OK;
fail:
    free(c);
    gd_ms_pair_law_free(&law);
    set_free(s);
    return oom(err);
}

/* One position under normal load F. pair_load (max_pairs) and line_load (slices) may be
 * NULL; *npairs counts the loaded pairs when pair_load is given, *flags gets the
 * GD_LTCA_* bits when line_load is given. */
static void solve(const ltca_set *s, size_t p, double F, double *ste, double *k, int *npairs,
                  double *pair_load, double *line_load, int *flags)
{
    const size_t o = s->off[p], c = s->off[p + 1] - o;
    const spring *sp = s->sp + o;
    const double *K = s->K + o, *S = s->S + o;
    if (pair_load) memset(pair_load, 0, (size_t)s->max_pairs * sizeof *pair_load);
    if (line_load) memset(line_load, 0, (size_t)s->slices * sizeof *line_load);
    if (npairs) *npairs = 0;
    if (flags) *flags = 0;
    if (c == 0) { /* not reached for eps_gamma >= 1; reported, never NaN */
        *ste = 0, *k = 0;
        if (flags) *flags = GD_LTCA_NO_CONTACT;
        return;
    }
    /* a = first j in [1, c) with f(e_j) >= F, or c: springs 0..a-1 carry load */
    size_t lo = 1, hi = c;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (K[mid - 1] * sp[mid].e - S[mid - 1] < F)
            lo = mid + 1;
        else
            hi = mid;
    }
    const size_t a = lo;
    double kc = K[a - 1], delta = (F + S[a - 1]) / kc;
    *ste = delta, *k = kc;
    if (s->kbody > 0) {
        *ste += F / s->kbody;
        *k = 1 / (1 / kc + 1 / s->kbody);
    }
    if (!pair_load && !line_load) return;
    for (size_t j = 0; j < a; j++) {
        double w = sp[j].k * (delta - sp[j].e);
        if (!(w > 0)) continue;
        if (pair_load) pair_load[sp[j].slot] += w;
        if (line_load) line_load[sp[j].slice] += w;
    }
    if (npairs && pair_load)
        for (int j = 0; j < s->max_pairs; j++)
            *npairs += pair_load[j] > 0;
    if (!line_load) return;
    const double db = s->b / s->slices;
    int *geo = s->geo_slices, loaded = 0, partial = 0;
    memset(geo, 0, (size_t)s->slices * sizeof *geo);
    for (size_t j = 0; j < c; j++)
        geo[sp[j].slice] = 1;
    for (int j = 0; j < s->slices; j++) {
        line_load[j] /= db;
        if (line_load[j] > 0)
            loaded++;
        else if (geo[j])
            partial = 1;
    }
    if (flags)
        *flags = (partial ? GD_LTCA_PARTIAL_FACE : 0) |
                 (s->slices > 4 && loaded <= 2 ? GD_LTCA_EDGE_CONTACT : 0);
}

void gd_ltca_free(gd_ltca_result *r)
{
    if (!r) return;
    free(r->angle_rad);
    free(r->ste);
    free(r->ste_unloaded);
    free(r->stiffness);
    free(r->pairs_in_contact);
    free(r->pair_load);
    free(r->line_load);
    free(r->face_load_factor);
    free(r->flags);
    free(r->line_load_mean);
    free(r);
}

gd_status gd_ltca_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                          gd_ltca_result **out, gd_error *err)
{
    *out = NULL;
    gd_tvms_options defaults;
    if (!opt) {
        gd_tvms_options_init(&defaults);
        opt = &defaults;
    }
    gd_status st = check_torque(opt->load_torque, err);
    ltca_set s;
    if (st || (st = build(g, opt, &s, err))) return st;
    gd_ltca_result *r = calloc(1, sizeof *r);
    if (!r) {
        set_free(&s);
        return oom(err);
    }
    const size_t n = s.points * (size_t)opt->cycles, N = (size_t)s.slices;
    const size_t P = (size_t)s.max_pairs;
    r->method = opt->method;
    r->geom = s.d;
    r->torque = opt->load_torque;
    r->force = opt->load_torque * s.force_per_torque;
    r->misalignment = opt->misalignment;
    r->mesh_period_rad = s.d.mesh_period;
    r->n = n;
    r->points = s.points;
    r->slices = s.slices;
    r->max_pairs = s.max_pairs;
    r->slice_width = s.b / s.slices;
    r->body_stiffness = s.kbody;
    r->angle_rad = malloc(n * sizeof *r->angle_rad);
    r->ste = malloc(n * sizeof *r->ste);
    r->ste_unloaded = malloc(n * sizeof *r->ste_unloaded);
    r->stiffness = malloc(n * sizeof *r->stiffness);
    r->pairs_in_contact = malloc(n * sizeof *r->pairs_in_contact);
    r->pair_load = malloc(n * P * sizeof *r->pair_load);
    r->line_load = malloc(n * N * sizeof *r->line_load);
    r->face_load_factor = malloc(n * sizeof *r->face_load_factor);
    r->flags = malloc(n * sizeof *r->flags);
    r->line_load_mean = calloc(N, sizeof *r->line_load_mean);
    if (!r->angle_rad || !r->ste || !r->ste_unloaded || !r->stiffness || !r->pairs_in_contact ||
        !r->pair_load || !r->line_load || !r->face_load_factor || !r->flags || !r->line_load_mean) {
        gd_ltca_free(r);
        set_free(&s);
        return oom(err);
    }
    const double F = r->force, mean_line = F / s.b;
    double smin = HUGE_VAL, smax = -HUGE_VAL, ssum = 0, kmin = HUGE_VAL, kmax = 0, ksum = 0;
    for (size_t i = 0; i < n; i++) {
        size_t p = i % s.points;
        double *ll = r->line_load + i * N;
        r->angle_rad[i] = s.d.mesh_period * (double)i / (double)s.points;
        if (i >= s.points) { /* later cycles repeat the first */
            r->ste[i] = r->ste[p];
            r->ste_unloaded[i] = r->ste_unloaded[p];
            r->stiffness[i] = r->stiffness[p];
            r->pairs_in_contact[i] = r->pairs_in_contact[p];
            memcpy(r->pair_load + i * P, r->pair_load + p * P, P * sizeof *r->pair_load);
            memcpy(ll, r->line_load + p * N, N * sizeof *ll);
            r->face_load_factor[i] = r->face_load_factor[p];
            r->flags[i] = r->flags[p];
            continue;
        }
        solve(&s, p, F, &r->ste[i], &r->stiffness[i], &r->pairs_in_contact[i], r->pair_load + i * P,
              ll, &r->flags[i]);
        r->ste_unloaded[i] = s.off[p + 1] > s.off[p] ? s.sp[s.off[p]].e : 0;
        double mx = 0;
        for (size_t j = 0; j < N; j++) {
            if (ll[j] > mx) mx = ll[j];
            r->line_load_mean[j] += ll[j] / (double)s.points;
        }
        r->face_load_factor[i] = mx / mean_line;
        if (r->flags[i]) r->flagged++;
        double e = r->ste[i], k = r->stiffness[i];
        ssum += e, ksum += k;
        if (e < smin) smin = e;
        if (e > smax) smax = e;
        if (k < kmin) kmin = k;
        if (k > kmax) kmax = k;
    }
    double mx = 0;
    for (size_t j = 0; j < N; j++)
        if (r->line_load_mean[j] > mx) mx = r->line_load_mean[j];
    r->face_load_factor_cycle = mx / mean_line;
    r->ste_mean = ssum / (double)s.points;
    r->ste_peak_to_peak = smax - smin;
    r->stiffness_mean = ksum / (double)s.points;
    r->stiffness_min = kmin;
    r->stiffness_max = kmax;
    set_free(&s);
    *out = r;
    return GD_OK;
}

void gd_ltca_map_free(gd_ltca_map *m)
{
    if (!m) return;
    free(m->torque);
    free(m->ste_peak_to_peak);
    free(m->ste_mean);
    free(m->stiffness_mean);
    free(m->face_load_factor_cycle);
    free(m->flagged);
    free(m->ste);
    free(m->ste_unloaded);
    free(m);
}

gd_status gd_ltca_map_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                              const double *torques, int nloads, gd_ltca_map **out, gd_error *err)
{
    *out = NULL;
    gd_tvms_options defaults;
    if (!opt) {
        gd_tvms_options_init(&defaults);
        opt = &defaults;
    }
    if (nloads < 1 || nloads > 100000)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "load", "give 1 to 100000 loads",
                            "%d loads is out of range", nloads);
    for (int l = 0; l < nloads; l++) {
        gd_status st = check_torque(torques[l], err);
        if (st) return st;
    }
    ltca_set s;
    gd_status st = build(g, opt, &s, err);
    if (st) return st;
    gd_ltca_map *m = calloc(1, sizeof *m);
    const size_t n = s.points, N = (size_t)s.slices, L = (size_t)nloads;
    double *ll = malloc(N * sizeof *ll), *llm = malloc(N * sizeof *llm);
    if (m) {
        m->nloads = nloads;
        m->points = n;
        m->torque = malloc(L * sizeof *m->torque);
        m->ste_peak_to_peak = malloc(L * sizeof *m->ste_peak_to_peak);
        m->ste_mean = malloc(L * sizeof *m->ste_mean);
        m->stiffness_mean = malloc(L * sizeof *m->stiffness_mean);
        m->face_load_factor_cycle = malloc(L * sizeof *m->face_load_factor_cycle);
        m->flagged = calloc(L, sizeof *m->flagged);
        m->ste = malloc(L * n * sizeof *m->ste);
        m->ste_unloaded = malloc(n * sizeof *m->ste_unloaded);
    }
    if (!m || !ll || !llm || !m->torque || !m->ste_peak_to_peak || !m->ste_mean ||
        !m->stiffness_mean || !m->face_load_factor_cycle || !m->flagged || !m->ste ||
        !m->ste_unloaded) {
        free(ll);
        free(llm);
        gd_ltca_map_free(m);
        set_free(&s);
        return oom(err);
    }
    for (size_t p = 0; p < n; p++)
        m->ste_unloaded[p] = s.off[p + 1] > s.off[p] ? s.sp[s.off[p]].e : 0;
    for (size_t l = 0; l < L; l++) {
        double F = torques[l] * s.force_per_torque;
        double smin = HUGE_VAL, smax = -HUGE_VAL, ssum = 0, ksum = 0;
        memset(llm, 0, N * sizeof *llm);
        for (size_t p = 0; p < n; p++) {
            double e, k;
            int fl = 0;
            solve(&s, p, F, &e, &k, NULL, NULL, ll, &fl);
            for (size_t j = 0; j < N; j++)
                llm[j] += ll[j];
            m->ste[l * n + p] = e;
            if (fl) m->flagged[l]++;
            ssum += e, ksum += k;
            if (e < smin) smin = e;
            if (e > smax) smax = e;
        }
        double mx = 0;
        for (size_t j = 0; j < N; j++)
            if (llm[j] > mx) mx = llm[j];
        m->torque[l] = torques[l];
        m->ste_peak_to_peak[l] = smax - smin;
        m->ste_mean[l] = ssum / (double)n;
        m->stiffness_mean[l] = ksum / (double)n;
        m->face_load_factor_cycle[l] = mx / (double)n / (F / s.b);
    }
    free(ll);
    free(llm);
    set_free(&s);
    *out = m;
    return GD_OK;
}
