/* Shaft speeds follow the gear ratios from the reference shaft: an external mesh
 * reverses the sense, omega_driven = -omega_driver * rb_driver / rb_driven; a planetary
 * set with a held member ties its free members and planets (docs/planetary.md). A given
 * speed_ratio must agree with the train, and a loop of meshes must close. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "geardyn/planetary.h"
#include "model/build_impl.h"

/* Shaft `other` turns at ratio through the link named `via` (a mesh or a planetary set,
 * at loc and path): set it when not yet seen, or check that a loop closes. */
static gd_status reach(gd_model *m, int *seen, int *queue, int *tail, int other, double ratio,
                       const char *kind, const char *name, gd_loc loc, const char *path,
                       gd_error *err)
{
    gd_model_build *b = m->build;
    gd_shaft *o = &m->shafts[other];
    if (!seen[other]) {
        if (o->speed_ratio_given && fabs(o->speed_ratio - ratio) > 1e-6 * fabs(ratio)) {
            char field[200];
            gd_build_path(field, sizeof field, b->shafts[other].path, "speed_ratio");
            return gd_build_fail(m, err, o->speed_ratio_loc, NULL, field,
                                 "remove speed_ratio: it follows from the gear meshes",
                                 "shaft '%s' has speed_ratio %g but its meshes give %g", o->name,
                                 o->speed_ratio, ratio);
        }
        o->speed_ratio = ratio;
        seen[other] = 1;
        queue[(*tail)++] = other;
    } else if (fabs(o->speed_ratio - ratio) > 1e-6 * fabs(ratio)) {
        return gd_build_fail(m, err, loc, NULL, path,
                             "check the radii or teeth of the meshes in the loop",
                             "%s '%s' closes a loop with inconsistent gear ratios "
                             "(%g vs %g for shaft '%s')",
                             kind, name, ratio, o->speed_ratio, o->name);
    }
    return GD_OK;
}

/* The planetary sets with a member on shaft s (not the held one) give their other free
 * member and their planets the speeds of gd_planetary_kinematics_of. */
static gd_status spread_planetary(gd_model *m, int s, int *seen, int *queue, int *tail,
                                  gd_error *err)
{
    gd_status st;
    for (int k = 0; k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        gd_planetary_kinematics kin;
        gd_planetary_kinematics_of(g, &kin);
        if (kin.input < 0) continue; /* a differential: no fixed ratio */
        int from = -1;
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++)
            if (j != g->held && m->nodes[g->member[j].node].shaft == s && kin.speed[j] != 0)
                from = j;
        if (from < 0) continue;
        double unit = m->shafts[s].speed_ratio / kin.speed[from];
        const char *path = m->build->planetary[k].path;
        for (int j = 0; j < GD_PLANETARY_NMEMBERS; j++) {
            int other = m->nodes[g->member[j].node].shaft;
            if (j == from || other == s) continue; /* the held member's speed is 0 */
            if ((st = reach(m, seen, queue, tail, other, unit * kin.speed[j], "planetary set",
                            g->name, g->loc, path, err)))
                return st;
        }
        for (int n = 0; n < g->nplanets; n++)
            if ((st = reach(m, seen, queue, tail, m->nodes[g->first_planet + n].shaft,
                            unit * kin.planet_speed, "planetary set", g->name, g->loc, path, err)))
                return st;
    }
    return GD_OK;
}

/* An engaged synchroniser turns its idler with its shaft (ratio 1 either way). */
static gd_status spread_synchronisers(gd_model *m, int s, int *seen, int *queue, int *tail,
                                      gd_error *err)
{
    gd_status st;
    for (int k = 0; k < m->nsynchronisers; k++) {
        const gd_synchroniser *g = &m->synchronisers[k];
        if (g->engaged < 0) continue;
        int a = m->nodes[m->idlers[g->engaged].node].shaft, b = m->nodes[g->node].shaft;
        int other = a == s ? b : b == s ? a : -1;
        if (other < 0) continue;
        if ((st = reach(m, seen, queue, tail, other, m->shafts[s].speed_ratio, "synchroniser",
                        g->name, g->loc, m->build->syncs[k].path, err)))
            return st;
    }
    return GD_OK;
}

static gd_status spread(gd_model *m, int *seen, int *queue, gd_error *err)
{
    gd_model_build *b = m->build;
    gd_status st;
    /* every connected group starts from its own root: the reference shaft first */
    for (int start = -1; start < m->nshafts; start++) {
        /* a shaft not geared to the reference keeps its own speed_ratio (default 1) */
        int root = start < 0 ? m->reference_shaft : start;
        if (seen[root]) continue;
        seen[root] = 1;
        int head = 0, tail = 0;
        queue[tail++] = root;
        while (head < tail) {
            int s = queue[head++];
            for (int k = 0; k < m->nmeshes; k++) {
                const gd_mesh *g = &m->meshes[k];
                int sa = m->nodes[g->driver].shaft, sb = m->nodes[g->driven].shaft;
                int other;
                double ratio;
                if (sa == s) {
                    other = sb;
                    ratio = -m->shafts[s].speed_ratio * g->base_radius[0] / g->base_radius[1];
                } else if (sb == s) {
                    other = sa;
                    ratio = -m->shafts[s].speed_ratio * g->base_radius[1] / g->base_radius[0];
                } else {
                    continue;
                }
                if ((st = reach(m, seen, queue, &tail, other, ratio, "mesh", g->name, g->loc,
                                b->meshes[k].path, err)))
                    return st;
            }
            if ((st = spread_planetary(m, s, seen, queue, &tail, err)) ||
                (st = spread_synchronisers(m, s, seen, queue, &tail, err)))
                return st;
        }
    }
    return GD_OK;
}

gd_status gd_build_propagate_speeds(gd_model *m, gd_error *err)
{
    int *seen = calloc((size_t)m->nshafts, sizeof *seen);
    int *queue = calloc((size_t)m->nshafts, sizeof *queue);
    gd_status st = seen && queue ? spread(m, seen, queue, err) : gd_build_oom(m, err);
    free(seen);
    free(queue);
    if (st) return st;
    static const char *const ROTATIONS[] = {"ccw", "cw"};
    for (int k = 0; k < m->nmeshes; k++) {
        gd_mesh *g = &m->meshes[k];
        const gd_bmesh *bm = &m->build->meshes[k];
        double ratio = m->shafts[m->nodes[g->driver].shaft].speed_ratio;
        g->driver_sense = ratio < 0 ? -1 : 1;
        int want = bm->driver_rotation;
        if (want && (want > 0 ? 1 : -1) != g->driver_sense) {
            char fp[200];
            gd_build_path(fp, sizeof fp, bm->path, "driver_rotation");
            return gd_build_fail(m, err, g->loc, fp, fp,
                                 "the sense follows from the reference shaft's `rotation` and the "
                                 "meshes; change `rotation:` at the top or remove this key",
                                 "driver turns %s here, but the gear train makes it turn %s",
                                 ROTATIONS[want > 0 ? 0 : 1], g->driver_sense > 0 ? "ccw" : "cw");
        }
    }
    return GD_OK;
}
