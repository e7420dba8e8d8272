/* The document model behind gd_plot: sections of panels of traces, written by svg.c and
 * html.c. Builders (plot_*.c) fill it through the functions below; an allocation failure
 * is remembered in the document (p->nomem) and reported once by pl_done, so builders
 * need not check every call. */
#ifndef GD_PLOT_IMPL_H
#define GD_PLOT_IMPL_H
#include <stdio.h>

#include "geardyn/plot.h"

typedef enum pl_mode {
    PL_LINES,
    PL_MARKERS,
    PL_LINES_MARKERS,
    PL_FILL /* closed polygons (NaN separates them), no outline */
} pl_mode;

typedef enum pl_symbol { PL_CIRCLE, PL_SQUARE, PL_DIAMOND, PL_TRIANGLE } pl_symbol;

typedef struct pl_trace {
    char name[160];
    int n;
    double *x, *y;
    /* mode-shape traces of a 3-D panel: complex x and y motion along the shaft */
    double *xr, *xi, *yr, *yi;
    int frame; /* 3-D panel: which mode this trace belongs to */
    pl_mode mode;
    pl_symbol symbol;
    const char *color;         /* CSS colour */
    const char **marker_color; /* n colours of the markers (static strings), or NULL */
    int dash;                  /* dashed line */
    int legend;                /* shown in the legend */
    char **text;               /* n hover labels, or NULL */
    int y2;                    /* against the panel's right-hand axis (y2label) */
    char label[64];            /* written on the plot at the trace's last point */
    int label_right;           /* the label to the right of that point (else to its left) */
    int label_below;           /* HTML: the label below the point (neighbours alternate) */
} pl_trace;

typedef enum pl_kind { PL_XY, PL_TABLE, PL_MODE3D } pl_kind;

typedef struct pl_panel {
    pl_kind kind;
    char title[200], xlabel[120], ylabel[120];
    char y2label[120];        /* right-hand axis of the traces marked y2 */
    char subtitle[400];       /* a line under the title (what was left out, ...) */
    double ylim[2], y2lim[2]; /* fixed ranges of the y axes when lo < hi; else the data's */
    int xint;                 /* x ticks on whole numbers only (orders) */
    double xlim[2];           /* fixed x range when lo < hi */
    int xlog, ylog;
    int equal; /* equal scales on x and y (orbits, the model drawing) */
    int ntraces, cap;
    pl_trace *traces;
    /* table */
    int nrows, ncols;
    char **cells; /* (nrows + 1) x ncols, row 0 the header */
    /* 3-D panel: frame labels */
    int nframes;
    char **frames;
} pl_panel;

typedef struct pl_section {
    char title[200];
    char *note;
    int npanels, cap;
    pl_panel *panels;
    char csv_name[96];
    char *csv; /* the numbers behind the plots */
    size_t csv_len, csv_cap;
} pl_section;

struct gd_plot {
    char title[200];
    int nsections, cap;
    pl_section *sections;
    int nomem;
};

/* builders */
pl_section *pl_section_add(gd_plot *p, const char *title);
void pl_note(gd_plot *p, pl_section *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
pl_panel *pl_panel_add(gd_plot *p, pl_section *s, pl_kind kind, const char *title,
                       const char *xlabel, const char *ylabel);
/* A trace with copies of n x and y values (y may be NULL: zeros). */
pl_trace *pl_trace_add(gd_plot *p, pl_panel *pn, const char *name, int n, const double *x,
                       const double *y, pl_mode mode, const char *color);
/* Hover label of point i. */
void pl_trace_text(gd_plot *p, pl_trace *t, int i, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
void pl_table_init(gd_plot *p, pl_panel *pn, int nrows, int ncols);
void pl_cell(gd_plot *p, pl_panel *pn, int row, int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
void pl_csv(gd_plot *p, pl_section *s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* Returns GD_ENOMEM (freeing p) if any allocation failed, else hands p to *out. */
gd_status pl_done(gd_plot *p, gd_plot **out, gd_error *err);
char *pl_strdup(gd_plot *p, const char *s);

/* a record's curve name (e.g. "gear_a.x", "mesh force"), quantity and unit
 * (record_label.c) */
void pl_record_describe(const gd_system *sys, const gd_tr_record *rec, char *name, size_t n,
                        const char **quantity, const char **unit);

/* An excitation order's name on the plot: "1x driving", "2x", "mesh 48x driving" (the
 * mesh's name kept unless it is just "mesh", so it does not read "mesh mesh 48x ...");
 * the Campbell diagram's, the waterfall's and the periodic plot's (plot_campbell.c) */
void pl_order_label(const gd_order *o, char *buf, size_t n);

/* colours: a palette for curves, and the whirl colours */
const char *pl_color(int i);
const char *pl_whirl_color(gd_whirl w);

/* axes: "nice" tick values for a range; returns the count (at most max) */
int pl_ticks(double lo, double hi, int logscale, double *ticks, int max);
/* data range of a panel's traces (finite values; positive ones on a log axis); axis 0
 * x, 1 y of the left-hand axis, 2 y of the traces on the right-hand one (y2) */
void pl_range(const pl_panel *pn, int axis, double *lo, double *hi);

/* writers */
gd_status pl_write_svg(const gd_plot *p, FILE *f, gd_error *err);
gd_status pl_write_html(const gd_plot *p, FILE *f, const char *plotly_path, gd_error *err);
/* the SVG drawn for PNG and PDF (raster.c): no data-x/data-y numbers, curves and
 * markers thinned to the resolution (pl_decimate) */
gd_status pl_write_svg_raster(const gd_plot *p, FILE *f, gd_error *err);
/* Of n points in pixels (x, y), the indices (ascending, into keep[n]) of those to draw
 * at a resolution of cell pixels: every point dropped lies within one cell of the line
 * through those kept (decimate.c). Returns their count. */
int pl_decimate(const double *x, const double *y, int n, double cell, int *keep);
/* the height of a panel in the SVG (pixels); raster: in the SVG drawn for PNG and PDF
 * (tables cut at 40 rows) */
double pl_svg_panel_height(const pl_panel *pn, int raster);
/* PNG (pdf = 0) or PDF of the document's SVG through the plugin geardyn-raster.so
 * (raster.c); errors name path */
gd_status pl_write_raster(const gd_plot *p, const char *path, FILE *f, int pdf, gd_error *err);
/* GD_OK when the plugin loads, else a located error (path, --plot) naming what is missing */
gd_status pl_raster_check(const char *path, int pdf, gd_error *err);
/* the folder of libgeardyn.so (or of the program that linked libgeardyn.a); 0 if unknown */
int pl_self_dir(char *dir, size_t size);
/* text escaped for XML / HTML, and for a JSON string */
void pl_xml_text(FILE *f, const char *s);
void pl_json_text(FILE *f, const char *s);
/* a number as JSON (null when not finite), shortest exact form */
void pl_json_number(FILE *f, double v);

#endif
