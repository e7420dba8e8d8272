/* PNG and PDF plots: the document's SVG (svg.c) rendered by librsvg onto a cairo image
 * surface (PNG) or PDF surface, so the static figure and the raster ones are the same
 * drawing. PNG: one image of the whole document at twice the SVG's pixel size (sharp
 * when pasted into a report), less for very tall documents (cairo's 32767 px limit).
 * PDF: one page per section, a section taller than an A4-shaped page split between its
 * panels onto pages of their own, so a figure is never cut. Built only when librsvg and
 * cairo were found (GD_HAVE_RASTER); otherwise pl_raster_missing names the packages.
 * A document taller than 8000 SVG pixels (a report) is drawn at its own size. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

const char *pl_raster_missing(void)
{
#ifdef GD_HAVE_RASTER
    return NULL;
#else
    return "librsvg-2.0 and cairo (Debian: librsvg2-dev libcairo2-dev, scripts/install-deps.sh)";
#endif
}

#ifndef GD_HAVE_RASTER
gd_status pl_write_raster(const gd_plot *p, FILE *f, int pdf, gd_error *err)
{
    (void)p;
    (void)f;
    return gd_error_set(err, GD_EINPUT, "", 0, 0, "--plot", "install them and rebuild geardyn",
                        "%s output needs %s, which this build lacks", pdf ? "PDF" : "PNG",
                        pl_raster_missing());
}
#else
#include <cairo-pdf.h>
#include <cairo.h>
#include <librsvg/rsvg.h>

/* The SVG of a document in memory. */
static gd_status svg_bytes(const gd_plot *p, char **buf, size_t *len, gd_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *m = open_memstream(buf, len);
    if (!m) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_status st = pl_write_svg(p, m, err);
    if (fclose(m) != 0 && !st) st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (st) {
        free(*buf);
        *buf = NULL;
    }
    return st;
}

static gd_status rsvg_fail(GError *ge, gd_error *err)
{
    gd_status st = gd_error_set(err, GD_EIO, "", 0, 0, "--plot", "", "cannot render the figure: %s",
                                ge ? ge->message : "librsvg");
    if (ge) g_error_free(ge);
    return st;
}

/* An SVG parsed; *w, *h: its size in SVG pixels. */
static RsvgHandle *load(const char *buf, size_t len, double *w, double *h, GError **ge)
{
    RsvgHandle *hd = rsvg_handle_new_from_data((const guint8 *)buf, len, ge);
    if (!hd) return NULL;
    if (!rsvg_handle_get_intrinsic_size_in_pixels(hd, w, h)) *w = *h = 0;
    return hd;
}

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int length)
{
    return fwrite(data, 1, length, (FILE *)closure) == length ? CAIRO_STATUS_SUCCESS
                                                              : CAIRO_STATUS_WRITE_ERROR;
}

enum { TALL = 8000 }; /* SVG pixels */

static gd_status write_png(const gd_plot *p, FILE *f, gd_error *err)
{
    char *buf;
    size_t len;
    gd_status st = svg_bytes(p, &buf, &len, err);
    if (st) return st;
    GError *ge = NULL;
    double w, h;
    RsvgHandle *hd = load(buf, len, &w, &h, &ge);
    free(buf);
    if (!hd) return rsvg_fail(ge, err);
    /* twice the pixels for a figure; a long document (a report) at its own size, which
     * keeps it to about 1 MB and a second */
    double scale = h > TALL ? 1 : 2;
    if (h * scale > 32000) scale = 32000 / h;
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, (int)(w * scale + 0.5),
                                                     (int)(h * scale + 0.5));
    cairo_t *cr = cairo_create(sf);
    cairo_scale(cr, scale, scale);
    RsvgRectangle vp = {0, 0, w, h};
    if (!rsvg_handle_render_document(hd, cr, &vp, &ge)) st = rsvg_fail(ge, err);
    cairo_destroy(cr);
    if (!st && cairo_surface_write_to_png_stream(sf, to_file, f) != CAIRO_STATUS_SUCCESS)
        st = gd_error_set(err, GD_EIO, "", 0, 0, "--plot", "check the free space",
                          "cannot write the PNG");
    cairo_surface_destroy(sf);
    g_object_unref(hd);
    return st;
}

/* The height of a page at most (an A4 page's shape at the SVG's 960 px width). */
enum { PAGE_MAX = 1360 };

static gd_status pdf_page(cairo_surface_t *sf, const gd_plot *page, gd_error *err)
{
    char *buf;
    size_t len;
    gd_status st = svg_bytes(page, &buf, &len, err);
    if (st) return st;
    GError *ge = NULL;
    double w, h;
    RsvgHandle *hd = load(buf, len, &w, &h, &ge);
    free(buf);
    if (!hd) return rsvg_fail(ge, err);
    cairo_pdf_surface_set_size(sf, w, h);
    cairo_t *cr = cairo_create(sf);
    RsvgRectangle vp = {0, 0, w, h};
    if (!rsvg_handle_render_document(hd, cr, &vp, &ge)) st = rsvg_fail(ge, err);
    cairo_show_page(cr);
    cairo_destroy(cr);
    g_object_unref(hd);
    return st;
}

static gd_status write_pdf(const gd_plot *p, FILE *f, gd_error *err)
{
    cairo_surface_t *sf = cairo_pdf_surface_create_for_stream(to_file, f, 960, PAGE_MAX);
    cairo_pdf_surface_set_metadata(sf, CAIRO_PDF_METADATA_TITLE, p->title);
    cairo_pdf_surface_set_metadata(sf, CAIRO_PDF_METADATA_CREATOR, "geardyn");
    gd_status st = GD_OK;
    /* a page is a view of the document: one section, or a run of its panels */
    gd_plot page = *p;
    for (int i = 0; i < p->nsections && !st; i++) {
        const pl_section *s = &p->sections[i];
        int k0 = 0;
        do {
            pl_section part = *s;
            double used = 0;
            int k1 = k0;
            while (k1 < s->npanels) {
                double ph = pl_svg_panel_height(&s->panels[k1]);
                if (k1 > k0 && used + ph > PAGE_MAX - 160) break;
                used += ph;
                k1++;
            }
            part.panels = s->panels ? s->panels + k0 : NULL; /* a note-only section has none */
            part.npanels = k1 - k0;
            if (k0 > 0) {
                snprintf(part.title, sizeof part.title, "%.180s (continued)", s->title);
                part.note = NULL;
            }
            page.sections = &part;
            page.nsections = 1;
            st = pdf_page(sf, &page, err);
            k0 = k1;
        } while (k0 < s->npanels && !st);
    }
    cairo_surface_finish(sf);
    if (!st && cairo_surface_status(sf) != CAIRO_STATUS_SUCCESS)
        st = gd_error_set(err, GD_EIO, "", 0, 0, "--plot", "check the free space",
                          "cannot write the PDF: %s",
                          cairo_status_to_string(cairo_surface_status(sf)));
    cairo_surface_destroy(sf);
    return st;
}

gd_status pl_write_raster(const gd_plot *p, FILE *f, int pdf, gd_error *err)
{
    return pdf ? write_pdf(p, f, err) : write_png(p, f, err);
}
#endif
