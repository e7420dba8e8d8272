/* The builder's shafts: sections, named stations, the element rule per section and
 * the speed ratio (gd_model_add_shaft), and stations added later (gd_model_add_node).
 * Their nodes and elements are made by gd_model_finish (shaft_discretise.c). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "model/build_impl.h"

/* ---- shafts and stations ---- */

void gd_section_spec_init(gd_section_spec *s)
{
    memset(s, 0, sizeof *s);
}

void gd_station_spec_init(gd_station_spec *s)
{
    memset(s, 0, sizeof *s);
}

void gd_shaft_spec_init(gd_shaft_spec *s)
{
    memset(s, 0, sizeof *s);
    s->speed_ratio = 1.0;
}

void gd_node_spec_init(gd_node_spec *s)
{
    memset(s, 0, sizeof *s);
}

static double shaft_length(const gd_shaft *sh)
{
    double total = 0;
    for (int i = 0; i < sh->nsections; i++)
        total += sh->sections[i].length;
    return total;
}

/* A station's checks: its name, and its position on a shaft with sections. */
static gd_status check_station(const gd_model *m, gd_error *err, const char *path, const char *name,
                               double at, gd_loc loc, int nsections, double total)
{
    gd_status st = gd_build_name(m, err, loc, path, name, NULL, NULL);
    if (st) return st;
    if (nsections && (!(at >= -1e-12) || at > total * (1 + 1e-12))) {
        char hint[120], q[220];
        snprintf(hint, sizeof hint, "positions run from 0 to the shaft length %g m", total);
        gd_build_path(q, sizeof q, path, "at");
        return gd_build_fail(m, err, loc, q, q, hint, "position %g m lies outside the shaft", at);
    }
    return GD_OK;
}

static gd_status add_station(gd_model *m, gd_bshaft *bs, const char *path, const char *name,
                             double at, gd_loc loc)
{
    gd_bstation *ns = realloc(bs->stations, (size_t)(bs->nstations + 1) * sizeof *ns);
    if (!ns) return GD_ENOMEM;
    bs->stations = ns;
    gd_bstation *t = &ns[bs->nstations];
    t->name = gd_build_strdup(name);
    t->path = gd_build_strdup(path);
    t->at = at;
    t->loc = loc;
    if (!t->name || !t->path) {
        free(t->name);
        free(t->path);
        return GD_ENOMEM;
    }
    bs->nstations++;
    return GD_OK;
}

gd_status gd_model_add_shaft(gd_model *m, const gd_shaft_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int idx = m->nshafts;
    char path[160], q[200], sp[220], fb[32];
    if (s->path)
        snprintf(path, sizeof path, "%s", s->path);
    else
        snprintf(path, sizeof path, "shafts[%d]", idx);
    gd_shaft sh;
    memset(&sh, 0, sizeof sh);
    snprintf(fb, sizeof fb, "shaft%d", idx + 1);
    if ((st = gd_build_name(m, err, s->loc, path, s->name, fb, sh.name))) return st;
    sh.loc = s->loc;
    sh.speed_ratio = s->has_speed_ratio ? s->speed_ratio : 1.0;
    sh.speed_ratio_given = s->has_speed_ratio != 0;
    sh.speed_ratio_loc = s->speed_ratio_loc;
    if (s->elements_per_section < 0 || s->elements_per_section > GD_MAX_SECTION_ELEMENTS)
        return gd_build_fail(m, err, s->loc,
                             gd_build_path(q, sizeof q, path, "elements_per_section"), q,
                             "give a whole number from 1 to 10000",
                             "%d elements per section is out of range", s->elements_per_section);
    if ((st = gd_build_positive(m, err, s->loc, path, "max_element_length", s->max_element_length,
                                1)))
        return st;
    if (s->elements_per_section > 0 && s->max_element_length > 0)
        return gd_build_fail(m, err, s->loc, NULL, path, "keep one of the two",
                             "both elements_per_section and max_element_length given");
    if (s->nsections <= 0 && s->nstations <= 0)
        return gd_build_fail(m, err, s->loc, NULL, path,
                             "give `sections:` for a flexible shaft, or `nodes:` for lumped bodies",
                             "shaft has neither sections nor nodes");
    int per_section = s->elements_per_section > 0 ? s->elements_per_section : 1;
    double max_len = s->max_element_length;
    double total = 0;
    for (int i = 0; i < s->nsections; i++) {
        const gd_section_spec *c = &s->sections[i];
        snprintf(sp, sizeof sp, "%s.sections[%d]", path, i);
        if ((st = gd_build_positive(m, err, c->loc, sp, "length", c->length, 0)) ||
            (st = gd_build_positive(m, err, c->loc, sp, "outer_diameter", c->outer_diameter, 0)) ||
            (st = gd_build_positive(m, err, c->loc, sp, "inner_diameter", c->inner_diameter, 1)))
            return st;
        if (c->inner_diameter >= c->outer_diameter) {
            char fp[240];
            gd_build_path(fp, sizeof fp, sp, "inner_diameter");
            return gd_build_fail(m, err, c->loc, fp, fp,
                                 "the bore must be smaller than the outer diameter",
                                 "inner diameter %g m is not less than outer diameter %g m",
                                 c->inner_diameter, c->outer_diameter);
        }
        if (!c->material && !s->material)
            return gd_build_fail(m, err, c->loc, NULL, sp,
                                 "give `material:` on the section or on the shaft",
                                 "section has no material");
        if (c->elements < 0 || c->elements > GD_MAX_SECTION_ELEMENTS) {
            char fp[240];
            gd_build_path(fp, sizeof fp, sp, "elements");
            return gd_build_fail(m, err, c->loc, fp, fp, "give a whole number from 1 to 10000",
                                 "%d elements is out of range", c->elements);
        }
        /* the count max_element_length asks for, checked as a double before it becomes
           an int (1 m at 1e-9 m would be 1e9 elements, 1e72 m overflows an int) */
        double want = max_len > 0 && !c->elements ? ceil(c->length / max_len - 1e-9) : 0;
        if (!(want <= GD_MAX_SECTION_ELEMENTS)) {
            char fp[200];
            gd_build_path(fp, sizeof fp, path, "max_element_length");
            return gd_build_fail(
                m, err, c->loc, NULL, sp,
                "use a longer max_element_length, give the section `elements:`, or split it "
                "into shorter sections",
                "a section of %g m with max_element_length %g m would have %.3g elements, more "
                "than the limit of %d per section",
                c->length, max_len, want, GD_MAX_SECTION_ELEMENTS);
        }
        total += c->length;
    }
    for (int i = 0; i < s->nstations; i++) {
        snprintf(sp, sizeof sp, "%s.nodes[%d]", path, i);
        if ((st = check_station(m, err, sp, s->stations[i].name, s->stations[i].at,
                                s->stations[i].loc, s->nsections, total)))
            return st;
    }

    /* commit */
    gd_bshaft bs;
    memset(&bs, 0, sizeof bs);
    bs.path = gd_build_strdup(path);
    bs.material = gd_build_strdup(s->material);
    if (s->nsections > 0) {
        sh.sections = calloc((size_t)s->nsections, sizeof *sh.sections);
        bs.section_material = calloc((size_t)s->nsections, sizeof *bs.section_material);
    }
    int bad = !bs.path || (s->material && !bs.material) ||
              (s->nsections > 0 && (!sh.sections || !bs.section_material));
    for (int i = 0; i < s->nsections && !bad; i++) {
        const gd_section_spec *c = &s->sections[i];
        gd_section *sec = &sh.sections[i];
        sec->length = c->length;
        sec->outer_diameter = c->outer_diameter;
        sec->inner_diameter = c->inner_diameter;
        sec->material = -1;
        sec->loc = c->loc;
        if (c->elements > 0) {
            sec->elements = c->elements;
        } else if (max_len > 0) {
            sec->max_element_length = max_len;
            sec->elements = (int)ceil(sec->length / max_len - 1e-9);
        } else {
            sec->elements = per_section;
        }
        sh.nsections++;
        if (c->material && !(bs.section_material[i] = gd_build_strdup(c->material))) bad = 1;
    }
    for (int i = 0; i < s->nstations && !bad; i++) {
        snprintf(sp, sizeof sp, "%s.nodes[%d]", path, i);
        if (add_station(m, &bs, sp, s->stations[i].name, s->stations[i].at, s->stations[i].loc))
            bad = 1;
    }
    if (bad || !gd_build_grow(&m->shafts, m->nshafts, sizeof *m->shafts) ||
        !gd_build_grow(&m->build->shafts, m->nshafts, sizeof *m->build->shafts)) {
        gd_build_free_shaft(&bs, s->nsections);
        free(sh.sections);
        return gd_build_oom(m, err);
    }
    m->shafts[idx] = sh;
    m->build->shafts[idx] = bs;
    m->nshafts++;
    if (index) *index = idx;
    return GD_OK;
}

gd_status gd_model_add_node(gd_model *m, const gd_node_spec *s, int *index, gd_error *err)
{
    gd_status st;
    if ((st = gd_build_open(m, err))) return st;
    int sh = s->shaft ? gd_model_find_shaft(m, s->shaft) : -1;
    if (sh < 0) {
        char q[220];
        gd_build_path(q, sizeof q, s->path ? s->path : "nodes", "shaft");
        return gd_build_fail(m, err, s->loc, NULL, q, "add the shaft first, then its nodes",
                             "unknown shaft '%s'", s->shaft ? s->shaft : "");
    }
    gd_bshaft *bs = &m->build->shafts[sh];
    char path[200];
    if (s->path)
        snprintf(path, sizeof path, "%s", s->path);
    else
        snprintf(path, sizeof path, "%s.nodes[%d]", bs->path, bs->nstations);
    const gd_shaft *shaft = &m->shafts[sh];
    if ((st = check_station(m, err, path, s->name, s->at, s->loc, shaft->nsections,
                            shaft_length(shaft))))
        return st;
    if (add_station(m, bs, path, s->name, s->at, s->loc)) return gd_build_oom(m, err);
    if (index) *index = bs->nstations - 1;
    return GD_OK;
}
