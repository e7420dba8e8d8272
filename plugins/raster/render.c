/* geardyn-raster.so: PNG and PDF plots, the SVG that libgeardyn made (src/plot/svg.c)
 * rendered by librsvg onto a cairo image surface (PNG) or PDF surface, so the static
 * figure and the raster ones are the same drawing. Loaded by src/plot/raster.c with
 * dlopen on the first PNG or PDF, so that librsvg, cairo and the ~45 libraries they pull
 * in are loaded only by a process that draws one (issue 35 item 1); the contract is
 * src/plot/raster_abi.h.
 * PNG: one image of the whole document at twice the SVG's pixel size (sharp when pasted
 * into a report); a document taller than 8000 SVG pixels (a report) at its own size,
 * and less when cairo's 32767 px limit needs it.
 * PDF: one page per SVG (the library splits a document into pages). */
#include <cairo-pdf.h>
#include <cairo.h>
#include <errno.h>
#include <librsvg/rsvg.h>
#include <stdio.h>
#include <string.h>

#include "plot/raster_abi.h"

/* exported (the plugin is built with hidden visibility like the library) */
#define GD_RASTER_EXPORT __attribute__((visibility("default")))
GD_RASTER_EXPORT int gd_raster_abi(void);
GD_RASTER_EXPORT int gd_raster_render(gd_raster_job *job);

int gd_raster_abi(void)
{
    return GD_RASTER_ABI;
}

static int render_fail(gd_raster_job *job, GError *ge)
{
    snprintf(job->why, sizeof job->why, "librsvg cannot render the figure: %s",
             ge ? ge->message : "(no reason given)");
    if (ge) g_error_free(ge);
    return GD_RASTER_ERENDER;
}

static cairo_status_t to_file(void *closure, const unsigned char *data, unsigned int length)
{
    gd_raster_job *job = closure;
    errno = 0;
    if (fwrite(data, 1, length, job->out) == length) return CAIRO_STATUS_SUCCESS;
    if (!job->write_errno) job->write_errno = errno ? errno : EIO;
    return CAIRO_STATUS_WRITE_ERROR;
}

static int write_fail(gd_raster_job *job, const char *what, cairo_status_t cs)
{
    if (!job->write_errno) { /* cairo's own failure, not the stream's */
        snprintf(job->why, sizeof job->why, "cairo cannot make the %s: %s", what,
                 cairo_status_to_string(cs));
        return GD_RASTER_ENOMEM;
    }
    snprintf(job->why, sizeof job->why, "cannot write the %s: %s", what,
             strerror(job->write_errno));
    return GD_RASTER_EWRITE;
}

/* An SVG parsed; *w, *h: its size in SVG pixels. */
static RsvgHandle *load(const gd_raster_job *job, int i, double *w, double *h, GError **ge)
{
    RsvgHandle *hd = rsvg_handle_new_from_data((const guint8 *)job->svg[i], job->len[i], ge);
    if (!hd) return NULL;
    if (!rsvg_handle_get_intrinsic_size_in_pixels(hd, w, h)) *w = *h = 0;
    return hd;
}

enum { TALL = 8000, CAIRO_MAX = 32000 }; /* SVG pixels; cairo's limit is 32767 */

static int write_png(gd_raster_job *job)
{
    GError *ge = NULL;
    double w, h;
    RsvgHandle *hd = load(job, 0, &w, &h, &ge);
    if (!hd) return render_fail(job, ge);
    /* twice the pixels for a figure; a long document at its own size, which keeps it
     * to about 1 MB and a second */
    double scale = h > TALL ? 1 : 2;
    if (h * scale > CAIRO_MAX) scale = CAIRO_MAX / h;
    if (w * scale > CAIRO_MAX) scale = CAIRO_MAX / w;
    cairo_surface_t *sf = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, (int)(w * scale + 0.5),
                                                     (int)(h * scale + 0.5));
    int st = GD_RASTER_OK;
    if (cairo_surface_status(sf) != CAIRO_STATUS_SUCCESS) {
        st = write_fail(job, "PNG image", cairo_surface_status(sf));
    } else {
        cairo_t *cr = cairo_create(sf);
        cairo_scale(cr, scale, scale);
        RsvgRectangle vp = {0, 0, w, h};
        if (!rsvg_handle_render_document(hd, cr, &vp, &ge)) st = render_fail(job, ge);
        cairo_destroy(cr);
        cairo_status_t cs;
        if (!st &&
            (cs = cairo_surface_write_to_png_stream(sf, to_file, job)) != CAIRO_STATUS_SUCCESS)
            st = write_fail(job, "PNG", cs);
    }
    cairo_surface_destroy(sf);
    g_object_unref(hd);
    return st;
}

static int write_pdf(gd_raster_job *job)
{
    cairo_surface_t *sf = cairo_pdf_surface_create_for_stream(to_file, job, 960, 1360);
    cairo_pdf_surface_set_metadata(sf, CAIRO_PDF_METADATA_TITLE, job->title ? job->title : "");
    cairo_pdf_surface_set_metadata(sf, CAIRO_PDF_METADATA_CREATOR, "geardyn");
    int st = GD_RASTER_OK;
    for (int i = 0; i < job->npages && !st; i++) {
        GError *ge = NULL;
        double w, h;
        RsvgHandle *hd = load(job, i, &w, &h, &ge);
        if (!hd) {
            st = render_fail(job, ge);
            break;
        }
        cairo_pdf_surface_set_size(sf, w, h);
        cairo_t *cr = cairo_create(sf);
        RsvgRectangle vp = {0, 0, w, h};
        if (!rsvg_handle_render_document(hd, cr, &vp, &ge)) st = render_fail(job, ge);
        cairo_show_page(cr);
        cairo_destroy(cr);
        g_object_unref(hd);
    }
    cairo_surface_finish(sf);
    if (!st && cairo_surface_status(sf) != CAIRO_STATUS_SUCCESS)
        st = write_fail(job, "PDF", cairo_surface_status(sf));
    cairo_surface_destroy(sf);
    return st;
}

int gd_raster_render(gd_raster_job *job)
{
    job->write_errno = 0;
    job->why[0] = '\0';
    if (job->npages < 1 || (!job->pdf && job->npages != 1)) {
        snprintf(job->why, sizeof job->why, "%d pages for a %s", job->npages,
                 job->pdf ? "PDF" : "PNG");
        return GD_RASTER_ERENDER;
    }
    return job->pdf ? write_pdf(job) : write_png(job);
}
