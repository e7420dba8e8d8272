/* Static SVG of a plot document, drawn here (no library): panels stacked in one column,
 * each with axes, ticks, grid, curves clipped to the plot area and a legend. Every
 * curve is a <g class="trace"> carrying its numbers exactly (data-x, data-y: shortest
 * round-trip decimals), so a reader (or a test) gets back what was plotted; markers
 * are elements of class "marker". 3-D panels are HTML only: SVG says so. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

enum { W = 960, LEFT = 92, RIGHT = W - 240, LEGEND_X = W - 225, TOP = 34, BOTTOM = 52 };

typedef struct frame {
    double x0, y0, pw, ph;     /* plot area in pixels */
    double xlo, xhi, ylo, yhi; /* data ranges (log10 on a log axis) */
    double sx, sy, offx, offy; /* equal-scale mapping */
    int xlog, ylog, equal;
} frame;

static double tr(double v, int logscale)
{
    return logscale ? (v > 0 ? log10(v) : NAN) : v;
}

static double px(const frame *f, double v)
{
    v = tr(v, f->xlog);
    if (f->equal) return f->x0 + f->offx + (v - f->xlo) * f->sx;
    return f->x0 + (v - f->xlo) / (f->xhi - f->xlo) * f->pw;
}

static double py(const frame *f, double v)
{
    v = tr(v, f->ylog);
    if (f->equal) return f->y0 + f->ph - f->offy - (v - f->ylo) * f->sy;
    return f->y0 + f->ph - (v - f->ylo) / (f->yhi - f->ylo) * f->ph;
}

static int note_lines(const char *s)
{
    return s ? (int)(strlen(s) / 140) + 1 : 0;
}

/* The rows of a table drawn for PNG and PDF: a Campbell or report table of hundreds of
 * rows made PNGs 8000 to 22874 px tall (issue 35); the rest are in the SVG, the HTML
 * and the CSV, which the line under the cut says. */
enum { RASTER_TABLE_ROWS = 40 };

static int table_rows(const pl_panel *pn, int raster)
{
    return raster && pn->nrows > RASTER_TABLE_ROWS ? RASTER_TABLE_ROWS : pn->nrows;
}

double pl_svg_panel_height(const pl_panel *pn, int raster)
{
    if (pn->kind == PL_TABLE)
        return 40 + 20.0 * (table_rows(pn, raster) + 1 + (table_rows(pn, raster) < pn->nrows));
    if (pn->kind == PL_MODE3D) return 36;
    if (pn->equal) {
        double xl, xh, yl, yh;
        pl_range(pn, 0, &xl, &xh);
        pl_range(pn, 1, &yl, &yh);
        double ph = (RIGHT - LEFT) * (yh - yl) / (xh - xl);
        return TOP + BOTTOM + (ph < 160 ? 160 : ph > 640 ? 640 : ph);
    }
    return 330 + (pn->subtitle[0] ? 16 : 0);
}

static int has_y2(const pl_panel *pn)
{
    for (int t = 0; t < pn->ntraces; t++)
        if (pn->traces[t].y2) return 1;
    return 0;
}

static void number(FILE *f, double v)
{
    if (isfinite(v))
        fprintf(f, "%.17g", v);
    else
        fputs("nan", f);
}

static void fmt_tick(char *buf, size_t n, double v, int logscale)
{
    if (logscale)
        snprintf(buf, n, "1e%d", (int)lround(log10(v)));
    else
        snprintf(buf, n, "%.6g", v);
}

static void marker(FILE *f, pl_symbol s, double x, double y, const char *c)
{
    switch (s) {
    case PL_SQUARE:
        fprintf(
            f,
            "<rect class=\"marker\" x=\"%.2f\" y=\"%.2f\" width=\"8\" height=\"8\" fill=\"%s\"/>",
            x - 4, y - 4, c);
        break;
    case PL_DIAMOND:
        fprintf(f,
                "<polygon class=\"marker\" points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f %.2f,%.2f\" "
                "fill=\"%s\"/>",
                x, y - 6, x + 6, y, x, y + 6, x - 6, y, c);
        break;
    case PL_TRIANGLE:
        fprintf(f,
                "<polygon class=\"marker\" points=\"%.2f,%.2f %.2f,%.2f %.2f,%.2f\" fill=\"%s\"/>",
                x, y - 6, x + 6, y + 5, x - 6, y + 5, c);
        break;
    default:
        fprintf(f, "<circle class=\"marker\" cx=\"%.2f\" cy=\"%.2f\" r=\"3.5\" fill=\"%s\"/>", x, y,
                c);
    }
}

/* The resolution of the curves drawn for PNG and PDF (SVG pixels): a PNG has two
 * device pixels to one SVG pixel, so a quarter of one is finer than the eye sees. */
#define RASTER_CELL 0.25

/* The points of a trace as polyline/polygon runs, broken at values a log axis or NaN
 * cannot show; for raster output (raster != 0) thinned to RASTER_CELL (pl_decimate).
 * -1 when out of memory. */
static int runs(FILE *f, const frame *fr, const pl_trace *t, const char *clip, int raster)
{
    double *xs = NULL, *ys = NULL;
    int *keep = NULL;
    if (raster && t->mode != PL_FILL) {
        xs = malloc((size_t)t->n * sizeof *xs + 1);
        ys = malloc((size_t)t->n * sizeof *ys + 1);
        keep = malloc((size_t)t->n * sizeof *keep + 1);
        if (!xs || !ys || !keep) {
            free(xs), free(ys), free(keep);
            return -1;
        }
    }
    int i = 0;
    while (i < t->n) {
        while (i < t->n && !(isfinite(px(fr, t->x[i])) && isfinite(py(fr, t->y[i]))))
            i++;
        int j = i;
        while (j < t->n && isfinite(px(fr, t->x[j])) && isfinite(py(fr, t->y[j])))
            j++;
        if (j > i) {
            if (t->mode == PL_FILL)
                fprintf(f,
                        "<polygon clip-path=\"url(#%s)\" fill=\"%s\" fill-opacity=\"0.18\" "
                        "stroke=\"none\" points=\"",
                        clip, t->color);
            else
                fprintf(f,
                        "<polyline clip-path=\"url(#%s)\" fill=\"none\" stroke=\"%s\" "
                        "stroke-width=\"1.6\"%s points=\"",
                        clip, t->color, t->dash ? " stroke-dasharray=\"6,4\"" : "");
            if (keep) {
                for (int k = i; k < j; k++)
                    xs[k - i] = px(fr, t->x[k]), ys[k - i] = py(fr, t->y[k]);
                int m = pl_decimate(xs, ys, j - i, RASTER_CELL, keep);
                for (int k = 0; k < m; k++)
                    fprintf(f, "%s%.2f,%.2f", k ? " " : "", xs[keep[k]], ys[keep[k]]);
            } else {
                for (int k = i; k < j; k++)
                    fprintf(f, "%s%.2f,%.2f", k > i ? " " : "", px(fr, t->x[k]), py(fr, t->y[k]));
            }
            fputs("\"/>\n", f);
        }
        i = j;
    }
    free(xs), free(ys), free(keep);
    return 0;
}

static int xy_panel(FILE *f, const pl_panel *pn, double y, double h, int id, int raster)
{
    int two = has_y2(pn) && !pn->equal && !pn->ylog;
    double top = TOP + (pn->subtitle[0] ? 16 : 0);
    frame fr = {.x0 = LEFT,
                .y0 = y + top,
                .pw = RIGHT - LEFT - (two ? 64 : 0),
                .ph = h - top - BOTTOM,
                .xlog = pn->xlog,
                .ylog = pn->ylog,
                .equal = pn->equal};
    double xl, xh, yl, yh;
    pl_range(pn, 0, &xl, &xh);
    pl_range(pn, 1, &yl, &yh);
    if (pn->xlim[0] < pn->xlim[1] && !pn->equal) xl = pn->xlim[0], xh = pn->xlim[1];
    if (pn->ylim[0] < pn->ylim[1] && !pn->equal) {
        yl = pn->ylim[0];
        yh = pn->ylim[1];
    } else if (!pn->equal && !pn->ylog) { /* a little room above and below the curves */
        double d = 0.04 * (yh - yl);
        yl -= d;
        yh += d;
    }
    fr.xlo = tr(xl, fr.xlog);
    fr.xhi = tr(xh, fr.xlog);
    fr.ylo = tr(yl, fr.ylog);
    fr.yhi = tr(yh, fr.ylog);
    if (fr.xlog) fr.xlo = floor(fr.xlo), fr.xhi = ceil(fr.xhi);
    if (fr.ylog) fr.ylo = floor(fr.ylo), fr.yhi = ceil(fr.yhi);
    if (fr.equal) {
        double s1 = fr.pw / (fr.xhi - fr.xlo), s2 = fr.ph / (fr.yhi - fr.ylo);
        fr.sx = fr.sy = s1 < s2 ? s1 : s2;
        fr.offx = 0.5 * (fr.pw - (fr.xhi - fr.xlo) * fr.sx);
        fr.offy = 0.5 * (fr.ph - (fr.yhi - fr.ylo) * fr.sy);
    }
    frame fr2 = fr; /* the right-hand axis: its own linear range */
    double y2l = 0, y2h = 1;
    if (two) {
        pl_range(pn, 2, &y2l, &y2h);
        double d = 0.04 * (y2h - y2l);
        y2l -= d;
        y2h += d;
        if (pn->y2lim[0] < pn->y2lim[1]) y2l = pn->y2lim[0], y2h = pn->y2lim[1];
        fr2.ylo = y2l;
        fr2.yhi = y2h;
    }
    char clip[32];
    snprintf(clip, sizeof clip, "clip%d", id);
    fprintf(f, "<g class=\"panel\" data-title=\"");
    pl_xml_text(f, pn->title);
    fprintf(f,
            "\">\n<clipPath id=\"%s\"><rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\"/>"
            "</clipPath>\n",
            clip, fr.x0 - 6, fr.y0 - 6, fr.pw + 12, fr.ph + 12);
    fprintf(f, "<text x=\"%d\" y=\"%.1f\" font-size=\"14\" font-weight=\"bold\">", LEFT, y + 20);
    pl_xml_text(f, pn->title);
    fputs("</text>\n", f);
    if (pn->subtitle[0]) {
        fprintf(f, "<text class=\"subtitle\" x=\"%d\" y=\"%.1f\" font-size=\"11\">", LEFT, y + 37);
        pl_xml_text(f, pn->subtitle);
        fputs("</text>\n", f);
    }
    fprintf(f,
            "<rect x=\"%.1f\" y=\"%.1f\" width=\"%.1f\" height=\"%.1f\" fill=\"none\" "
            "stroke=\"#444\"/>\n",
            fr.x0, fr.y0, fr.pw, fr.ph);
    /* ticks and grid */
    double ticks[32];
    char lab[32];
    for (int axis = 0; axis < 2; axis++) {
        double lo = axis ? yl : xl, hi = axis ? yh : xh;
        int lg = axis ? fr.ylog : fr.xlog;
        if (fr.equal) { /* the visible range is wider than the data */
            lo = axis ? fr.ylo - fr.offy / fr.sy : fr.xlo - fr.offx / fr.sx;
            hi = axis ? fr.ylo + (fr.ph - fr.offy) / fr.sy : fr.xlo + (fr.pw - fr.offx) / fr.sx;
        } else if (lg) {
            lo = pow(10, axis ? fr.ylo : fr.xlo);
            hi = pow(10, axis ? fr.yhi : fr.xhi);
        }
        int nt = pl_ticks(lo, hi, lg, ticks, 32);
        if (!axis && pn->xint && !lg) { /* whole numbers only, a step of 1, 2, 5, 10... */
            int m = 0;
            for (int k = 0; k < nt; k++)
                if (ticks[k] == floor(ticks[k])) ticks[m++] = ticks[k];
            if (m < 2) {
                m = 0;
                for (double v = ceil(lo); v <= hi && m < 32; v++)
                    ticks[m++] = v;
            }
            nt = m;
        }
        for (int k = 0; k < nt; k++) {
            fmt_tick(lab, sizeof lab, ticks[k], lg);
            if (axis) {
                double v = py(&fr, ticks[k]);
                if (v < fr.y0 - 0.5 || v > fr.y0 + fr.ph + 0.5) continue;
                fprintf(
                    f,
                    "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.2f\" y2=\"%.2f\" stroke=\"#ddd\"/>"
                    "<text x=\"%.1f\" y=\"%.2f\" font-size=\"11\" text-anchor=\"end\">%s</text>\n",
                    fr.x0, fr.x0 + fr.pw, v, v, fr.x0 - 5, v + 4, lab);
            } else {
                double v = px(&fr, ticks[k]);
                if (v < fr.x0 - 0.5 || v > fr.x0 + fr.pw + 0.5) continue;
                fprintf(f,
                        "<line x1=\"%.2f\" x2=\"%.2f\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"#ddd\"/>"
                        "<text x=\"%.2f\" y=\"%.1f\" font-size=\"11\" "
                        "text-anchor=\"middle\">%s</text>\n",
                        v, v, fr.y0, fr.y0 + fr.ph, v, fr.y0 + fr.ph + 15, lab);
            }
        }
    }
    if (two) {
        int nt = pl_ticks(y2l, y2h, 0, ticks, 32);
        for (int k = 0; k < nt; k++) {
            double v = py(&fr2, ticks[k]);
            if (v < fr.y0 - 0.5 || v > fr.y0 + fr.ph + 0.5) continue;
            fmt_tick(lab, sizeof lab, ticks[k], 0);
            fprintf(f,
                    "<line x1=\"%.1f\" x2=\"%.1f\" y1=\"%.2f\" y2=\"%.2f\" stroke=\"#444\"/>"
                    "<text x=\"%.1f\" y=\"%.2f\" font-size=\"11\">%s</text>\n",
                    fr.x0 + fr.pw, fr.x0 + fr.pw + 4, v, v, fr.x0 + fr.pw + 6, v + 4, lab);
        }
        fprintf(f,
                "<text transform=\"translate(%.1f,%.1f) rotate(90)\" font-size=\"12\" "
                "text-anchor=\"middle\">",
                fr.x0 + fr.pw + 44, fr.y0 + fr.ph / 2);
        pl_xml_text(f, pn->y2label);
        fputs("</text>\n", f);
    }
    fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"12\" text-anchor=\"middle\">",
            fr.x0 + fr.pw / 2, fr.y0 + fr.ph + 36);
    pl_xml_text(f, pn->xlabel);
    fprintf(f,
            "</text>\n<text transform=\"translate(%.1f,%.1f) rotate(-90)\" font-size=\"12\" "
            "text-anchor=\"middle\">",
            fr.x0 - 62, fr.y0 + fr.ph / 2);
    pl_xml_text(f, pn->ylabel);
    fputs("</text>\n", f);
    /* curves, then the legend; labels written at curve ends step down out of each
     * other's way */
    int shown = 0, nlab = 0;
    double labx[32], laby[32];
    for (int t = 0; t < pn->ntraces; t++) {
        const pl_trace *c = &pn->traces[t];
        fprintf(f, "<g class=\"trace\" data-name=\"");
        pl_xml_text(f, c->name);
        fprintf(f, "\" data-mode=\"%s\" data-n=\"%d\"",
                c->mode == PL_FILL      ? "fill"
                : c->mode == PL_MARKERS ? "markers"
                                        : "lines",
                c->n);
        if (!raster) { /* the numbers are for readers of the SVG, not for drawing */
            fputs(" data-x=\"", f);
            for (int i = 0; i < c->n; i++) {
                if (i) fputc(' ', f);
                number(f, c->x[i]);
            }
            fputs("\" data-y=\"", f);
            for (int i = 0; i < c->n; i++) {
                if (i) fputc(' ', f);
                number(f, c->y[i]);
            }
            fputc('"', f);
        }
        fputs(c->y2 ? " data-axis=\"y2\">\n" : ">\n", f);
        const frame *cf = c->y2 && two ? &fr2 : &fr;
        if (c->mode != PL_MARKERS && runs(f, cf, c, clip, raster)) return -1;
        double la = NAN, lb = NAN; /* the last marker drawn */
        const char *lc = NULL;
        if (c->mode == PL_MARKERS || c->mode == PL_LINES_MARKERS)
            for (int i = 0; i < c->n; i++) {
                double a = px(cf, c->x[i]), b = py(cf, c->y[i]);
                if (!isfinite(a) || !isfinite(b)) continue;
                const char *mc = c->marker_color ? c->marker_color[i] : c->color;
                /* raster: a marker on top of the last one, of its colour, adds nothing */
                if (raster && mc == lc && fabs(a - la) < RASTER_CELL && fabs(b - lb) < RASTER_CELL)
                    continue;
                marker(f, c->symbol, a, b, mc);
                fputc('\n', f);
                la = a, lb = b, lc = mc;
            }
        if (c->label[0] && c->n > 0) { /* at the last point shown, inside the frame */
            double a = px(cf, c->x[c->n - 1]), b = py(cf, c->y[c->n - 1]);
            if (isfinite(a) && isfinite(b)) {
                if (b < fr.y0 + 12) b = fr.y0 + 12;
                for (int again = 1; again;) {
                    again = 0;
                    for (int q = 0; q < nlab; q++)
                        if (fabs(labx[q] - a) < 80 && fabs(laby[q] - b) < 11)
                            b = laby[q] + 11, again = 1;
                }
                if (nlab < 32) labx[nlab] = a, laby[nlab++] = b;
                fprintf(f,
                        "<text class=\"label\" x=\"%.2f\" y=\"%.2f\" font-size=\"10\" "
                        "text-anchor=\"%s\" fill=\"%s\">",
                        c->label_right ? a + 3 : a - 3, c->label_right ? b + 10 : b - 4,
                        c->label_right ? "start" : "end", c->color);
                pl_xml_text(f, c->label);
                fputs("</text>\n", f);
            }
        }
        fputs("</g>\n", f);
        if (!c->legend) continue;
        if (shown < 16) {
            double ly = fr.y0 + 8 + 17.0 * shown;
            if (c->mode == PL_MARKERS)
                marker(f, c->symbol, LEGEND_X + 10, ly - 4, c->color);
            else
                fprintf(f,
                        "<line x1=\"%d\" x2=\"%d\" y1=\"%.1f\" y2=\"%.1f\" stroke=\"%s\" "
                        "stroke-width=\"%s\"%s/>",
                        LEGEND_X, LEGEND_X + 20, ly - 4, ly - 4, c->color,
                        c->mode == PL_FILL ? "8\" stroke-opacity=\"0.3" : "2",
                        c->dash ? " stroke-dasharray=\"5,3\"" : "");
            fprintf(f, "<text x=\"%d\" y=\"%.1f\" font-size=\"11\">", LEGEND_X + 26, ly);
            char nm[40];
            snprintf(nm, sizeof nm, "%.34s", c->name);
            pl_xml_text(f, nm);
            fputs("</text>\n", f);
        } else if (shown == 16) {
            fprintf(f, "<text x=\"%d\" y=\"%.1f\" font-size=\"11\">(more in the HTML)</text>\n",
                    LEGEND_X + 26, fr.y0 + 8 + 17.0 * shown);
        }
        shown++;
    }
    fputs("</g>\n", f);
    return 0;
}

static void table_panel(FILE *f, const pl_panel *pn, double y, int raster)
{
    int shown = table_rows(pn, raster);
    fprintf(f,
            "<g class=\"table\" data-rows=\"%d\" data-cols=\"%d\">\n<text x=\"%d\" y=\"%.1f\" "
            "font-size=\"14\" font-weight=\"bold\">",
            pn->nrows, pn->ncols, LEFT, y + 20);
    pl_xml_text(f, pn->title);
    fputs("</text>\n", f);
    double cw = (double)(W - 40) / (pn->ncols > 0 ? pn->ncols : 1);
    for (int r = 0; r <= shown; r++)
        for (int c = 0; c < pn->ncols; c++) {
            const char *s = pn->cells[(size_t)r * pn->ncols + c];
            fprintf(f, "<text x=\"%.1f\" y=\"%.1f\" font-size=\"%d\"%s>", 20 + c * cw,
                    y + 44 + 20.0 * r, cw < 70 ? 9 : 11, r ? "" : " font-weight=\"bold\"");
            char cut[96];
            snprintf(cut, sizeof cut, "%.*s", (int)(cw / (cw < 70 ? 5.5 : 6.6)), s ? s : "");
            pl_xml_text(f, cut);
            fputs("</text>\n", f);
        }
    if (shown < pn->nrows)
        fprintf(f,
                "<text class=\"cut\" x=\"20\" y=\"%.1f\" font-size=\"11\" font-style=\"italic\">"
                "... %d more rows: every row is in the SVG and HTML plots and the CSV</text>\n",
                y + 44 + 20.0 * (shown + 1), pn->nrows - shown);
    fputs("</g>\n", f);
}

static gd_status write_svg(const gd_plot *p, FILE *f, int raster, gd_error *err)
{
    double h = 40;
    for (int i = 0; i < p->nsections; i++) {
        const pl_section *s = &p->sections[i];
        h += 48 + 16.0 * note_lines(s->note);
        for (int k = 0; k < s->npanels; k++)
            h += pl_svg_panel_height(&s->panels[k], raster);
    }
    fprintf(f,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" "
            "width=\"%d\" height=\"%.0f\" viewBox=\"0 0 %d %.0f\" font-family=\"sans-serif\">\n"
            "<title>",
            W, h, W, h);
    pl_xml_text(f, p->title);
    fprintf(f, "</title>\n<rect width=\"%d\" height=\"%.0f\" fill=\"white\"/>\n", W, h);
    double y = 24;
    int id = 0;
    for (int i = 0; i < p->nsections; i++) {
        const pl_section *s = &p->sections[i];
        y += 12;
        fprintf(f,
                "<g class=\"section\">\n<text x=\"20\" y=\"%.1f\" font-size=\"18\" "
                "font-weight=\"bold\">",
                y + 6);
        pl_xml_text(f, s->title);
        fputs("</text>\n", f);
        y += 30;
        for (int l = 0; l < note_lines(s->note); l++) {
            char line[160];
            snprintf(line, sizeof line, "%.140s", s->note + 140 * l);
            fprintf(f, "<text x=\"20\" y=\"%.1f\" font-size=\"12\">", y);
            pl_xml_text(f, line);
            fputs("</text>\n", f);
            y += 16;
        }
        y += 6;
        for (int k = 0; k < s->npanels; k++) {
            const pl_panel *pn = &s->panels[k];
            double ph = pl_svg_panel_height(pn, raster);
            if (pn->kind == PL_XY) {
                if (xy_panel(f, pn, y, ph, id++, raster))
                    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            } else if (pn->kind == PL_TABLE)
                table_panel(f, pn, y, raster);
            else {
                fprintf(f, "<text x=\"%d\" y=\"%.1f\" font-size=\"12\" font-style=\"italic\">",
                        LEFT, y + 22);
                pl_xml_text(f, pn->title);
                fputs(": animated 3-D view in the HTML output (--plot FILE.html)</text>\n", f);
            }
            y += ph;
        }
        fputs("</g>\n", f);
    }
    fputs("</svg>\n", f);
    if (ferror(f)) return gd_error_set(err, GD_EIO, "", 0, 0, "", "", "write error");
    return GD_OK;
}

gd_status pl_write_svg(const gd_plot *p, FILE *f, gd_error *err)
{
    return write_svg(p, f, 0, err);
}

gd_status pl_write_svg_raster(const gd_plot *p, FILE *f, gd_error *err)
{
    return write_svg(p, f, 1, err);
}

void pl_xml_text(FILE *f, const char *s)
{
    for (; *s; s++) {
        switch (*s) {
        case '&':
            fputs("&amp;", f);
            break;
        case '<':
            fputs("&lt;", f);
            break;
        case '>':
            fputs("&gt;", f);
            break;
        case '"':
            fputs("&quot;", f);
            break;
        default:
            /* XML 1.0 allows no control characters but tab and newline */
            fputc((unsigned char)*s < 0x20 && *s != '\n' && *s != '\t' ? ' ' : *s, f);
        }
    }
}
