/* The contract between libgeardyn (raster.c) and its PNG/PDF plugin geardyn-raster.so
 * (plugins/raster/render.c). librsvg and cairo pull ~45 shared libraries (ICU, pango,
 * fontconfig, X11) into a process, so they live in the plugin, which the library loads
 * with dlopen on the first PNG or PDF it writes (issue 35 item 1). The library makes the
 * SVG of each page; the plugin only renders SVG onto a cairo surface and streams it out.
 * The plugin links neither libgeardyn nor anything of it: this header is all they share,
 * and GD_RASTER_ABI changes whenever gd_raster_job does. */
#ifndef GD_PLOT_RASTER_ABI_H
#define GD_PLOT_RASTER_ABI_H
#include <stddef.h>
#include <stdio.h>

#define GD_RASTER_ABI 1
#define GD_RASTER_PLUGIN_NAME "geardyn-raster.so"

enum {
    GD_RASTER_OK = 0,
    GD_RASTER_ERENDER = 1, /* librsvg could not parse or draw an SVG (why says what) */
    GD_RASTER_EWRITE = 2,  /* writing to out failed (write_errno says why) */
    GD_RASTER_ENOMEM = 3   /* a surface could not be made (too large, out of memory) */
};

typedef struct gd_raster_job {
    /* in */
    int pdf;                /* 0: one PNG of svg[0]; 1: a PDF, one page per SVG */
    int npages;             /* the SVG documents (1 for a PNG) */
    const char *const *svg; /* npages SVG documents, not NUL-terminated */
    const size_t *len;      /* their sizes in bytes */
    const char *title;      /* the PDF's title metadata */
    FILE *out;              /* the caller's stream; the plugin writes, never closes it */
    /* out */
    int write_errno; /* errno of the failed write (GD_RASTER_EWRITE), else 0 */
    char why[512];   /* what failed, for any status but GD_RASTER_OK */
} gd_raster_job;

/* the plugin's exported functions, found by dlsym under these names */
typedef int (*gd_raster_abi_fn)(void);                  /* "gd_raster_abi": GD_RASTER_ABI */
typedef int (*gd_raster_render_fn)(gd_raster_job *job); /* "gd_raster_render": a GD_RASTER_ code */

#endif
