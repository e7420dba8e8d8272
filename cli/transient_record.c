/* The --record spec parser of `geardyn transient` (see transient_record.h). */
#include "transient_record.h"

#include <stdlib.h>
#include <string.h>

#include "cli.h"

static int push(gd_cli_records *recs, gd_tr_record_kind kind, int index, int index2,
                const char *unit, const char *a, const char *b, const char *c)
{
    if (recs->n == recs->cap) {
        int cap = recs->cap ? 2 * recs->cap : 16;
        gd_cli_record *r = realloc(recs->r, (size_t)cap * sizeof *r);
        if (!r) {
            fprintf(stderr, "geardyn: error: out of memory\n");
            return GD_EXIT_FAIL;
        }
        recs->r = r;
        recs->cap = cap;
    }
    gd_cli_record *r = &recs->r[recs->n++];
    r->rec.kind = kind;
    r->rec.index = index;
    r->rec.index2 = index2;
    r->unit = unit;
    /* name = a b c, truncated to the buffer */
    size_t off = 0;
    const char *parts[3] = {a, b, c};
    for (int k = 0; k < 3; k++)
        for (const char *p = parts[k]; *p && off + 1 < sizeof r->name; p++)
            r->name[off++] = *p;
    r->name[off] = 0;
    return 0;
}

static int dof_of_name(const char *s)
{
    for (int d = 0; d < GD_NODE_DOFS; d++)
        if (!strcmp(s, gd_dof_names[d])) return d;
    return -1;
}

/* The node names, for messages (truncated). */
static void node_list(const gd_model *m, char *buf, size_t size)
{
    size_t len = 0;
    buf[0] = 0;
    for (int i = 0; i < m->nnodes && len + 4 < size; i++) {
        int w = snprintf(buf + len, size - len, "%s%s", i ? ", " : "", m->nodes[i].name);
        if (w < 0 || (size_t)w >= size - len) {
            snprintf(buf + (size - 5 > len ? len : size - 5), 5, " ...");
            return;
        }
        len += (size_t)w;
    }
}

static int active_dofs_of(const gd_system *sys, int node, char *buf, size_t size)
{
    size_t len = 0;
    int count = 0;
    buf[0] = 0;
    for (int d = 0; d < GD_NODE_DOFS; d++)
        if (gd_system_dof(sys, node, (gd_dof)d) >= 0 && len + 8 < size) {
            int w = snprintf(buf + len, size - len, "%s%s", count ? ", " : "", gd_dof_names[d]);
            if (w > 0) len += (size_t)w;
            count++;
        }
    return count;
}

static int find_node(const gd_model *m, const char *cmd, const char *item, const char *name,
                     int *node)
{
    *node = gd_model_find_node(m, name);
    if (*node >= 0) return 0;
    char list[600];
    node_list(m, list, sizeof list);
    return gd_cli_usage_error(cmd, "--record '%s': unknown node '%s' (nodes: %s)", item, name,
                              list);
}

static int node_dof(const gd_system *sys, const char *cmd, const char *item, const char *text,
                    int *dof_out, int *node_out, int *type_out)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", text);
    char *dot = strrchr(buf, '.');
    if (!dot || dot == buf || !dot[1])
        return gd_cli_usage_error(cmd,
                                  "--record '%s': expected NODE.DOF[:disp|vel|angle|speed], "
                                  "ratio:A/B, mesh:NAME[:what] or sfd:BEARING[:what]",
                                  item);
    *dot = 0;
    int node, rc = find_node(sys->model, cmd, item, buf, &node);
    if (rc) return rc;
    int d = dof_of_name(dot + 1);
    if (d < 0)
        return gd_cli_usage_error(
            cmd, "--record '%s': unknown DOF '%s' (use x, y, z, rx, ry or rz)", item, dot + 1);
    int idx = gd_system_dof(sys, node, (gd_dof)d);
    if (idx < 0) {
        char act[64];
        if (active_dofs_of(sys, node, act, sizeof act))
            return gd_cli_usage_error(cmd,
                                      "--record '%s': %s.%s is not an active DOF (node '%s' has "
                                      "%s)",
                                      item, buf, dot + 1, buf, act);
        return gd_cli_usage_error(cmd, "--record '%s': node '%s' has no active DOF", item, buf);
    }
    *dof_out = idx;
    if (node_out) *node_out = node;
    if (type_out) *type_out = d;
    return 0;
}

static int parse_ratio(const gd_system *sys, const char *cmd, const char *item,
                       gd_cli_records *recs)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", item + 6);
    char *slash = strchr(buf, '/');
    if (!slash || slash == buf || !slash[1])
        return gd_cli_usage_error(cmd, "--record '%s': expected ratio:NODE_A/NODE_B", item);
    *slash = 0;
    int dofs[2];
    const char *names[2] = {buf, slash + 1};
    for (int k = 0; k < 2; k++) {
        int node, rc = find_node(sys->model, cmd, item, names[k], &node);
        if (rc) return rc;
        dofs[k] = gd_system_dof(sys, node, GD_RZ);
        if (dofs[k] < 0)
            return gd_cli_usage_error(cmd, "--record '%s': node '%s' has no active rz DOF", item,
                                      names[k]);
    }
    char nm[200];
    snprintf(nm, sizeof nm, "%.90s/%.90s", names[0], names[1]);
    return push(recs, GD_REC_SPEED_RATIO, dofs[0], dofs[1], "-", "ratio:", nm, "");
}

static const char *const MESH_WHAT[] = {"force", "state", "deflection", "stiffness"};
static const gd_tr_record_kind MESH_KIND[] = {GD_REC_MESH_FORCE, GD_REC_MESH_STATE,
                                              GD_REC_MESH_DEFLECTION, GD_REC_MESH_STIFFNESS};
static const char *const MESH_UNIT[] = {"N", "-", "m", "N/m"};
static const char *const SFD_WHAT[] = {"fx", "fy", "ecc"};
static const gd_tr_record_kind SFD_KIND[] = {GD_REC_SFD_FX, GD_REC_SFD_FY, GD_REC_SFD_ECCENTRICITY};
static const char *const SFD_UNIT[] = {"N", "N", "-"};

static int push_mesh(const gd_model *m, int i, int w, gd_cli_records *recs)
{
    char tail[32];
    snprintf(tail, sizeof tail, ":%s", MESH_WHAT[w]);
    return push(recs, MESH_KIND[w], i, 0, MESH_UNIT[w], "mesh:", gd_model_mesh_name(m, i), tail);
}

static int parse_mesh(const gd_system *sys, const char *cmd, const char *item, gd_cli_records *recs)
{
    const gd_model *m = sys->model;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", item + 5);
    char *colon = strchr(buf, ':');
    int w = 0;
    if (colon) {
        *colon = 0;
        w = -1;
        for (int k = 0; k < 4; k++)
            if (!strcmp(colon + 1, MESH_WHAT[k])) w = k;
        if (w < 0)
            return gd_cli_usage_error(cmd,
                                      "--record '%s': unknown mesh quantity '%s' (use force, "
                                      "state, deflection or stiffness)",
                                      item, colon + 1);
    }
    if (!strcmp(buf, "*")) {
        if (!m->nmeshes)
            return gd_cli_usage_error(cmd, "--record '%s': the model has no mesh", item);
        for (int i = 0; i < m->nmeshes; i++) {
            int rc = push_mesh(m, i, w, recs);
            if (rc) return rc;
        }
        return 0;
    }
    int i = gd_model_find_mesh(m, buf);
    for (int k = m->nmeshes; i < 0 && k < gd_model_mesh_count(m); k++)
        if (!strcmp(gd_model_mesh_name(m, k), buf)) i = k; /* a planetary set's mesh */
    if (i < 0) {
        char list[600] = "";
        size_t len = 0;
        for (int k = 0; k < m->nmeshes && len + 70 < sizeof list; k++) {
            int wr =
                snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "", m->meshes[k].name);
            if (wr > 0) len += (size_t)wr;
        }
        return gd_cli_usage_error(cmd, "--record '%s': unknown mesh '%s' (meshes: %s)", item, buf,
                                  m->nmeshes ? list : "none");
    }
    return push_mesh(m, i, w, recs);
}

static int push_sfd(const gd_model *m, const gd_transient_model *tm, int s, int w,
                    gd_cli_records *recs)
{
    char tail[32];
    snprintf(tail, sizeof tail, ":%s", SFD_WHAT[w]);
    return push(recs, SFD_KIND[w], s, 0, SFD_UNIT[w], "sfd:", m->bearings[tm->sfd_bearing[s]].name,
                tail);
}

static int parse_sfd(const gd_system *sys, const gd_transient_model *tm, const char *cmd,
                     const char *item, gd_cli_records *recs)
{
    const gd_model *m = sys->model;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", item + 4);
    char *colon = strchr(buf, ':');
    int w = 2;
    if (colon) {
        *colon = 0;
        w = -1;
        for (int k = 0; k < 3; k++)
            if (!strcmp(colon + 1, SFD_WHAT[k])) w = k;
        if (w < 0)
            return gd_cli_usage_error(cmd,
                                      "--record '%s': unknown damper quantity '%s' (use fx, fy "
                                      "or ecc)",
                                      item, colon + 1);
    }
    if (!tm->spec.nsfds)
        return gd_cli_usage_error(cmd,
                                  "--record '%s': the model has no squeeze film damper (a bearing "
                                  "with sfd:)",
                                  item);
    if (!strcmp(buf, "*")) {
        for (int s = 0; s < tm->spec.nsfds; s++) {
            int rc = push_sfd(m, tm, s, w, recs);
            if (rc) return rc;
        }
        return 0;
    }
    for (int s = 0; s < tm->spec.nsfds; s++)
        if (!strcmp(m->bearings[tm->sfd_bearing[s]].name, buf)) return push_sfd(m, tm, s, w, recs);
    char list[400] = "";
    size_t len = 0;
    for (int s = 0; s < tm->spec.nsfds && len + 70 < sizeof list; s++) {
        int wr = snprintf(list + len, sizeof list - len, "%s%s", s ? ", " : "",
                          m->bearings[tm->sfd_bearing[s]].name);
        if (wr > 0) len += (size_t)wr;
    }
    return gd_cli_usage_error(cmd, "--record '%s': no squeeze film damper '%s' (dampers: %s)", item,
                              buf, list);
}

/* law:NAME[:RECORD]: a record of a law of the model's `laws:` list (its first record by
 * default; law:* every law) */
static int push_law(const gd_law *L, int i, int w, gd_cli_records *recs)
{
    char tail[48];
    snprintf(tail, sizeof tail, ":%s", L->type->records[w].name);
    return push(recs, GD_REC_LAW, i, w, L->type->records[w].unit, "law:", L->name, tail);
}

static int parse_law(const gd_transient_model *tm, const char *cmd, const char *item,
                     gd_cli_records *recs)
{
    const gd_transient_spec *sp = &tm->spec;
    char buf[256];
    snprintf(buf, sizeof buf, "%s", item + 4);
    char *colon = strchr(buf, ':');
    const char *what = colon ? colon + 1 : NULL;
    if (colon) *colon = 0;
    if (!sp->nlaws)
        return gd_cli_usage_error(cmd, "--record '%s': the model has no law (a `laws:` list)",
                                  item);
    int all = !strcmp(buf, "*"), found = 0;
    for (int i = 0; i < sp->nlaws; i++) {
        const gd_law *L = &sp->laws[i];
        if (!all && strcmp(L->name, buf)) continue;
        found = 1;
        if (!L->type->nrecords)
            return gd_cli_usage_error(cmd, "--record '%s': law '%s' (%s) has no records", item,
                                      L->name, L->type->name);
        int w = what ? gd_law_record_index(L->type, what) : 0;
        if (w < 0) {
            char list[200] = "";
            size_t len = 0;
            for (int k = 0; k < L->type->nrecords && len + 40 < sizeof list; k++) {
                int wr = snprintf(list + len, sizeof list - len, "%s%s", k ? ", " : "",
                                  L->type->records[k].name);
                if (wr > 0) len += (size_t)wr;
            }
            return gd_cli_usage_error(cmd,
                                      "--record '%s': law '%s' (%s) has no record '%s' (use %s)",
                                      item, L->name, L->type->name, what, list);
        }
        int rc = push_law(L, i, w, recs);
        if (rc) return rc;
    }
    if (found) return 0;
    char list[400] = "";
    size_t len = 0;
    for (int i = 0; i < sp->nlaws && len + 70 < sizeof list; i++) {
        int wr = snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", sp->laws[i].name);
        if (wr > 0) len += (size_t)wr;
    }
    return gd_cli_usage_error(cmd, "--record '%s': no law '%s' (laws: %s)", item, buf, list);
}

static const char *const DOF_WHAT[] = {"disp", "vel", "angle", "speed"};
static const gd_tr_record_kind DOF_KIND[] = {GD_REC_DISP, GD_REC_VEL, GD_REC_ANGLE, GD_REC_SPEED};

static int parse_dof(const gd_system *sys, const char *cmd, const char *item, gd_cli_records *recs)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", !strncmp(item, "node:", 5) ? item + 5 : item);
    char *colon = strrchr(buf, ':');
    int w = 0;
    if (colon) {
        *colon = 0;
        w = -1;
        for (int k = 0; k < 4; k++)
            if (!strcmp(colon + 1, DOF_WHAT[k])) w = k;
        if (w < 0)
            return gd_cli_usage_error(cmd,
                                      "--record '%s': unknown DOF quantity '%s' (use disp, vel, "
                                      "angle or speed)",
                                      item, colon + 1);
    }
    int dof = -1, node = -1, type = 0, rc = node_dof(sys, cmd, item, buf, &dof, &node, &type);
    if (rc) return rc;
    int rot = type >= GD_RX;
    static const char *const lin_unit[] = {"m", "m/s", "m", "m/s"};
    static const char *const rot_unit[] = {"rad", "rad/s", "rad", "rad/s"};
    char tail[16];
    snprintf(tail, sizeof tail, ":%s", DOF_WHAT[w]);
    return push(recs, DOF_KIND[w], dof, 0, rot ? rot_unit[w] : lin_unit[w], buf, "", tail);
}

static int parse_item(const gd_system *sys, const gd_transient_model *tm, const char *cmd,
                      const char *item, gd_cli_records *recs)
{
    if (!strncmp(item, "ratio:", 6)) return parse_ratio(sys, cmd, item, recs);
    if (!strncmp(item, "mesh:", 5)) return parse_mesh(sys, cmd, item, recs);
    if (!strncmp(item, "sfd:", 4)) return parse_sfd(sys, tm, cmd, item, recs);
    if (!strncmp(item, "law:", 4)) return parse_law(tm, cmd, item, recs);
    return parse_dof(sys, cmd, item, recs);
}

int gd_cli_parse_records(const char *cmd, const gd_system *sys, const gd_transient_model *tm,
                         const char *text, gd_cli_records *recs)
{
    const char *p = text;
    for (;;) {
        const char *e = strchr(p, ',');
        size_t len = e ? (size_t)(e - p) : strlen(p);
        while (len && (*p == ' ' || *p == '\t')) {
            p++;
            len--;
        }
        while (len && (p[len - 1] == ' ' || p[len - 1] == '\t'))
            len--;
        if (!len) return gd_cli_usage_error(cmd, "--record '%s': empty item", text);
        if (len >= 255) return gd_cli_usage_error(cmd, "--record: item too long");
        char item[256];
        memcpy(item, p, len);
        item[len] = 0;
        int rc = parse_item(sys, tm, cmd, item, recs);
        if (rc) return rc;
        if (!e) return 0;
        p = e + 1;
    }
}

int gd_cli_default_records(const gd_system *sys, const gd_transient_model *tm, gd_cli_records *recs)
{
    const gd_model *m = sys->model;
    int rc = 0;
    for (int i = 0; i < tm->spec.nmeshes && !rc; i++) {
        rc = push_mesh(m, tm->meshes[i].mesh, 0, recs);
        if (!rc && tm->meshes[i].backlash) rc = push_mesh(m, tm->meshes[i].mesh, 1, recs);
    }
    for (int s = 0; s < tm->spec.nsfds && !rc; s++) {
        rc = push_sfd(m, tm, s, 0, recs);
        if (!rc) rc = push_sfd(m, tm, s, 1, recs);
    }
    for (int i = 0; i < tm->spec.nlaws && !rc; i++)
        if (tm->spec.laws[i].type->nrecords) rc = push_law(&tm->spec.laws[i], i, 0, recs);
    if (rc || recs->n) return rc;
    for (int i = 0; i < sys->ndof && !rc; i++)
        if (sys->dof_type[i] == GD_RZ) {
            char label[GD_NODE_NAME_MAX + 8];
            gd_system_dof_label(sys, i, label, (int)sizeof label);
            rc = push(recs, GD_REC_SPEED, i, 0, "rad/s", label, "", ":speed");
        }
    if (rc || recs->n) return rc;
    for (int i = 0; i < sys->ndof && i < 64 && !rc; i++) {
        char label[GD_NODE_NAME_MAX + 8];
        gd_system_dof_label(sys, i, label, (int)sizeof label);
        rc = push(recs, GD_REC_DISP, i, 0, sys->dof_type[i] >= GD_RX ? "rad" : "m", label, "",
                  ":disp");
    }
    return rc;
}

void gd_cli_records_free(gd_cli_records *recs)
{
    free(recs->r);
    recs->r = NULL;
    recs->n = recs->cap = 0;
}
