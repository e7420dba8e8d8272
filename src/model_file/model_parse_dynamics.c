/* Model keys that only time integration reads (docs/model-format.md, "Time
 * integration"): mesh TVMS tables, damping laws, transmission error and backlash;
 * squeeze film dampers on bearings; applied loads, prescribed motion and cam torques. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model_file/model_file_impl.h"

#define PI 3.14159265358979323846

/* ---- meshes ---- */

static const char *const MESH_DAMPING_KEYS[] = {"constant", "per_stiffness", "separated", NULL};
static const char *const BACKLASH_KEYS[] = {"gap", "coast_stiffness_ratio", NULL};
static const char *const TVMS_KEYS[] = {"angle", "stiffness", "interpolation", "phase", NULL};

gd_status gd_mp_mesh_dynamics(gd_mparser *p, const gd_ynode *mm, const char *path, int teeth,
                              gd_mesh_spec *s, gd_table **tvms, gd_table **ste)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char q[200];
    *tvms = *ste = NULL;

    const gd_ynode *damp = gd_ymap_get(mm, "damping");
    if (damp && damp->kind == GD_Y_MAP) {
        gd_ypath_key(q, sizeof q, path, "damping");
        if ((st = gd_ycheck_keys(r, damp, q, MESH_DAMPING_KEYS)) ||
            (st = gd_yread_qty(r, damp, "constant", q, GD_QTY_DAMPING, GD_YNONNEG, &s->damping,
                               NULL)) ||
            (st = gd_yread_qty(r, damp, "per_stiffness", q, GD_QTY_TIME, GD_YNONNEG,
                               &s->damping_per_stiffness, NULL)) ||
            (st = gd_yread_qty(r, damp, "separated", q, GD_QTY_DAMPING, GD_YNONNEG,
                               &s->damping_separated, NULL)))
            return st;
    } else if ((st = gd_yread_qty(r, mm, "damping", path, GD_QTY_DAMPING, GD_YNONNEG, &s->damping,
                                  NULL))) {
        return st;
    }

    /* a table spans the mesh period: without the driver's teeth (period 0) the
       builder reports the missing teeth */
    double period = teeth > 0 ? 2 * PI / teeth : 0;
    const gd_ynode *tv = gd_ymap_get(mm, "tvms");
    if (tv) {
        gd_ypath_key(q, sizeof q, path, "tvms");
        if ((st = gd_yexpect(r, tv, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, tv, q, TVMS_KEYS)) ||
            (st = gd_yread_qty(r, tv, "phase", q, GD_QTY_ANGLE, 0, &s->tvms_phase, NULL)))
            return st;
        /* gd_mp_read_table checks only its own keys: hand it the map without `phase` */
        gd_ynode copy = *tv;
        gd_ynode *keys[4], *items[4];
        copy.n = 0;
        copy.keys = keys;
        copy.items = items;
        for (size_t i = 0; i < tv->n && copy.n < 4; i++)
            if (strcmp(tv->keys[i]->text, "phase")) {
                keys[copy.n] = tv->keys[i];
                items[copy.n++] = tv->items[i];
            }
        if ((st = gd_mp_read_table(p, &copy, q, "angle", GD_QTY_ANGLE, "stiffness",
                                   GD_QTY_STIFFNESS, period, GD_INTERP_LINEAR, tvms)))
            return st;
        s->tvms = gd_mp_table_spec(*tvms);
    }
    const gd_ynode *te = gd_ymap_get(mm, "transmission_error");
    if (te) {
        gd_ypath_key(q, sizeof q, path, "transmission_error");
        if ((st = gd_mp_read_table(p, te, q, "angle", GD_QTY_ANGLE, "error", GD_QTY_LENGTH, period,
                                   GD_INTERP_LINEAR, ste)))
            return st;
        s->transmission_error = gd_mp_table_spec(*ste);
    }
    const gd_ynode *bl = gd_ymap_get(mm, "backlash");
    if (bl) {
        gd_ypath_key(q, sizeof q, path, "backlash");
        if ((st = gd_yexpect(r, bl, GD_Y_MAP, q)) ||
            (st = gd_ycheck_keys(r, bl, q, BACKLASH_KEYS)) ||
            (st = gd_yread_qty(r, bl, "gap", q, GD_QTY_LENGTH, GD_YREQ | GD_YNONNEG,
                               &s->backlash_gap, NULL)) ||
            (st = gd_yread_qty(r, bl, "coast_stiffness_ratio", q, GD_QTY_DIMLESS, GD_YNONNEG,
                               &s->coast_stiffness_ratio, NULL)))
            return st;
        s->backlash = 1;
    }
    return GD_OK;
}

/* ---- squeeze film dampers ---- */

static const char *const SFD_KEYS[] = {"viscosity", "diameter",   "length",           "clearance",
                                       "film",      "correction", "max_eccentricity", NULL};
static const char *const FILMS[] = {"pi", "2pi", NULL};

gd_status gd_mp_bearing_sfd(gd_mparser *p, const gd_ynode *bm, const char *path, gd_bearing_spec *b)
{
    const gd_ynode *sm = gd_ymap_get(bm, "sfd");
    if (!sm) return GD_OK;
    gd_yreader *r = &p->r;
    char q[200];
    gd_ypath_key(q, sizeof q, path, "sfd");
    gd_sfd_params *s = &b->sfd;
    double diameter = 0;
    int film = 0;
    gd_status st;
    if ((st = gd_yexpect(r, sm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, sm, q, SFD_KEYS)) ||
        (st = gd_yread_qty(r, sm, "viscosity", q, GD_QTY_VISCOSITY, GD_YREQ | GD_YPOS,
                           &s->viscosity, NULL)) ||
        (st = gd_yread_qty(r, sm, "diameter", q, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &diameter,
                           NULL)) ||
        (st = gd_yread_qty(r, sm, "length", q, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &s->length,
                           NULL)) ||
        (st = gd_yread_qty(r, sm, "clearance", q, GD_QTY_LENGTH, GD_YREQ | GD_YPOS, &s->clearance,
                           NULL)) ||
        (st = gd_yread_str(r, sm, "film", q, FILMS, 0, NULL, &film, NULL)) ||
        (st = gd_yread_qty(r, sm, "max_eccentricity", q, GD_QTY_DIMLESS, GD_YPOS,
                           &s->max_eccentricity, NULL)))
        return st;
    s->radius = 0.5 * diameter;
    s->film = film == 0 ? GD_SFD_PI_FILM : GD_SFD_2PI_FILM;
    const gd_ynode *corr = gd_ymap_get(sm, "correction");
    s->correction = 0; /* auto */
    if (corr) {
        char fp[220];
        gd_ypath_key(fp, sizeof fp, q, "correction");
        if (corr->kind == GD_Y_SCALAR && !strcmp(corr->text, "auto"))
            s->correction = 0;
        else if (corr->kind == GD_Y_SCALAR && !strcmp(corr->text, "none"))
            s->correction = -1;
        else if ((st = gd_yread_node_qty(r, corr, fp, GD_QTY_DIMLESS, GD_YPOS, &s->correction)))
            return gd_yfail(r, corr, fp, "write auto, none or a positive factor",
                            "'%s' is not a correction",
                            corr->kind == GD_Y_SCALAR ? corr->text : "?");
    }
    b->has_sfd = 1;
    return GD_OK;
}

/* ---- top level: excitations, prescribed, cam_torques ---- */

static const char *const EXCITATION_KEYS[] = {"unbalances", "loads", NULL};
static const char *const LOAD_KEYS[] = {"name",      "node",  "dof",   "value", "mean", "amplitude",
                                        "frequency", "order", "phase", "table", NULL};
static const char *const DOF_CHOICES[] = {"x", "y", "z", "rx", "ry", "rz", NULL};

static gd_status read_dof(gd_mparser *p, const gd_ynode *map, const char *path, gd_dof *dof)
{
    int d = GD_RZ;
    gd_status st = gd_yread_str(&p->r, map, "dof", path, DOF_CHOICES, 0, NULL, &d, NULL);
    *dof = (gd_dof)d;
    return st;
}

static gd_status read_load(gd_mparser *p, const gd_ynode *lm, const char *q, int index)
{
    gd_yreader *r = &p->r;
    gd_status st;
    char fb[32], name[GD_NAME_MAX];
    gd_excitation_spec e;
    gd_excitation_spec_init(&e);
    snprintf(fb, sizeof fb, "load%d", index + 1);
    if ((st = gd_yexpect(r, lm, GD_Y_MAP, q)) || (st = gd_ycheck_keys(r, lm, q, LOAD_KEYS)) ||
        (st = gd_mp_read_name(p, lm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, lm, "node", q, 1, &e.node)) || (st = read_dof(p, lm, q, &e.dof)))
        return st;
    e.name = name;
    e.loc = gd_mp_loc(lm);
    e.path = q;
    gd_qty vq = e.dof >= GD_RX ? GD_QTY_TORQUE : GD_QTY_FORCE;
    gd_load_law *L = &e.law;
    int has_value, has_mean, has_amp, has_freq, has_order, has_table;
    double order = 0;
    if ((st = gd_yread_qty(r, lm, "value", q, vq, 0, &L->mean, &has_value)) ||
        (st = gd_yread_qty(r, lm, "mean", q, vq, 0, &L->mean, &has_mean)) ||
        (st = gd_yread_qty(r, lm, "amplitude", q, vq, 0, &L->amplitude, &has_amp)) ||
        (st = gd_yread_qty(r, lm, "frequency", q, GD_QTY_ANGULAR_SPEED, GD_YPOS, &L->frequency,
                           &has_freq)) ||
        (st = gd_yread_qty(r, lm, "order", q, GD_QTY_DIMLESS, GD_YPOS, &order, &has_order)) ||
        (st = gd_yread_qty(r, lm, "phase", q, GD_QTY_ANGLE, 0, &L->phase, NULL)))
        return st;
    has_table = gd_ymap_get(lm, "table") != NULL;
    const char *hint = "give `value`, or `amplitude` with `frequency` (in time) or `order` (per "
                       "revolution), or a `table` over one revolution";
    if (has_value && (has_mean || has_amp || has_freq || has_order || has_table))
        return gd_yfail(r, lm, q, hint, "`value` is a constant load: give nothing else with it");
    if (has_freq + has_order + has_table > 1)
        return gd_yfail(r, lm, q, hint, "more than one of frequency, order and table");
    if ((has_freq || has_order) && !has_amp)
        return gd_yfail(r, lm, q, hint, "a harmonic load needs `amplitude`");
    if (has_amp && !has_freq && !has_order)
        return gd_yfail(r, lm, q, hint, "`amplitude` needs `frequency` or `order`");
    if (!has_value && !has_mean && !has_amp && !has_table)
        return gd_yfail(r, lm, q, hint, "the load has no value");
    gd_table *t = NULL;
    if (has_freq) {
        L->kind = GD_LOAD_HARMONIC_TIME;
    } else if (has_order) {
        L->kind = GD_LOAD_HARMONIC_ANGLE;
        L->frequency = order;
    } else if (has_table) {
        char tq[220];
        L->kind = GD_LOAD_TABLE_ANGLE;
        if ((st = gd_mp_read_table(p, gd_ymap_get(lm, "table"),
                                   gd_ypath_key(tq, sizeof tq, q, "table"), "angle", GD_QTY_ANGLE,
                                   "value", vq, 2 * PI, GD_INTERP_LINEAR, &t)))
            return st;
        e.table = gd_mp_table_spec(t);
    } else {
        L->kind = GD_LOAD_CONSTANT;
    }
    st = gd_model_add_excitation(p->m, &e, NULL, r->err);
    gd_table_free(t);
    return st;
}

static gd_status parse_excitations(gd_mparser *p)
{
    const gd_ynode *ex = gd_ymap_get(p->root, "excitations");
    if (!ex) return GD_OK;
    gd_status st;
    int on = 1;
    if ((st = gd_yexpect(&p->r, ex, GD_Y_MAP, "excitations")) ||
        (st = gd_ycheck_keys(&p->r, ex, "excitations", EXCITATION_KEYS)) ||
        (st = gd_yread_bool(&p->r, ex, "unbalances", "excitations", 0, &on, NULL)) ||
        (st = gd_model_set_excite_unbalances(p->m, on, p->r.err)))
        return st;
    const gd_ynode *list;
    if ((st = gd_mp_get_list(p, ex, "loads", "excitations", &list, 0)) || !list) return st;
    for (size_t i = 0; i < list->n; i++) {
        char q[80];
        gd_ypath_index(q, sizeof q, "excitations.loads", i);
        if ((st = read_load(p, list->items[i], q, (int)i))) return st;
    }
    return GD_OK;
}

static const char *const PRESCRIBED_KEYS[] = {"node",      "dof",       "motion", "speed", "table",
                                              "amplitude", "frequency", "phase",  NULL};
static const char *const MOTIONS[] = {"nominal", NULL};

static gd_status read_prescribed(gd_mparser *p, const gd_ynode *pm, const char *q, size_t index)
{
    (void)index;
    gd_prescribed_spec pr;
    gd_prescribed_spec_init(&pr);
    int has_motion, has_speed, has_amp, has_freq, has_table;
    gd_status st;
    if ((st = gd_yexpect(&p->r, pm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, pm, q, PRESCRIBED_KEYS)) ||
        (st = gd_mp_node_name(p, pm, "node", q, 1, &pr.node)) ||
        (st = read_dof(p, pm, q, &pr.dof)) ||
        (st = gd_yread_str(&p->r, pm, "motion", q, MOTIONS, 0, NULL, NULL, &has_motion)) ||
        (st = gd_yread_qty(&p->r, pm, "speed", q, GD_QTY_ANGULAR_SPEED, 0, &pr.law.speed,
                           &has_speed)) ||
        (st =
             gd_yread_qty(&p->r, pm, "amplitude", q, pr.dof >= GD_RX ? GD_QTY_ANGLE : GD_QTY_LENGTH,
                          0, &pr.law.amplitude, &has_amp)) ||
        (st = gd_yread_qty(&p->r, pm, "frequency", q, GD_QTY_ANGULAR_SPEED, GD_YPOS,
                           &pr.law.frequency, &has_freq)) ||
        (st = gd_yread_qty(&p->r, pm, "phase", q, GD_QTY_ANGLE, 0, &pr.law.phase, NULL)))
        return st;
    pr.loc = gd_mp_loc(pm);
    pr.path = q;
    has_table = gd_ymap_get(pm, "table") != NULL;
    if (has_motion + has_speed + has_table + has_amp != 1 || has_amp != has_freq)
        return gd_yfail(&p->r, pm, q,
                        "give one of `motion: nominal`, `speed: ...`, `table: {time: [...], "
                        "angle: [...]}` or `amplitude` with `frequency`",
                        "the prescribed motion is missing or given twice");
    gd_table *t = NULL;
    if (has_motion) {
        pr.law.kind = GD_PRESCRIBED_NOMINAL;
    } else if (has_speed) {
        pr.law.kind = GD_PRESCRIBED_SPEED;
    } else if (has_amp) {
        pr.law.kind = GD_PRESCRIBED_HARMONIC;
    } else {
        char tq[100];
        gd_qty vq = pr.dof >= GD_RX ? GD_QTY_ANGLE : GD_QTY_LENGTH;
        if ((st = gd_mp_read_table(
                 p, gd_ymap_get(pm, "table"), gd_ypath_key(tq, sizeof tq, q, "table"), "time",
                 GD_QTY_TIME, pr.dof >= GD_RX ? "angle" : "position", vq, 0, GD_INTERP_SPLINE, &t)))
            return st;
        pr.law.kind = GD_PRESCRIBED_TABLE;
        pr.table = gd_mp_table_spec(t);
    }
    st = gd_model_add_prescribed(p->m, &pr, NULL, p->r.err);
    gd_table_free(t);
    return st;
}

static gd_status parse_prescribed(gd_mparser *p)
{
    return gd_mp_each(p, "prescribed", read_prescribed);
}

static const char *const CAM_KEYS[] = {"name",   "camshaft", "lift", "include_acceleration",
                                       "valves", NULL};
static const char *const VALVE_KEYS[] = {"mass", "phase", NULL};
static const char *const HARMONIC_KEYS[] = {"mean", "cos", "sin", NULL};

/* The lift law; a table goes to *t (to free after the add). */
static gd_status read_lift(gd_mparser *p, const gd_ynode *lm, const char *q, gd_cam_spec *c,
                           gd_table **t)
{
    gd_status st;
    gd_lift_law *law = &c->lift;
    const gd_ynode *h = gd_ymap_get(lm, "harmonics");
    if (lm->kind == GD_Y_MAP && h) {
        char hq[160];
        static const char *const only[] = {"harmonics", NULL};
        if ((st = gd_ycheck_keys(&p->r, lm, q, only))) return st;
        gd_ypath_key(hq, sizeof hq, q, "harmonics");
        if ((st = gd_yexpect(&p->r, h, GD_Y_MAP, hq)) ||
            (st = gd_ycheck_keys(&p->r, h, hq, HARMONIC_KEYS)) ||
            (st = gd_yread_qty(&p->r, h, "mean", hq, GD_QTY_LENGTH, 0, &law->harmonic.mean, NULL)))
            return st;
        law->kind = GD_LIFT_HARMONIC;
        law->harmonic.order = 1;
        const char *keys[2] = {"cos", "sin"};
        double *dst[2] = {law->harmonic.cos_amp, law->harmonic.sin_amp};
        for (int k = 0; k < 2; k++) {
            const gd_ynode *v = gd_ymap_get(h, keys[k]);
            if (!v) continue;
            double *vals;
            int n;
            if ((st = gd_mp_read_qty_list(p, h, keys[k], hq, GD_QTY_LENGTH, &vals, &n))) return st;
            if (n > GD_HARMONICS_MAX) {
                free(vals);
                return gd_yfail(&p->r, v, hq, "use fewer harmonics", "more than %d harmonics",
                                GD_HARMONICS_MAX);
            }
            memcpy(dst[k], vals, (size_t)n * sizeof *vals);
            if (n > law->harmonic.n) law->harmonic.n = n;
            free(vals);
        }
        return GD_OK;
    }
    if ((st = gd_mp_read_table(p, lm, q, "angle", GD_QTY_ANGLE, "lift", GD_QTY_LENGTH, 2 * PI,
                               GD_INTERP_SPLINE, t)))
        return st;
    law->kind = GD_LIFT_TABLE;
    c->lift_table = gd_mp_table_spec(*t);
    return GD_OK;
}

static gd_status read_valves(gd_mparser *p, const gd_ynode *valves, const char *vq, double *mass,
                             double *phase)
{
    gd_status st;
    for (size_t j = 0; j < valves->n; j++) {
        char ip[120];
        gd_ypath_index(ip, sizeof ip, vq, j);
        const gd_ynode *v = valves->items[j];
        if ((st = gd_yexpect(&p->r, v, GD_Y_MAP, ip)) ||
            (st = gd_ycheck_keys(&p->r, v, ip, VALVE_KEYS)) ||
            (st = gd_yread_qty(&p->r, v, "mass", ip, GD_QTY_MASS, GD_YREQ | GD_YPOS, &mass[j],
                               NULL)) ||
            (st = gd_yread_qty(&p->r, v, "phase", ip, GD_QTY_ANGLE, 0, &phase[j], NULL)))
            return st;
    }
    return GD_OK;
}

static gd_status read_cam(gd_mparser *p, const gd_ynode *cm, const char *q, size_t i)
{
    char fb[32], lq[100], vq[100], name[GD_NAME_MAX];
    gd_cam_spec c;
    gd_cam_spec_init(&c);
    snprintf(fb, sizeof fb, "cam%zu", i + 1);
    const gd_ynode *valves;
    gd_status st;
    if ((st = gd_yexpect(&p->r, cm, GD_Y_MAP, q)) ||
        (st = gd_ycheck_keys(&p->r, cm, q, CAM_KEYS)) ||
        (st = gd_mp_read_name(p, cm, q, name, fb, 0)) ||
        (st = gd_mp_node_name(p, cm, "camshaft", q, 1, &c.camshaft)) ||
        (st =
             gd_yread_bool(&p->r, cm, "include_acceleration", q, 0, &c.include_acceleration, NULL)))
        return st;
    c.name = name;
    c.loc = gd_mp_loc(cm);
    c.path = q;
    if (!gd_ymap_get(cm, "lift"))
        return gd_yfail(&p->r, cm, gd_ypath_key(lq, sizeof lq, q, "lift"),
                        "add the valve lift law: `lift: {angle: [...], lift: [...]}` over one "
                        "cam revolution, or `lift: {harmonics: {mean, cos: [...], sin: [...]}}`",
                        "cam torque without a lift law");
    gd_table *t = NULL;
    double *mass = NULL, *phase = NULL;
    if (!(st = read_lift(p, gd_ymap_get(cm, "lift"), gd_ypath_key(lq, sizeof lq, q, "lift"), &c,
                         &t)) &&
        !(st = gd_mp_get_list(p, cm, "valves", q, &valves, 1))) {
        gd_ypath_key(vq, sizeof vq, q, "valves");
        mass = calloc(valves->n + 1, sizeof *mass);
        phase = calloc(valves->n + 1, sizeof *phase);
        if (!mass || !phase)
            st = gd_mp_oom(p);
        else
            st = read_valves(p, valves, vq, mass, phase);
        c.nvalves = (int)valves->n;
        c.valve_mass = mass;
        c.valve_phase = phase;
    }
    if (!st) st = gd_model_add_cam(p->m, &c, NULL, p->r.err);
    gd_table_free(t);
    free(mass);
    free(phase);
    return st;
}

static gd_status parse_cams(gd_mparser *p)
{
    return gd_mp_each(p, "cam_torques", read_cam);
}

gd_status gd_mp_dynamics(gd_mparser *p)
{
    gd_status st;
    if ((st = parse_excitations(p)) || (st = parse_prescribed(p)) || (st = parse_cams(p)))
        return st;
    return GD_OK;
}
