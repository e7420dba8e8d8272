/* PNG and PDF plots: the document's SVG (svg.c), rendered by the plugin geardyn-raster.so
 * (plugins/raster/render.c, librsvg and cairo), which is loaded with dlopen only when a
 * PNG or PDF is written: the library itself links no image, font or PDF library (issue
 * 35 item 1). The contract is raster_abi.h.
 * The plugin is looked for, in order: $GEARDYN_RASTER_PLUGIN (only there, when set);
 * LIBDIR/geardyn beside the installed libgeardyn.so, or beside an installed program that
 * linked libgeardyn.a (BINDIR/../LIBDIR/geardyn); the folder of libgeardyn.so or of the
 * program itself (the build tree, where the plugin is built beside them).
 * The SVG drawn is the document's without its numbers and with its curves thinned to the
 * resolution (pl_write_svg_raster): librsvg refuses a 100 000-point curve (issue 38 M8).
 * PDF: one page per section, a section taller than an A4-shaped page split between its
 * panels onto pages of their own, so a figure is never cut. */
#define _POSIX_C_SOURCE 200809L /* open_memstream */
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "plot/plot_impl.h"
#include "plot/raster_abi.h"

/* The SVG of a document in memory. */
static gd_status svg_bytes(const gd_plot *p, char **buf, size_t *len, gd_error *err)
{
    *buf = NULL;
    *len = 0;
    FILE *m = open_memstream(buf, len);
    if (!m) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    gd_status st = pl_write_svg_raster(p, m, err);
    if (fclose(m) != 0 && !st) st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (st) {
        free(*buf);
        *buf = NULL;
    }
    return st;
}

/* Opens the plugin (RTLD_NODELETE: librsvg's GLib types cannot be unloaded, so the
 * plugin stays mapped once loaded and a later dlopen only counts a reference; the
 * library keeps no handle of its own). NULL with *why, *tried filled when absent. */
static void *plugin_open(char *tried, size_t tried_size, char *why, size_t why_size)
{
    char dir[1024], cand[4][1200];
    int n = 0;
    const char *env = getenv("GEARDYN_RASTER_PLUGIN");
    if (env && *env) {
        snprintf(cand[n++], sizeof cand[0], "%s", env);
    } else if (pl_self_dir(dir, sizeof dir)) {
        snprintf(cand[n++], sizeof cand[0], "%s/geardyn/%s", dir, GD_RASTER_PLUGIN_NAME);
        /* a program in BINDIR that linked libgeardyn.a (not when dir is LIBDIR already) */
        char up[1200], *lib;
        snprintf(up, sizeof up, "%s/%s", dir, GD_BIN_TO_LIB);
        if ((lib = realpath(up, NULL)) && strcmp(lib, dir))
            snprintf(cand[n++], sizeof cand[0], "%s/geardyn/%s", lib, GD_RASTER_PLUGIN_NAME);
        free(lib);
        snprintf(cand[n++], sizeof cand[0], "%s/%s", dir, GD_RASTER_PLUGIN_NAME);
    }
    size_t used = 0;
    tried[0] = why[0] = '\0';
    for (int i = 0; i < n; i++) {
        void *h = dlopen(cand[i], RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
        if (h) {
            gd_raster_abi_fn abi;
            *(void **)&abi = dlsym(h, "gd_raster_abi");
            if (abi && abi() == GD_RASTER_ABI && dlsym(h, "gd_raster_render")) return h;
            snprintf(why, why_size, "%.400s is from another version of geardyn (ABI %d, not %d)",
                     cand[i], abi ? abi() : -1, GD_RASTER_ABI);
            dlclose(h);
        } else if (!why[0] || access(cand[i], F_OK) == 0) {
            /* the reason of a file that exists (a missing library of its own) wins */
            const char *e = dlerror();
            snprintf(why, why_size, "%s", e ? e : "dlopen failed");
        }
        if (used < tried_size)
            used += (size_t)snprintf(tried + used, tried_size - used, "%s%s", used ? ", " : "",
                                     cand[i]);
    }
    if (!n) snprintf(why, why_size, "cannot find the library's own folder");
    return NULL;
}

static gd_status missing(const char *path, int pdf, const char *tried, const char *why,
                         gd_error *err)
{
    const char *env = getenv("GEARDYN_RASTER_PLUGIN");
    return gd_error_set(
        err, GD_EIO, path, 0, 0, "--plot",
        env && *env ? "set GEARDYN_RASTER_PLUGIN to the path of " GD_RASTER_PLUGIN_NAME
                      ", or unset it; or write FILE.svg or FILE.html"
                    : "build geardyn with librsvg2-dev and libcairo2-dev installed "
                      "(scripts/install-deps.sh) and 'make install', or set "
                      "GEARDYN_RASTER_PLUGIN to the path of " GD_RASTER_PLUGIN_NAME
                      "; or write FILE.svg or FILE.html",
        "%s plots need the plugin " GD_RASTER_PLUGIN_NAME ", which cannot be loaded (tried %s): %s",
        pdf ? "PDF" : "PNG", tried[0] ? tried : "nothing", why);
}

gd_status pl_raster_check(const char *path, int pdf, gd_error *err)
{
    char tried[2048], why[600];
    void *h = plugin_open(tried, sizeof tried, why, sizeof why);
    if (!h) return missing(path, pdf, tried, why, err);
    dlclose(h);
    return GD_OK;
}

/* The height of a page at most (an A4 page's shape at the SVG's 960 px width). */
enum { PAGE_MAX = 1360 };

/* The SVG of every page: one section, or a run of its panels, per page. */
static gd_status pdf_pages(const gd_plot *p, char ***svg, size_t **len, int *npages, gd_error *err)
{
    int cap = 0;
    *svg = NULL;
    *len = NULL;
    *npages = 0;
    gd_status st = GD_OK;
    gd_plot page = *p;
    for (int i = 0; i < p->nsections && !st; i++) {
        const pl_section *s = &p->sections[i];
        int k0 = 0;
        do {
            pl_section part = *s;
            double used = 0;
            int k1 = k0;
            while (k1 < s->npanels) {
                double ph = pl_svg_panel_height(&s->panels[k1], 1);
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
            if (*npages == cap) {
                cap = cap ? 2 * cap : 8;
                char **s2 = realloc(*svg, (size_t)cap * sizeof **svg);
                if (s2) *svg = s2;
                size_t *l2 = realloc(*len, (size_t)cap * sizeof **len);
                if (l2) *len = l2;
                if (!s2 || !l2) {
                    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
                    break;
                }
            }
            st = svg_bytes(&page, &(*svg)[*npages], &(*len)[*npages], err);
            if (!st) ++*npages;
            k0 = k1;
        } while (k0 < s->npanels && !st);
    }
    return st;
}

gd_status pl_write_raster(const gd_plot *p, const char *path, FILE *f, int pdf, gd_error *err)
{
    char tried[2048], why[600];
    void *h = plugin_open(tried, sizeof tried, why, sizeof why);
    if (!h) return missing(path, pdf, tried, why, err);
    gd_raster_render_fn render;
    *(void **)&render = dlsym(h, "gd_raster_render");
    char **svg = NULL;
    size_t *len = NULL;
    int npages = 0;
    gd_status st;
    if (pdf) {
        st = pdf_pages(p, &svg, &len, &npages, err);
    } else {
        svg = malloc(sizeof *svg);
        len = malloc(sizeof *len);
        st = svg && len ? svg_bytes(p, svg, len, err)
                        : gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        npages = !st;
    }
    if (!st) {
        gd_raster_job job = {.pdf = pdf,
                             .npages = npages,
                             .svg = (const char *const *)svg,
                             .len = len,
                             .title = p->title,
                             .out = f};
        int rc = render(&job);
        if (rc == GD_RASTER_EWRITE) {
            errno = job.write_errno;
            st = gd_error_set(err, GD_EIO, path, 0, 0, "--plot", "check the free space", "%s",
                              job.why);
        } else if (rc != GD_RASTER_OK) {
            st = gd_error_set(err, rc == GD_RASTER_ENOMEM ? GD_ENOMEM : GD_EIO, path, 0, 0,
                              "--plot", "write FILE.svg or FILE.html instead", "%s", job.why);
        }
    }
    for (int i = 0; i < npages; i++)
        free(svg[i]);
    free(svg);
    free(len);
    dlclose(h);
    return st;
}
