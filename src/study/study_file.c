/* Reading a study file (docs/studies.md): model, analysis, parameters, design, outputs.
 * Everything is checked before any case runs, with errors located in the study file:
 * a parameter path that reaches nothing in the model, an empty range or list, an output
 * the analysis does not have. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "study/study_impl.h"

static const char *const TOP_KEYS[] = {"title",   "model", "analysis", "parameters", "design",
                                       "samples", "seed",  "outputs",  NULL};
static const char *const PARAM_KEYS[] = {"name", "path", "values", "range", "scale", "unit", NULL};
static const char *const RANGE_KEYS[] = {"from", "to", "count", "spacing", NULL};
static const char *const DESIGNS[] = {"factorial", "zip", "random", "latin-hypercube", NULL};
static const char *const SPACINGS[] = {"linear", "log", NULL};
/* gd_operating_kind's order, the words of `--operating-point` */
static const char *const OPERATING_POINTS[] = {"static", "zero", NULL};

static gd_status oom(gd_yreader *r)
{
    return gd_error_set(r->err, GD_ENOMEM, r->file, 0, 0, "", "", "out of memory");
}

static char *read_text(const char *path, gd_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) {
        gd_error_set(err, GD_EIO, path, 0, 0, "", "check the path and permissions",
                     "cannot open study file: %s", strerror(errno));
        return NULL;
    }
    size_t cap = 4096, n = 0;
    char *buf = malloc(cap);
    while (buf) {
        n += fread(buf + n, 1, cap - n - 1, f);
        if (n < cap - 1) break;
        char *more = realloc(buf, cap *= 2);
        if (!more) free(buf);
        buf = more;
    }
    fclose(f);
    if (!buf)
        gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    else
        buf[n] = '\0';
    return buf;
}

/* A plain number (no unit) at n. */
static gd_status plain_number(gd_yreader *r, const gd_ynode *n, const char *field, double *out)
{
    if (gd_yexpect(r, n, GD_Y_SCALAR, field)) return GD_EINPUT;
    char *end;
    errno = 0;
    *out = strtod(n->text, &end);
    if (end == n->text || *end || errno || !isfinite(*out))
        return gd_yfail(r, n, field, "give a plain number; put the unit in the parameter's `unit:`",
                        "'%s' is not a number", n->text);
    return GD_OK;
}

static gd_status read_range(gd_yreader *r, const gd_ynode *map, const char *path, gd_study_param *p,
                            int sampled)
{
    char f[256];
    if (gd_yexpect(r, map, GD_Y_MAP, path) || gd_ycheck_keys(r, map, path, RANGE_KEYS))
        return GD_EINPUT;
    const gd_ynode *from = gd_ymap_get(map, "from"), *to = gd_ymap_get(map, "to");
    if (!from || !to)
        return gd_yfail(r, map, path, "write `range: {from: A, to: B, count: N}`",
                        "a range needs `from` and `to`");
    if (plain_number(r, from, gd_ypath_key(f, sizeof f, path, "from"), &p->from) ||
        plain_number(r, to, gd_ypath_key(f, sizeof f, path, "to"), &p->to))
        return GD_EINPUT;
    int spacing = 0;
    if (gd_yread_str(r, map, "spacing", path, SPACINGS, 0, NULL, &spacing, NULL)) return GD_EINPUT;
    p->log = spacing == 1;
    if (p->log && (p->from <= 0 || p->to <= 0))
        return gd_yfail(r, map, path, "log spacing needs from > 0 and to > 0",
                        "log range from %g to %g", p->from, p->to);
    long count = 0;
    int has_count = 0;
    if (gd_yread_int(r, map, "count", path, 0, 100000000L, 0, &count, &has_count)) return GD_EINPUT;
    if (sampled) {
        if (has_count)
            return gd_yfail(r, gd_ymap_get(map, "count"), gd_ypath_key(f, sizeof f, path, "count"),
                            "a random or Latin-hypercube design draws `samples:` values; drop "
                            "`count`",
                            "count given in a sampled design");
        if (!(p->to > p->from))
            return gd_yfail(r, map, path, "give from < to", "empty range: from %g, to %g", p->from,
                            p->to);
        return GD_OK;
    }
    if (!has_count)
        return gd_yfail(r, map, path, "add `count: N` (the number of values, from and to included)",
                        "a range needs a count in a %s design", "factorial or zip");
    if (count < 1)
        return gd_yfail(r, gd_ymap_get(map, "count"), gd_ypath_key(f, sizeof f, path, "count"),
                        "give count >= 1", "empty range: count %ld", count);
    if (count > 1 && p->from == p->to)
        return gd_yfail(r, map, path, "give different from and to, or count: 1",
                        "empty range: from = to = %g with %ld values", p->from, count);
    p->nvalues = (size_t)count;
    return GD_OK;
}

static gd_status read_values(gd_yreader *r, const gd_ynode *list, const char *path,
                             gd_study_param *p)
{
    if (gd_yexpect(r, list, GD_Y_SEQ, path)) return GD_EINPUT;
    if (list->n == 0)
        return gd_yfail(r, list, path, "list at least one value", "empty list of values");
    p->nvalues = list->n;
    p->values = calloc(list->n, sizeof *p->values);
    if (!p->values) return oom(r);
    p->numeric = 1;
    for (size_t i = 0; i < list->n; i++) {
        char f[256];
        const gd_ynode *v = list->items[i];
        if (gd_yexpect(r, v, GD_Y_SCALAR, gd_ypath_index(f, sizeof f, path, i))) return GD_EINPUT;
        char *end;
        double x = strtod(v->text, &end);
        if (end == v->text || *end || !isfinite(x)) p->numeric = 0;
        p->values[i] = x;
    }
    if (p->numeric) return GD_OK;
    p->texts = calloc(list->n, sizeof *p->texts);
    if (!p->texts) return oom(r);
    for (size_t i = 0; i < list->n; i++) {
        p->values[i] = NAN;
        if (!(p->texts[i] = strdup(list->items[i]->text))) return oom(r);
    }
    return GD_OK;
}

static gd_status read_param(gd_yreader *r, gd_study *s, const gd_ynode *map, const char *path,
                            gd_study_param *p)
{
    char f[256];
    if (gd_yexpect(r, map, GD_Y_MAP, path) || gd_ycheck_keys(r, map, path, PARAM_KEYS))
        return GD_EINPUT;
    const char *str;
    if (gd_yread_str(r, map, "path", path, NULL, GD_YREQ, &str, NULL, NULL)) return GD_EINPUT;
    if (!(p->path = strdup(str))) return oom(r);
    str = p->path;
    if (gd_yread_str(r, map, "name", path, NULL, 0, &str, NULL, NULL)) return GD_EINPUT;
    if (!(p->name = strdup(str))) return oom(r);
    str = "";
    if (gd_yread_str(r, map, "unit", path, NULL, 0, &str, NULL, NULL)) return GD_EINPUT;
    if (!(p->unit = strdup(str))) return oom(r);
    p->scale = 1;
    const gd_ynode *scale = gd_ymap_get(map, "scale");
    if (scale && plain_number(r, scale, gd_ypath_key(f, sizeof f, path, "scale"), &p->scale))
        return GD_EINPUT;

    /* the path must reach something in the model (a missing last key is checked by a
     * trial load in gd_study_load) */
    int adds;
    gd_error perr;
    if (gd_model_source_check_path(s->src, p->path, &adds, &perr)) {
        char hint[320];
        snprintf(hint, sizeof hint, "%s", perr.hint);
        return gd_yfail(r, gd_ymap_get(map, "path"), gd_ypath_key(f, sizeof f, path, "path"), hint,
                        "'%s' reaches nothing in %s: %s", p->path, gd_model_source_file(s->src),
                        perr.message);
    }

    const gd_ynode *values = gd_ymap_get(map, "values"), *range = gd_ymap_get(map, "range");
    int sampled = s->design == GD_DESIGN_RANDOM || s->design == GD_DESIGN_LHS;
    if (!!values == !!range)
        return gd_yfail(r, map, path,
                        "give either `values: [...]` or `range: {from: A, to: B, count: N}`",
                        values ? "both values and range given" : "no values or range");
    if (values && sampled)
        return gd_yfail(r, values, gd_ypath_key(f, sizeof f, path, "values"),
                        "a random or Latin-hypercube design samples a `range: {from, to}`",
                        "a list of values in a sampled design");
    if (values) return read_values(r, values, gd_ypath_key(f, sizeof f, path, "values"), p);
    p->numeric = 1;
    return read_range(r, range, gd_ypath_key(f, sizeof f, path, "range"), p, sampled);
}

/* "name", "name[k]" or "name[a:b]" against the analysis's outputs. */
static gd_status read_output(gd_yreader *r, gd_study *s, const gd_ynode *n, const char *path)
{
    if (gd_yexpect(r, n, GD_Y_SCALAR, path)) return GD_EINPUT;
    const gd_study_runner *a = s->analysis;
    char name[128];
    long lo = 0, hi = 0;
    const char *br = strchr(n->text, '[');
    size_t len = br ? (size_t)(br - n->text) : strlen(n->text);
    snprintf(name, sizeof name, "%.*s", (int)(len < sizeof name ? len : sizeof name - 1), n->text);
    int def = -1;
    for (int i = 0; i < a->noutputs; i++)
        if (!strcmp(a->outputs[i].name, name)) def = i;
    if (def < 0) {
        char hint[320] = "";
        for (int i = 0; i < a->noutputs; i++) {
            size_t u = strlen(hint);
            snprintf(hint + u, sizeof hint - u, "%s%s%s",
                     i ? ", " : "outputs of this analysis: ", a->outputs[i].name,
                     a->outputs[i].indexed ? "[k]" : "");
        }
        return gd_yfail(r, n, path, hint, "unknown output '%s' of %s", name, a->name);
    }
    if (br) {
        char *end;
        lo = strtol(br + 1, &end, 10);
        hi = lo;
        if (*end == ':') hi = strtol(end + 1, &end, 10);
        if (end == br + 1 || strcmp(end, "]") || lo < 1 || hi < lo || hi - lo > 100000)
            return gd_yfail(r, n, path, "write name[k] or name[a:b] with 1 <= a <= b",
                            "bad index in '%s'", n->text);
        if (!a->outputs[def].indexed)
            return gd_yfail(r, n, path, "drop the [...]", "output '%s' takes no index", name);
    } else if (a->outputs[def].indexed) {
        return gd_yfail(r, n, path, "write name[k] (k from 1) or name[a:b]",
                        "output '%s' needs an index", name);
    }
    size_t add = br ? (size_t)(hi - lo + 1) : 1;
    gd_study_request *req = realloc(s->req, (s->noutputs + add) * sizeof *req);
    if (!req) return oom(r);
    s->req = req;
    char **names = realloc(s->out_names, (s->noutputs + add) * sizeof *names);
    if (!names) return oom(r);
    s->out_names = names;
    for (size_t i = 0; i < add; i++) {
        char col[160];
        if (br)
            snprintf(col, sizeof col, "%s[%ld]", name, lo + (long)i);
        else
            snprintf(col, sizeof col, "%s", name);
        s->req[s->noutputs] = (gd_study_request){def, br ? (int)(lo + (long)i) : 0};
        if (!(s->out_names[s->noutputs] = strdup(col))) return oom(r);
        s->noutputs++;
    }
    return GD_OK;
}

static gd_status read_analysis(gd_yreader *r, gd_study *s, const gd_ynode *root)
{
    const gd_ynode *an = gd_ymap_get(root, "analysis");
    if (!an)
        return gd_yfail(r, root, "analysis", "add `analysis: {type: modal, ...}`",
                        "missing key 'analysis'");
    const char *type = NULL;
    const gd_ynode *map = an->kind == GD_Y_SCALAR ? NULL : an;
    if (map) {
        if (gd_yexpect(r, map, GD_Y_MAP, "analysis") ||
            gd_yread_str(r, map, "type", "analysis", NULL, GD_YREQ, &type, NULL, NULL))
            return GD_EINPUT;
    } else {
        type = an->text;
    }
    s->analysis = gd_study_find_analysis(type);
    if (!s->analysis) {
        char hint[320] = "analyses: ";
        for (int i = 0; gd_study_analysis_table[i]; i++) {
            size_t u = strlen(hint);
            snprintf(hint + u, sizeof hint - u, "%s%s", i ? ", " : "",
                     gd_study_analysis_table[i]->name);
        }
        return gd_yfail(r, map ? gd_ymap_get(map, "type") : an, map ? "analysis.type" : "analysis",
                        hint, "unknown analysis '%s'", type);
    }
    if (map) {
        const char *allowed[32] = {"type"};
        int n = 1;
        for (const char *const *k = s->analysis->keys; k && *k && n < 30; k++)
            allowed[n++] = *k;
        const gd_ynode *op = gd_ymap_get(map, "operating_point");
        if (op && !s->analysis->operating_speed)
            return gd_yfail(r, op, "analysis.operating_point",
                            "drop it: only modal, campbell, frf and unbalance linearise the "
                            "model's laws",
                            "analysis '%s' linearises nothing", s->analysis->name);
        if (s->analysis->operating_speed) allowed[n++] = "operating_point";
        if (gd_ycheck_keys(r, map, "analysis", allowed)) return GD_EINPUT;
        /* the state the laws are linearised about, as `--operating-point` of the CLI */
        int kind = GD_OPERATING_STATIC;
        if (gd_yread_str(r, map, "operating_point", "analysis", OPERATING_POINTS, 0, NULL, &kind,
                         NULL))
            return GD_EINPUT;
        s->op_kind = kind;
    }
    return s->analysis->options(r, map, &s->opts);
}

/* The model, relative to the study file's folder. */
static gd_status load_model(gd_yreader *r, gd_study *s, const gd_ynode *root)
{
    const char *model;
    if (gd_yread_str(r, root, "model", "", NULL, GD_YREQ, &model, NULL, NULL)) return GD_EINPUT;
    const char *slash = strrchr(s->file, '/');
    char path[2048];
    if (model[0] == '/' || !slash)
        snprintf(path, sizeof path, "%s", model);
    else
        snprintf(path, sizeof path, "%.*s/%s", (int)(slash - s->file), s->file, model);
    gd_error merr;
    gd_status st = gd_model_source_load(path, &s->src, &merr);
    if (st == GD_EIO)
        return gd_yfail(r, gd_ymap_get(root, "model"), "model",
                        "the model path is relative to the study file's folder",
                        "cannot read model '%s': %s", path, merr.message);
    if (st) *r->err = merr;
    return st;
}

/* A parameter whose path adds a key the model file lacks: a trial load with its first
 * value shows whether the model accepts that key at all (a typo would fail every case). */
static gd_status trial_load(gd_yreader *r, gd_study *s, const gd_ynode *plist, int p)
{
    char assignment[1024];
    gd_study_assignment(s, 0, p, assignment, sizeof assignment);
    const char *set[1] = {assignment};
    gd_load_options opt = {1, set};
    gd_error e;
    gd_status st;
    if (s->analysis->gear_pair) {
        gd_gear_pair_geometry g;
        gd_tvms_options t;
        st = gd_model_source_gear_pair(
            s->src, s->analysis->mesh_name ? s->analysis->mesh_name(s->opts) : NULL, &opt, &g, &t,
            NULL, 0, &e);
    } else {
        gd_model *m = NULL;
        st = gd_model_source_model(s->src, &opt, &m, &e);
        gd_model_free(m);
    }
    if (st != GD_EINPUT || e.line != 0 || strncmp(e.file, "--set", 5)) return GD_OK;
    char f[64], g[96], hint[320];
    snprintf(hint, sizeof hint, "%s", e.hint[0] ? e.hint : "check the path against the model file");
    const gd_ynode *pn = gd_ymap_get(plist->items[p], "path");
    return gd_yfail(
        r, pn,
        gd_ypath_key(g, sizeof g, gd_ypath_index(f, sizeof f, "parameters", (size_t)p), "path"),
        hint, "the model does not accept '%s': %s: %s", s->params[p].path, e.field, e.message);
}

/* The analysis's options against the model as the file gives it (names of meshes,
 * nodes): a wrong name would fail every case. */
static gd_status check_analysis(gd_yreader *r, gd_study *s, const gd_ynode *root)
{
    if (!s->analysis->check) return GD_OK;
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_error e;
    gd_status st = gd_model_source_model(s->src, NULL, &m, &e);
    if (!st) st = gd_system_build(m, &sys, &e);
    if (st) { /* the model itself is wrong: its own located error */
        *r->err = e;
    } else if ((st = s->analysis->check(sys, s->opts, &e))) {
        char hint[320];
        snprintf(hint, sizeof hint, "%s", e.hint);
        st = gd_yfail(r, gd_ymap_get(root, "analysis"), e.field[0] ? e.field : "analysis", hint,
                      "%s", e.message);
    }
    gd_system_free(sys);
    gd_model_free(m);
    return st;
}

static gd_status parse(gd_yreader *r, gd_study *s, const gd_ydoc *doc)
{
    const gd_ynode *root = doc->root;
    if (!root || root->kind != GD_Y_MAP)
        return gd_yfail(r, root, "", "a study file is a map: model, analysis, parameters, outputs",
                        "not a map of keys");
    if (gd_ycheck_keys(r, root, "", TOP_KEYS) || load_model(r, s, root) ||
        read_analysis(r, s, root))
        return GD_EINPUT;
    int design = 0;
    if (gd_yread_str(r, root, "design", "", DESIGNS, 0, NULL, &design, NULL)) return GD_EINPUT;
    s->design = (gd_study_design)design;
    long samples = 0, seed = 1;
    int has_samples = 0;
    if (gd_yread_int(r, root, "samples", "", 1, 100000000L, 0, &samples, &has_samples) ||
        gd_yread_int(r, root, "seed", "", 0, 0x7fffffffL, 0, &seed, NULL))
        return GD_EINPUT;
    int sampled = s->design == GD_DESIGN_RANDOM || s->design == GD_DESIGN_LHS;
    if (sampled && !has_samples)
        return gd_yfail(r, gd_ymap_get(root, "design"), "samples", "add `samples: N` (and `seed:`)",
                        "a %s design needs the number of samples", DESIGNS[design]);
    if (!sampled && has_samples)
        return gd_yfail(r, gd_ymap_get(root, "samples"), "samples",
                        "use `design: random` or `design: latin-hypercube`, or drop `samples`",
                        "samples given in a %s design", DESIGNS[design]);
    s->ncases = (size_t)samples;

    const gd_ynode *plist = gd_ymap_get(root, "parameters");
    if (!plist)
        return gd_yfail(r, root, "parameters", "add `parameters: [{path: ..., values: [...]}]`",
                        "missing key 'parameters'");
    if (gd_yexpect(r, plist, GD_Y_SEQ, "parameters")) return GD_EINPUT;
    if (plist->n == 0)
        return gd_yfail(r, plist, "parameters", "list at least one parameter", "no parameters");
    s->params = calloc(plist->n, sizeof *s->params);
    if (!s->params) return oom(r);
    for (size_t i = 0; i < plist->n; i++) {
        char path[64];
        s->nparams = (int)i + 1;
        if (read_param(r, s, plist->items[i], gd_ypath_index(path, sizeof path, "parameters", i),
                       &s->params[i]))
            return GD_EINPUT;
        for (size_t j = 0; j < i; j++)
            if (!strcmp(s->params[j].name, s->params[i].name))
                return gd_yfail(r, plist->items[i], path, "give each parameter its own `name:`",
                                "two parameters are named '%s'", s->params[i].name);
        const char *name = s->params[i].name;
        if (!strcmp(name, "case") || !strcmp(name, "status") || !strcmp(name, "message"))
            return gd_yfail(r, plist->items[i], path, "give the parameter another `name:`",
                            "'%s' is a column of the table itself", name);
    }
    if (s->design == GD_DESIGN_ZIP)
        for (int i = 1; i < s->nparams; i++)
            if (s->params[i].nvalues != s->params[0].nvalues) {
                char path[64];
                return gd_yfail(r, plist->items[i],
                                gd_ypath_index(path, sizeof path, "parameters", (size_t)i),
                                "a zip design takes value i of every parameter: give them all the "
                                "same number of values, or use `design: factorial`",
                                "%zu values where parameters[0] has %zu", s->params[i].nvalues,
                                s->params[0].nvalues);
            }

    const gd_ynode *outs = gd_ymap_get(root, "outputs");
    if (!outs)
        return gd_yfail(r, root, "outputs", "add `outputs: [...]` naming what to keep",
                        "missing key 'outputs'");
    if (gd_yexpect(r, outs, GD_Y_SEQ, "outputs")) return GD_EINPUT;
    if (outs->n == 0) return gd_yfail(r, outs, "outputs", "name at least one output", "no outputs");
    for (size_t i = 0; i < outs->n; i++) {
        char path[64];
        if (read_output(r, s, outs->items[i], gd_ypath_index(path, sizeof path, "outputs", i)))
            return GD_EINPUT;
    }
    for (int i = 0; i < s->noutputs; i++) {
        for (int j = 0; j < i; j++)
            if (!strcmp(s->out_names[i], s->out_names[j]))
                return gd_yfail(r, outs, "outputs", "list each output once",
                                "output '%s' listed twice", s->out_names[i]);
        for (int p = 0; p < s->nparams; p++)
            if (!strcmp(s->out_names[i], s->params[p].name))
                return gd_yfail(r, outs, "outputs", "rename the parameter (`name:`)",
                                "'%s' is both a parameter and an output", s->out_names[i]);
    }
    if (check_analysis(r, s, root)) return GD_EINPUT;
    gd_status st = gd_study_make_cases(s, (uint64_t)seed, r->err);
    for (int p = 0; !st && p < s->nparams; p++) {
        int adds = 0;
        gd_model_source_check_path(s->src, s->params[p].path, &adds, NULL);
        if (adds) st = trial_load(r, s, plist, p);
    }
    return st;
}

gd_status gd_study_load(const char *path, gd_study **out, gd_error *err)
{
    *out = NULL;
    gd_study *s = calloc(1, sizeof *s);
    if (!s) return gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
    gd_error local;
    if (!err) err = &local;
    gd_error_clear(err);
    gd_status st = GD_ENOMEM;
    gd_ydoc *doc = NULL;
    if (!(s->file = strdup(path)) || !(s->text = read_text(path, err))) {
        st = s->file ? err->status : GD_ENOMEM;
    } else if (!(st = gd_ydoc_load_string(s->text, path, &doc, err))) {
        gd_yreader r = {path, err};
        st = parse(&r, s, doc);
    }
    gd_ydoc_free(doc);
    if (st) {
        gd_study_free(s);
        return st;
    }
    *out = s;
    return GD_OK;
}

void gd_study_free(gd_study *s)
{
    if (!s) return;
    for (int i = 0; i < s->nparams; i++) {
        gd_study_param *p = &s->params[i];
        free(p->name);
        free(p->path);
        free(p->unit);
        free(p->values);
        for (size_t k = 0; p->texts && k < p->nvalues; k++)
            free(p->texts[k]);
        free(p->texts);
    }
    free(s->params);
    for (int i = 0; i < s->noutputs; i++)
        free(s->out_names[i]);
    free(s->out_names);
    free(s->req);
    free(s->samples);
    free(s->opts);
    gd_model_source_free(s->src);
    free(s->file);
    free(s->text);
    free(s);
}
