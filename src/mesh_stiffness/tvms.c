/* Time-varying mesh stiffness over mesh cycles: picks the stiffness law of the chosen
 * method, sums tooth pairs and slices (slicing.c), converts to the normal-plane
 * convention of mesh_stiffness.h, adds the body compliance in series and summarises. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/remainder_impl.h"
#include "mesh_stiffness/mesh_stiffness_impl.h"

static const char *const METHOD_NAMES[GD_TVMS_METHOD_COUNT_] = {"energy", "iso6336",
                                                                "single-pair-law", "square"};

const char *gd_tvms_method_name(gd_tvms_method m)
{
    return (int)m >= 0 && m < GD_TVMS_METHOD_COUNT_ ? METHOD_NAMES[m] : NULL;
}

gd_status gd_tvms_method_parse(const char *name, gd_tvms_method *m, gd_error *err)
{
    for (int i = 0; i < GD_TVMS_METHOD_COUNT_; i++)
        if (name && strcmp(name, METHOD_NAMES[i]) == 0) {
            *m = (gd_tvms_method)i;
            return GD_OK;
        }
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "method",
                        "use energy, iso6336, single-pair-law or square", "unknown method '%s'",
                        name ? name : "");
}

const char *gd_gear_pair_error_prefix(gd_error *err, const char *mesh_path)
{
    static const char *const OPTION_FIELDS[] = {"method",    "points", "cycles",       "slices",
                                                "harmonics", "load",   "misalignment", NULL};
    const char *section = "geometry";
    for (int i = 0; OPTION_FIELDS[i]; i++)
        if (!strcmp(err->field, OPTION_FIELDS[i])) section = "stiffness";
    char field[sizeof err->field];
    if (err->field[0])
        snprintf(field, sizeof field, "%s.%s.%.100s", mesh_path, section, err->field);
    else
        snprintf(field, sizeof field, "%s.%s", mesh_path, section);
    snprintf(err->field, sizeof err->field, "%s", field);
    return section;
}

void gd_tvms_options_init(gd_tvms_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->method = GD_TVMS_ENERGY;
    opt->points = 360;
    opt->cycles = 1;
    opt->slices = 50;
    opt->harmonics = 5;
    opt->quad_tol = 1e-10;
}

void gd_tvms_free(gd_tvms_result *r)
{
    if (!r) return;
    free(r->angle_rad);
    free(r->stiffness);
    free(r->pairs_in_contact);
    free(r->load_share);
    free(r->harmonic_amplitude);
    free(r->harmonic_phase);
    free(r);
}

gd_status gd_ms_check_options(const gd_tvms_options *o, gd_error *err)
{
    const char *f = NULL, *h = NULL;
    char msg[200];
    if ((int)o->method < 0 || o->method >= GD_TVMS_METHOD_COUNT_) {
        f = "method";
        h = "use one of: energy, iso6336, single-pair-law, square";
        snprintf(msg, sizeof msg, "unknown method %d", (int)o->method);
    } else if (o->points < 8 || o->points > 1000000) {
        f = "points";
        h = "give from 8 to 1000000 points per mesh cycle";
        snprintf(msg, sizeof msg, "%d points per mesh cycle is out of range", o->points);
    } else if (o->cycles < 1 || o->cycles > 10000) {
        f = "cycles";
        h = "give from 1 to 10000 mesh cycles";
        snprintf(msg, sizeof msg, "%d mesh cycles is out of range", o->cycles);
    } else if (o->slices < 1 || o->slices > 100000) {
        f = "slices";
        h = "give from 1 to 100000 slices";
        snprintf(msg, sizeof msg, "%d slices is out of range", o->slices);
    } else if (o->harmonics < 0 || o->harmonics > 100) {
        f = "harmonics";
        h = "give from 0 to 100 harmonics";
        snprintf(msg, sizeof msg, "%d harmonics is out of range", o->harmonics);
    } else if ((double)o->points * o->cycles > GD_TVMS_MAX_SAMPLES) {
        /* each bound alone allows 1e10 samples (hundreds of GB) */
        f = "points";
        h = "lower points or cycles";
        snprintf(msg, sizeof msg,
                 "points x cycles = %.3g samples, more than the limit of %.0e per table",
                 (double)o->points * o->cycles, GD_TVMS_MAX_SAMPLES);
    } else if ((double)o->points * o->slices > GD_TVMS_MAX_SLICE_EVALS) {
        /* each contact evaluation integrates the tooth: 1e11 of them take hours */
        f = "slices";
        h = "lower points or slices";
        snprintf(msg, sizeof msg,
                 "points x slices = %.3g contact evaluations, more than the limit of %.0e",
                 (double)o->points * o->slices, GD_TVMS_MAX_SLICE_EVALS);
    } else if (!(o->quad_tol > 0 && o->quad_tol <= 1e-3)) {
        f = "quad_tol";
        h = "give a relative tolerance in (0, 1e-3]";
        snprintf(msg, sizeof msg, "quadrature tolerance %g is out of range", o->quad_tol);
    }
    if (!f) return GD_OK;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, f, h, "%s", msg);
}

void gd_ms_tvms_summarise(gd_tvms_result *r)
{
    double sum = 0, mx = -HUGE_VAL, mn = HUGE_VAL;
    for (size_t i = 0; i < r->points; i++) {
        double k = r->stiffness[i];
        sum += k;
        if (k > mx) mx = k;
        if (k < mn) mn = k;
    }
    r->mean = sum / (double)r->points;
    r->max = mx;
    r->min = mn;
    r->peak_to_peak = mx - mn;
    gd_ms_fourier(r->stiffness, r->points, r->harmonics, r->harmonic_amplitude, r->harmonic_phase);
}

gd_status gd_tvms_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                          gd_tvms_result **out, gd_error *err)
{
    *out = NULL;
    gd_tvms_options defaults;
    if (!opt) {
        gd_tvms_options_init(&defaults);
        opt = &defaults;
    }
    gd_status st = gd_ms_check_options(opt, err);
    if (st) return st;
    gd_gear_pair_derived d;
    if ((st = gd_gear_pair_derive(g, &d, err))) return st;

    gd_tvms_result *r = calloc(1, sizeof *r);
    if (!r) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    r->method = opt->method;
    r->geom = d;
    r->mesh_period_rad = d.mesh_period;
    r->points = (size_t)opt->points;
    r->n = (size_t)opt->points * (size_t)opt->cycles;
    double cb = cos(d.base_helix_angle);
    r->transverse_factor = cb * cb;
    r->slices = g->helix_angle > 0 ? opt->slices : 1;
    r->max_pairs = (int)ceil(d.contact_ratio_total - 1e-12);
    if (r->max_pairs < 1) r->max_pairs = 1;
    r->harmonics = opt->harmonics;

    gd_ms_pair_law law;
    gd_ms_iso6336(g, &d, &law.iso);
    const gd_ms_iso iso = law.iso;
    double b = g->face_width;
    r->iso_single_stiffness = iso.c_single * b / r->transverse_factor;
    r->iso_mesh_stiffness_alpha = iso.c_gamma_alpha * b / r->transverse_factor;
    r->iso_mesh_stiffness_beta = iso.c_gamma_beta * b / r->transverse_factor;
    r->body_stiffness = opt->body_compliance ? gd_ms_body_stiffness(g, &d) : 0;

    r->angle_rad = malloc(r->n * sizeof *r->angle_rad);
    r->stiffness = malloc(r->n * sizeof *r->stiffness);
    r->pairs_in_contact = malloc(r->n * sizeof *r->pairs_in_contact);
    r->load_share = calloc(r->n * (size_t)r->max_pairs, sizeof *r->load_share);
    r->harmonic_amplitude = calloc((size_t)r->harmonics + 1, sizeof *r->harmonic_amplitude);
    r->harmonic_phase = calloc((size_t)r->harmonics + 1, sizeof *r->harmonic_phase);
    double *pair_k = calloc((size_t)r->max_pairs, sizeof *pair_k);
    int have_law = 0;
    if (!r->angle_rad || !r->stiffness || !r->pairs_in_contact || !r->load_share ||
        !r->harmonic_amplitude || !r->harmonic_phase || !pair_k)
        goto oom;

    if (gd_ms_pair_law_init(&law, g, &d, opt->method, opt->quad_tol)) goto oom;
    have_law = 1;
    gd_ms_slicing sl = {&d, b, r->slices, law.fn, law.ctx, r->max_pairs};
    for (size_t i = 0; i < r->n; i++) {
        double th = d.mesh_period * (double)i / (double)opt->points;
        int np = 0;
        double kt = gd_ms_slicing_eval(&sl, th, pair_k, &np);
        double k = kt / r->transverse_factor;
        if (opt->method == GD_TVMS_ISO6336) k = r->iso_mesh_stiffness_alpha;
        if (r->body_stiffness > 0 && k > 0) k = 1 / (1 / k + 1 / r->body_stiffness);
        r->angle_rad[i] = th;
        r->stiffness[i] = k;
        r->pairs_in_contact[i] = np;
        for (int j = 0; j < r->max_pairs; j++)
            r->load_share[i * (size_t)r->max_pairs + j] = kt > 0 ? pair_k[j] / kt : 0;
    }
    if (have_law) gd_ms_pair_law_free(&law);
    free(pair_k);

    gd_ms_tvms_summarise(r);
    if (!(r->min > 0)) {
        double mn = r->min;
        gd_tvms_free(r);
        return gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "report this geometry as a bug",
                            "mesh stiffness is not positive at some angle (min %g N/m)", mn);
    }
    *out = r;
    return GD_OK;
oom:
    free(pair_k);
    gd_tvms_free(r);
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "reduce points or cycles", "out of memory");
}

double gd_tvms_eval(const gd_tvms_result *r, double driver_angle)
{
    double T = r->mesh_period_rad;
    double ph = gd_remainder(driver_angle, T);
    if (ph < 0) ph += T;
    double x = ph / T * (double)r->points;
    size_t i = (size_t)x;
    if (i >= r->points) i = r->points - 1;
    double f = x - (double)i;
    return r->stiffness[i] * (1 - f) + r->stiffness[(i + 1) % r->points] * f;
}
