/* The plot document: sections, panels, traces, tables and CSV text, owned by gd_plot. */
#include <ctype.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

static void *grow(gd_plot *p, void *ptr, int *cap, int need, size_t size)
{
    if (need <= *cap) return ptr;
    int nc = *cap ? 2 * *cap : 4;
    while (nc < need)
        nc *= 2;
    void *q = realloc(ptr, (size_t)nc * size);
    if (!q) {
        p->nomem = 1;
        return NULL;
    }
    memset((char *)q + (size_t)*cap * size, 0, (size_t)(nc - *cap) * size);
    *cap = nc;
    return q;
}

char *pl_strdup(gd_plot *p, const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (!d) {
        p->nomem = 1;
        return NULL;
    }
    return memcpy(d, s, n);
}

gd_status gd_plot_new(const char *title, gd_plot **out, gd_error *err)
{
    gd_plot *p = calloc(1, sizeof *p);
    if (!p) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    snprintf(p->title, sizeof p->title, "%s", title ? title : "geardyn");
    *out = p;
    return GD_OK;
}

pl_section *pl_section_add(gd_plot *p, const char *title)
{
    pl_section *s = grow(p, p->sections, &p->cap, p->nsections + 1, sizeof *s);
    if (!s) return NULL;
    p->sections = s;
    s = &p->sections[p->nsections++];
    snprintf(s->title, sizeof s->title, "%s", title);
    return s;
}

void pl_note(gd_plot *p, pl_section *s, const char *fmt, ...)
{
    if (!s) return;
    char buf[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    free(s->note);
    s->note = pl_strdup(p, buf);
}

gd_status gd_plot_add_note(gd_plot *p, const char *title, const char *text, gd_error *err)
{
    pl_section *s = pl_section_add(p, title);
    if (s) s->note = pl_strdup(p, text);
    if (p->nomem) {
        p->nomem = 0;
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory building a plot");
    }
    return GD_OK;
}

pl_panel *pl_panel_add(gd_plot *p, pl_section *s, pl_kind kind, const char *title,
                       const char *xlabel, const char *ylabel)
{
    if (!s) return NULL;
    /* builders keep a panel's pointer while they add the next panels of the section:
     * room for PANELS_STABLE from the start, so those pointers are not moved by a
     * realloc (a builder that adds more refetches its pointers) */
    enum { PANELS_STABLE = 256 };
    pl_panel *pn =
        grow(p, s->panels, &s->cap, s->npanels + 1 > PANELS_STABLE ? s->npanels + 1 : PANELS_STABLE,
             sizeof *pn);
    if (!pn) return NULL;
    s->panels = pn;
    pn = &s->panels[s->npanels++];
    pn->kind = kind;
    snprintf(pn->title, sizeof pn->title, "%s", title);
    snprintf(pn->xlabel, sizeof pn->xlabel, "%s", xlabel ? xlabel : "");
    snprintf(pn->ylabel, sizeof pn->ylabel, "%s", ylabel ? ylabel : "");
    return pn;
}

static double *copy(gd_plot *p, const double *x, int n)
{
    double *d = calloc((size_t)(n > 0 ? n : 1), sizeof *d);
    if (!d) {
        p->nomem = 1;
        return NULL;
    }
    if (x) memcpy(d, x, (size_t)n * sizeof *d);
    return d;
}

pl_trace *pl_trace_add(gd_plot *p, pl_panel *pn, const char *name, int n, const double *x,
                       const double *y, pl_mode mode, const char *color)
{
    if (!pn) return NULL;
    pl_trace *t = grow(p, pn->traces, &pn->cap, pn->ntraces + 1, sizeof *t);
    if (!t) return NULL;
    pn->traces = t;
    t = &pn->traces[pn->ntraces++];
    snprintf(t->name, sizeof t->name, "%s", name);
    t->n = n;
    t->x = copy(p, x, n);
    t->y = copy(p, y, n);
    t->mode = mode;
    t->color = color;
    t->legend = 1;
    return t;
}

void pl_trace_text(gd_plot *p, pl_trace *t, int i, const char *fmt, ...)
{
    if (!t || i < 0 || i >= t->n) return;
    if (!t->text && !(t->text = calloc((size_t)t->n, sizeof *t->text))) {
        p->nomem = 1;
        return;
    }
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    free(t->text[i]);
    t->text[i] = pl_strdup(p, buf);
}

void pl_table_init(gd_plot *p, pl_panel *pn, int nrows, int ncols)
{
    if (!pn) return;
    pn->cells = calloc((size_t)(nrows + 1) * (size_t)ncols, sizeof *pn->cells);
    if (!pn->cells) {
        p->nomem = 1;
        return;
    }
    pn->nrows = nrows;
    pn->ncols = ncols;
}

void pl_cell(gd_plot *p, pl_panel *pn, int row, int col, const char *fmt, ...)
{
    if (!pn || !pn->cells || row < 0 || row > pn->nrows || col < 0 || col >= pn->ncols) return;
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    char **c = &pn->cells[(size_t)row * pn->ncols + col];
    free(*c);
    *c = pl_strdup(p, buf);
}

void pl_csv(gd_plot *p, pl_section *s, const char *fmt, ...)
{
    if (!s) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    if (s->csv_len + (size_t)n + 1 > s->csv_cap) {
        size_t nc = s->csv_cap ? s->csv_cap : 4096;
        while (nc < s->csv_len + (size_t)n + 1)
            nc *= 2;
        char *q = realloc(s->csv, nc);
        if (!q) {
            p->nomem = 1;
            return;
        }
        s->csv = q;
        s->csv_cap = nc;
    }
    va_start(ap, fmt);
    vsnprintf(s->csv + s->csv_len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    s->csv_len += (size_t)n;
}

static void free_panel(pl_panel *pn)
{
    for (int t = 0; t < pn->ntraces; t++) {
        pl_trace *tr = &pn->traces[t];
        free(tr->x);
        free(tr->y);
        free(tr->xr);
        free(tr->xi);
        free(tr->yr);
        free(tr->yi);
        if (tr->text)
            for (int i = 0; i < tr->n; i++)
                free(tr->text[i]);
        free(tr->text);
        free(tr->marker_color);
    }
    free(pn->traces);
    if (pn->cells)
        for (int i = 0; i < (pn->nrows + 1) * pn->ncols; i++)
            free(pn->cells[i]);
    free(pn->cells);
    for (int i = 0; i < pn->nframes; i++)
        free(pn->frames[i]);
    free(pn->frames);
}

static void free_section(pl_section *s)
{
    for (int k = 0; k < s->npanels; k++)
        free_panel(&s->panels[k]);
    free(s->panels);
    free(s->note);
    free(s->csv);
}

void gd_plot_free(gd_plot *p)
{
    if (!p) return;
    for (int i = 0; i < p->nsections; i++)
        free_section(&p->sections[i]);
    free(p->sections);
    free(p);
}

gd_status pl_done(gd_plot *p, gd_plot **out, gd_error *err)
{
    if (p->nomem) {
        gd_plot_free(p);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory building a plot");
    }
    *out = p;
    return GD_OK;
}

gd_status gd_plot_append(gd_plot *dst, gd_plot *src, gd_error *err)
{
    if (!src) return GD_OK;
    pl_section *s = grow(dst, dst->sections, &dst->cap, dst->nsections + src->nsections, sizeof *s);
    if (!s) {
        dst->nomem = 0;
        gd_plot_free(src);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory building a plot");
    }
    dst->sections = s;
    memcpy(dst->sections + dst->nsections, src->sections, (size_t)src->nsections * sizeof *s);
    dst->nsections += src->nsections;
    free(src->sections);
    free(src);
    return GD_OK;
}

int gd_plot_nsections(const gd_plot *p)
{
    return p ? p->nsections : 0;
}

int gd_plot_npanels(const gd_plot *p, int section)
{
    return p && section >= 0 && section < p->nsections ? p->sections[section].npanels : 0;
}

int gd_plot_ntraces(const gd_plot *p, int section, int panel)
{
    if (!p || section < 0 || section >= p->nsections) return 0;
    const pl_section *s = &p->sections[section];
    return panel >= 0 && panel < s->npanels ? s->panels[panel].ntraces : 0;
}

const char *pl_color(int i)
{
    /* Tableau 10: distinct on screen and in print */
    static const char *const c[10] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
    return c[(i % 10 + 10) % 10];
}

const char *pl_whirl_color(gd_whirl w)
{
    switch (w) {
    case GD_WHIRL_FORWARD:
        return "#1f4fd6";
    case GD_WHIRL_BACKWARD:
        return "#d62728";
    case GD_WHIRL_MIXED:
        return "#9467bd";
    default:
        return "#7f7f7f";
    }
}

void pl_range(const pl_panel *pn, int axis, double *lo, double *hi)
{
    int logscale = axis ? pn->ylog : pn->xlog;
    double a = INFINITY, b = -INFINITY;
    for (int t = 0; t < pn->ntraces; t++) {
        if (axis && pn->traces[t].y2 != (axis == 2)) continue;
        const double *v = axis ? pn->traces[t].y : pn->traces[t].x;
        for (int i = 0; i < pn->traces[t].n; i++) {
            if (!isfinite(v[i]) || (logscale && !(v[i] > 0))) continue;
            if (v[i] < a) a = v[i];
            if (v[i] > b) b = v[i];
        }
    }
    if (!(a <= b)) a = logscale ? 1 : 0, b = logscale ? 10 : 1;
    if (a == b) {
        double d = logscale ? 0 : (a == 0 ? 1 : 0.1 * fabs(a));
        if (logscale)
            a /= 10, b *= 10;
        else
            a -= d, b += d;
    }
    *lo = a;
    *hi = b;
}

int pl_ticks(double lo, double hi, int logscale, double *ticks, int max)
{
    int n = 0;
    if (logscale) {
        int e0 = (int)floor(log10(lo)), e1 = (int)ceil(log10(hi));
        int step = 1;
        while ((e1 - e0) / step + 1 > max)
            step++;
        for (int e = e0; e <= e1 && n < max; e += step)
            ticks[n++] = pow(10, e);
        return n;
    }
    double raw = (hi - lo) / 5, mag = pow(10, floor(log10(raw))), f = raw / mag;
    double step = (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * mag;
    for (double v = ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step && n < max; v += step)
        ticks[n++] = fabs(v) < 1e-12 * step ? 0 : v;
    return n;
}

/* A hover label with every "<number> <from>" (the unit a whole word) rewritten as
 * "<number x factor> <to>"; NULL when nothing changed or out of memory. */
static char *convert_text(const char *s, const char *from, const char *to, double factor)
{
    size_t lf = strlen(from), cap = 2 * strlen(s) + 64, n = 0;
    char *o = NULL;
    int changed = 0;
    const char *last = s; /* copied up to here */
    for (const char *u = strstr(s, from); u; u = strstr(u + lf, from)) {
        char after = u[lf];
        if (u - s < 2 || u[-1] != ' ' || (after && (isalnum((unsigned char)after) || after == '/')))
            continue;
        const char *b = u - 1; /* the number before the space */
        while (b > last && strchr("0123456789.eE+-", b[-1]))
            b--;
        if (b == u - 1) continue;
        char *end;
        double v = strtod(b, &end);
        if (end != u - 1) continue;
        if (!o && !(o = malloc(cap))) return NULL;
        char num[64];
        int ln = snprintf(num, sizeof num, "%.6g %s", v * factor, to);
        size_t keep = (size_t)(b - last);
        if (n + keep + (size_t)ln + 1 > cap) {
            cap = 2 * (n + keep + (size_t)ln + 1);
            char *g = realloc(o, cap);
            if (!g) {
                free(o);
                return NULL;
            }
            o = g;
        }
        memcpy(o + n, last, keep);
        n += keep;
        memcpy(o + n, num, (size_t)ln);
        n += (size_t)ln;
        last = u + lf;
        changed = 1;
    }
    if (!changed) {
        free(o);
        return NULL;
    }
    size_t rest = strlen(last);
    if (n + rest + 1 > cap) {
        char *g = realloc(o, n + rest + 1);
        if (!g) {
            free(o);
            return NULL;
        }
        o = g;
    }
    memcpy(o + n, last, rest + 1);
    return o;
}

int gd_plot_convert_x(gd_plot *p, const char *from, const char *to, double factor)
{
    /* hover labels of every trace: "126.53 Hz" -> "795.01 rad/s" */
    for (int i = 0; p && i < p->nsections; i++)
        for (int k = 0; k < p->sections[i].npanels; k++)
            for (int t = 0; t < p->sections[i].panels[k].ntraces; t++) {
                pl_trace *tr = &p->sections[i].panels[k].traces[t];
                for (int j = 0; tr->text && j < tr->n; j++) {
                    char *c = tr->text[j] ? convert_text(tr->text[j], from, to, factor) : NULL;
                    if (!c) continue;
                    free(tr->text[j]);
                    tr->text[j] = c;
                }
            }
    char want[48], repl[48];
    snprintf(want, sizeof want, "(%s)", from);
    snprintf(repl, sizeof repl, "(%s)", to);
    int n = 0;
    for (int i = 0; p && i < p->nsections; i++)
        for (int k = 0; k < p->sections[i].npanels; k++) {
            pl_panel *pn = &p->sections[i].panels[k];
            char *at = pn->kind == PL_XY ? strstr(pn->xlabel, want) : NULL;
            if (!at) continue;
            char label[sizeof pn->xlabel];
            snprintf(label, sizeof label, "%.*s%s%s", (int)(at - pn->xlabel), pn->xlabel, repl,
                     at + strlen(want));
            snprintf(pn->xlabel, sizeof pn->xlabel, "%s", label);
            for (int t = 0; t < pn->ntraces; t++)
                for (int j = 0; j < pn->traces[t].n; j++)
                    pn->traces[t].x[j] *= factor;
            pn->xlim[0] *= factor;
            pn->xlim[1] *= factor;
            n++;
        }
    return n;
}
