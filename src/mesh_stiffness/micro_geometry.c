/* Tooth micro-geometry: the initial separation of a contact from both gears' profile
 * and lead modifications and the mesh misalignment (docs/mesh-stiffness.md,
 * "Micro-geometry"). All amounts are material removed along the contact normal, so the
 * separations of the two flanks add. Profile reliefs follow the roll length
 * rho = sqrt(r^2 - r_b^2) (linear tip relief is then linear along the line of action,
 * as in Tavakoli & Houser, J. Mech. Trans. Autom. Des. 108 (1986) 86); a contact at s
 * from N1 has roll length s on the driver and N1N2 - s on the driven gear (N1N2 + s on
 * the ring of an internal pair, whose tip is its smallest roll length and its form
 * circle the largest: the reliefs run toward them the same way). Lead
 * modifications and the misalignment follow the face position y of the mesh. */
#include <math.h>
#include <stdio.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const char *const GEAR_NAME[2] = {"driver", "driven"};

static double roll_of_diameter(double D, double rb)
{
    double r = 0.5 * D;
    return r > rb ? sqrt(r * r - rb * rb) : 0;
}

static double start_roll(const gd_profile_relief *p, double rb)
{
    return p->start_diameter > 0 ? roll_of_diameter(p->start_diameter, rb)
                                 : p->start_roll_angle * rb;
}

void gd_ms_mods_init(gd_ms_mods *m, const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                     double misalignment)
{
    m->line_of_action = d->line_of_action;
    m->internal = d->internal;
    m->face_width = g->face_width;
    m->crowning = 0;
    m->slope = misalignment;
    for (int i = 0; i < 2; i++) {
        const gd_tooth_modifications *t = &g->gear[i].mod;
        double rb = d->base_radius[i];
        double ra = d->tip_radius[i];
        m->tip[i] = (gd_ms_relief){t->tip_relief.amount, start_roll(&t->tip_relief, rb),
                                   sqrt(ra * ra - rb * rb), (int)t->tip_relief.shape};
        m->root[i] = (gd_ms_relief){t->root_relief.amount, start_roll(&t->root_relief, rb),
                                    d->form_roll[i], (int)t->root_relief.shape};
        m->crowning += t->crowning;
        m->end_amount[i] = t->end_relief;
        m->end_length[i] = t->end_relief_length;
        m->end_shape[i] = (int)t->end_relief_shape;
        m->slope += t->helix_slope_deviation;
    }
}

/* 0 at `from`, amount at `to`, on the side of `to` only. */
static double relief(const gd_ms_relief *r, double rho)
{
    if (!(r->amount > 0)) return 0;
    double u = (rho - r->from) / (r->to - r->from);
    if (!(u > 0)) return 0;
    return r->amount * (r->shape == GD_RELIEF_PARABOLIC ? u * u : u);
}

static double end_relief(double amount, double len, int shape, double y, double b)
{
    if (!(amount > 0)) return 0;
    double u = y < len ? (len - y) / len : y > b - len ? (y - (b - len)) / len : 0;
    return amount * (shape == GD_RELIEF_PARABOLIC ? u * u : u);
}

double gd_ms_mods_separation(const gd_ms_mods *m, double s, double y)
{
    const double b = m->face_width;
    double rho[2] = {s, m->internal ? s + m->line_of_action : m->line_of_action - s};
    double c = 2 * y / b - 1;
    double e = m->crowning * c * c + m->slope * (y / b - 0.5);
    for (int i = 0; i < 2; i++)
        e += relief(&m->tip[i], rho[i]) + relief(&m->root[i], rho[i]) +
             end_relief(m->end_amount[i], m->end_length[i], m->end_shape[i], y, b);
    return e;
}

int gd_ms_mods_any(const gd_gear_pair_geometry *g)
{
    for (int i = 0; i < 2; i++) {
        const gd_tooth_modifications *t = &g->gear[i].mod;
        if (t->tip_relief.amount != 0 || t->root_relief.amount != 0 || t->crowning != 0 ||
            t->end_relief != 0 || t->helix_slope_deviation != 0)
            return 1;
    }
    return 0;
}

static gd_status fail(gd_error *err, int gear, const char *key, const char *hint, const char *msg)
{
    char field[96];
    snprintf(field, sizeof field, "%s.modifications.%s", GEAR_NAME[gear], key);
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, "%s", msg);
}

/* An amount: finite, >= 0 (unless signed), at most a tenth of the module. */
static gd_status check_amount(gd_error *err, int gear, const char *key, double v, int signed_ok,
                              double mn)
{
    char msg[300];
    if (!isfinite(v) || (!signed_ok && v < 0)) {
        snprintf(msg, sizeof msg, "%s of %g m is %s", key, v,
                 isfinite(v) ? "negative" : "not a number");
        return fail(err, gear, key, "give an amount >= 0, e.g. \"10 um\"", msg);
    }
    if (fabs(v) > 0.1 * mn) {
        snprintf(msg, sizeof msg,
                 "%s of %.4g um is more than a tenth of the normal module (%.4g um): not a "
                 "micro-geometry",
                 key, v * 1e6, 0.1 * mn * 1e6);
        return fail(err, gear, key,
                    "amounts are in m unless a unit is given: write micrometres, e.g. \"20 um\"",
                    msg);
    }
    return GD_OK;
}

/* The ring of an internal pair: its tip circle is inside the reference circle and its
 * form circle outside, so a tip relief starts outside the tip (at most at the
 * reference circle) and a root relief inside the form circle (at least at the
 * reference circle), above the tip relief's start. */
static gd_status check_ring_relief(const gd_profile_relief *p, const gd_gear_pair_derived *d,
                                   int tip, double rho, double rs, double other_start,
                                   gd_error *err)
{
    const char *key = tip ? "tip_relief" : "root_relief";
    const char *sk = p->start_diameter > 0 ? "start_diameter" : "start_roll_angle";
    char k[64], msg[400], hint[300];
    snprintf(k, sizeof k, "%s.%s", key, sk);
    double rb = d->base_radius[1], r = d->pitch_radius[1], ra = d->tip_radius[1];
    double rho_a = sqrt(ra * ra - rb * rb), rho_f = d->form_roll[1];
    double dF = 2 * sqrt(rb * rb + rho_f * rho_f);
    if (tip && rho <= rho_a) {
        snprintf(msg, sizeof msg,
                 "the ring's tip relief starts at diameter %.4g mm, not outside its tip %.4g mm",
                 2 * rs * 1e3, 2 * ra * 1e3);
        snprintf(hint, sizeof hint, "start it between %.4g and %.4g mm", 2 * ra * 1e3, 2 * r * 1e3);
        return fail(err, 1, k, hint, msg);
    }
    if (tip && rs > r * (1 + 1e-12)) {
        snprintf(msg, sizeof msg,
                 "the ring's tip relief from diameter %.4g mm to its tip is longer than the "
                 "addendum: it starts outside the reference diameter %.4g mm",
                 2 * rs * 1e3, 2 * r * 1e3);
        snprintf(hint, sizeof hint, "start it between %.4g and %.4g mm", 2 * ra * 1e3, 2 * r * 1e3);
        return fail(err, 1, k, hint, msg);
    }
    if (!tip && rho >= rho_f) {
        snprintf(msg, sizeof msg,
                 "the ring's root relief starts at diameter %.4g mm, not inside its form "
                 "diameter %.4g mm where the involute ends",
                 2 * rs * 1e3, dF * 1e3);
        return fail(err, 1, k, "start the root relief inside the form diameter", msg);
    }
    if (!tip && rs < r * (1 - 1e-12)) {
        snprintf(msg, sizeof msg,
                 "the ring's root relief from diameter %.4g mm out to its form circle is longer "
                 "than the dedendum: it starts inside the reference diameter %.4g mm",
                 2 * rs * 1e3, 2 * r * 1e3);
        snprintf(hint, sizeof hint, "start it between %.4g and %.4g mm", 2 * r * 1e3, dF * 1e3);
        return fail(err, 1, k, hint, msg);
    }
    if (!tip && other_start > 0 && rho <= other_start) {
        snprintf(msg, sizeof msg,
                 "the ring's root relief starts at or inside the start of its "
                 "tip relief");
        return fail(err, 1, k, "the ring's root relief must start outside its tip relief", msg);
    }
    return GD_OK;
}

static gd_status check_relief(const gd_profile_relief *p, const gd_gear_pair_derived *d, int i,
                              int tip, double mn, double other_start, gd_error *err)
{
    const char *key = tip ? "tip_relief" : "root_relief";
    char k[64], msg[400], hint[300];
    snprintf(k, sizeof k, "%s.amount", key);
    gd_status st = check_amount(err, i, k, p->amount, 0, mn);
    if (st || p->amount == 0) return st;
    double rb = d->base_radius[i], r = d->pitch_radius[i], ra = d->tip_radius[i];
    double rho_a = sqrt(ra * ra - rb * rb), rho_f = d->form_roll[i];
    double dF = 2 * sqrt(rb * rb + rho_f * rho_f);
    if (!(p->start_diameter >= 0) || !(p->start_roll_angle >= 0) ||
        (p->start_diameter == 0 && p->start_roll_angle == 0)) {
        snprintf(k, sizeof k, "%s.start_diameter", key);
        snprintf(hint, sizeof hint,
                 "give start_diameter (between %.4g and %.4g mm) or start_roll_angle", 2 * r * 1e3,
                 tip ? 2 * ra * 1e3 : dF * 1e3);
        return fail(err, i, k, hint, "a relief needs a positive start diameter or roll angle");
    }
    const char *sk = p->start_diameter > 0 ? "start_diameter" : "start_roll_angle";
    snprintf(k, sizeof k, "%s.%s", key, sk);
    if (p->start_diameter > 0 && p->start_diameter <= 2 * rb) {
        snprintf(msg, sizeof msg, "start diameter %.4g mm is not above the base diameter %.4g mm",
                 p->start_diameter * 1e3, 2 * rb * 1e3);
        return fail(err, i, k, "the relief starts on the involute, above the base circle", msg);
    }
    double rho = start_roll(p, rb), rs = sqrt(rb * rb + rho * rho);
    if (d->internal && i == 1) return check_ring_relief(p, d, tip, rho, rs, other_start, err);
    if (tip && rho >= rho_a) {
        snprintf(msg, sizeof msg,
                 "tip relief starts at diameter %.4g mm, not below the tip %.4g mm", 2 * rs * 1e3,
                 2 * ra * 1e3);
        return fail(err, i, k, "start the relief below the tip diameter", msg);
    }
    if (tip && rs < r * (1 - 1e-12)) {
        snprintf(msg, sizeof msg,
                 "tip relief from diameter %.4g mm to the tip is longer than the addendum: it "
                 "starts below the reference diameter %.4g mm",
                 2 * rs * 1e3, 2 * r * 1e3);
        snprintf(hint, sizeof hint, "start it between %.4g and %.4g mm", 2 * r * 1e3, 2 * ra * 1e3);
        return fail(err, i, k, hint, msg);
    }
    if (!tip && rho <= rho_f) {
        snprintf(msg, sizeof msg,
                 "root relief starts at diameter %.4g mm, not above the form diameter %.4g mm "
                 "where the involute begins",
                 2 * rs * 1e3, dF * 1e3);
        return fail(err, i, k, "start the root relief above the form diameter", msg);
    }
    if (!tip && rs > r * (1 + 1e-12)) {
        snprintf(msg, sizeof msg,
                 "root relief from diameter %.4g mm down to the form circle is longer than the "
                 "dedendum: it starts above the reference diameter %.4g mm",
                 2 * rs * 1e3, 2 * r * 1e3);
        snprintf(hint, sizeof hint, "start it between %.4g and %.4g mm", dF * 1e3, 2 * r * 1e3);
        return fail(err, i, k, hint, msg);
    }
    if (!tip && other_start > 0 && rho >= other_start) {
        snprintf(msg, sizeof msg, "root relief starts at or above the start of the tip relief");
        return fail(err, i, k, "the root relief must start below the tip relief", msg);
    }
    return GD_OK;
}

gd_status gd_ms_mods_check(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                           gd_error *err)
{
    const double mn = g->normal_module, b = g->face_width;
    char msg[300];
    gd_status st;
    for (int i = 0; i < 2; i++) {
        const gd_tooth_modifications *t = &g->gear[i].mod;
        if ((st = check_relief(&t->tip_relief, d, i, 1, mn, 0, err))) return st;
        double tip_start =
            t->tip_relief.amount > 0 ? start_roll(&t->tip_relief, d->base_radius[i]) : 0;
        if ((st = check_relief(&t->root_relief, d, i, 0, mn, tip_start, err))) return st;
        if (t->crowning < 0) {
            snprintf(msg, sizeof msg, "negative crowning %.4g um (a hollow lead) is not allowed",
                     t->crowning * 1e6);
            return fail(err, i, "crowning",
                        "give C_b >= 0 (material removed at each face end); a tilt is "
                        "helix_slope_deviation",
                        msg);
        }
        if ((st = check_amount(err, i, "crowning", t->crowning, 0, mn)) ||
            (st = check_amount(err, i, "end_relief.amount", t->end_relief, 0, mn)) ||
            (st = check_amount(err, i, "helix_slope_deviation", t->helix_slope_deviation, 1, mn)))
            return st;
        if (t->end_relief > 0 && !(t->end_relief_length > 0 && t->end_relief_length <= 0.5 * b)) {
            snprintf(msg, sizeof msg, "end relief length %.4g mm is outside (0, b/2 = %.4g mm]",
                     t->end_relief_length * 1e3, 0.5 * b * 1e3);
            return fail(err, i, "end_relief.length", "give the length of the relieved zone", msg);
        }
        if ((int)t->tip_relief.shape < 0 || (int)t->tip_relief.shape > 1 ||
            (int)t->root_relief.shape < 0 || (int)t->root_relief.shape > 1 ||
            (int)t->end_relief_shape < 0 || (int)t->end_relief_shape > 1)
            return fail(err, i, "shape", "use linear or parabolic", "unknown relief shape");
    }
    return GD_OK;
}
