/* PNG and PDF through the plugin geardyn-raster.so (src/plot/raster.c, issue 35 item 1)
 * and figures of many points (issue 38 M8): the thinning of curves to the resolution
 * (pl_decimate) keeps every dropped point within one cell of the line drawn; a figure of
 * six 100 000-point curves (which librsvg refused to parse: "the write failed / check
 * the free space") is written as PNG and PDF; a missing or foreign plugin is a located
 * error (exit 2, the plot path, --plot, the plugin's name and the override) that writes
 * nothing. */
#define _POSIX_C_SOURCE 200809L /* open_memstream, setenv */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "geardyn/plot.h"
#include "harness.h"
#include "plot/plot_impl.h"

/* distance from (px, py) to the segment a-b */
static double seg_dist(double px, double py, double ax, double ay, double bx, double by)
{
    double dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
    double t = l2 > 0 ? ((px - ax) * dx + (py - ay) * dy) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    return hypot(px - ax - t * dx, py - ay - t * dy);
}

/* pl_decimate on three curves of 200 000 points in a 630 px wide frame: a resonance
 * peak (smooth, monotonic x), a noisy signal (every column full of ups and downs) and a
 * Nyquist circle (x not monotonic). Every point dropped lies within one cell of the
 * polyline through the kept ones: checked against the two kept points around it and
 * the segments between the kept points of its own column, which is where the proof in
 * decimate.c puts it (an independent distance computation, not the decimation's own
 * bookkeeping). At most 4 points per column change; the first and last always kept. */
TEST(decimation_keeps_the_drawing)
{
    enum { N = 200000 };
    double *x = malloc(N * sizeof *x), *y = malloc(N * sizeof *y);
    int *keep = malloc(N * sizeof *keep);
    REQUIRE(x && y && keep);
    const double cell = 0.25;
    for (int c = 0; c < 3; c++) {
        unsigned seed = 12345;
        for (int i = 0; i < N; i++) {
            double s = (double)i / (N - 1);
            seed = seed * 1103515245u + 12345u;
            double noise = ((seed >> 8) & 0xffff) / 65535.0 - 0.5;
            if (c == 0) { /* 92 + 630 s, a peak at s = 0.3 on a 300 px tall frame */
                x[i] = 92 + 630 * s;
                y[i] = 400 - 280 / (1 + pow((s - 0.3) / 0.002, 2));
            } else if (c == 1) {
                x[i] = 92 + 630 * s;
                y[i] = 250 + 120 * noise;
            } else {
                x[i] = 400 + 150 * cos(40 * s);
                y[i] = 250 + 150 * sin(40 * s);
            }
        }
        int m = pl_decimate(x, y, N, cell, keep);
        CHECK(m > 2 && keep[0] == 0 && keep[m - 1] == N - 1);
        int changes = 1;
        for (int i = 1; i < N; i++)
            changes += floor(x[i] / cell) != floor(x[i - 1] / cell);
        CHECK(m <= 4 * changes);
        if (c < 2) CHECK(m < N / 10); /* x monotonic: far fewer than the points */
        double worst = 0;
        int k = 0; /* keep[k] <= i < keep[k + 1] */
        for (int i = 0; i < N; i++) {
            while (k + 1 < m && keep[k + 1] <= i)
                k++;
            if (keep[k] == i) continue;
            /* the segments of the kept points of i's column and the one spanning i */
            double best =
                seg_dist(x[i], y[i], x[keep[k]], y[keep[k]], x[keep[k + 1]], y[keep[k + 1]]);
            double col = floor(x[i] / cell);
            for (int a = k; a > 0 && floor(x[keep[a]] / cell) == col; a--)
                best = fmin(best, seg_dist(x[i], y[i], x[keep[a - 1]], y[keep[a - 1]], x[keep[a]],
                                           y[keep[a]]));
            for (int a = k + 1; a + 1 < m && floor(x[keep[a]] / cell) == col; a++)
                best = fmin(best, seg_dist(x[i], y[i], x[keep[a]], y[keep[a]], x[keep[a + 1]],
                                           y[keep[a + 1]]));
            worst = fmax(worst, best);
        }
        /* the bound of decimate.c: one cell (a point's own column), nothing more (with
         * the rounding of the distance computation) */
        CHECK(worst <= cell * (1 + 1e-12));
        printf("  curve %d: %d of %d points kept, farthest dropped %.3f px (cell %.2f)\n", c, m, N,
               worst, cell);
    }
    free(x), free(y), free(keep);
}

/* The document of issue 38 M8's figure: 6 curves of 100 000 points on a log axis, and a
 * Nyquist panel of 100 000 markers each. */
static gd_plot *big_figure(void)
{
    enum { N = 100000 };
    gd_plot *p = NULL;
    if (gd_plot_new("many points", &p, NULL)) return NULL;
    pl_section *s = pl_section_add(p, "Frequency response");
    pl_panel *mag = pl_panel_add(p, s, PL_XY, "magnitude", "f (Hz)", "|H|");
    pl_panel *nyq = pl_panel_add(p, s, PL_XY, "Nyquist", "re", "im");
    double *f = malloc(N * sizeof *f), *a = malloc(N * sizeof *a), *b = malloc(N * sizeof *b);
    if (!s || !mag || !nyq || !f || !a || !b) {
        free(f), free(a), free(b);
        gd_plot_free(p);
        return NULL;
    }
    mag->ylog = 1;
    for (int c = 0; c < 6; c++) {
        for (int i = 0; i < N; i++) {
            f[i] = 1 + 5000.0 * i / (N - 1);
            double r = f[i] / (300 * (c + 1)), den = (1 - r * r) * (1 - r * r) + 0.0004 * r * r;
            a[i] = (1 - r * r) / den;
            b[i] = -0.02 * r / den;
        }
        char name[32];
        snprintf(name, sizeof name, "out%d", c);
        double *m = malloc(N * sizeof *m);
        if (!m) break;
        for (int i = 0; i < N; i++)
            m[i] = hypot(a[i], b[i]);
        pl_trace_add(p, mag, name, N, f, m, PL_LINES, pl_color(c));
        pl_trace_add(p, nyq, name, N, a, b, PL_LINES_MARKERS, pl_color(c));
        free(m);
    }
    free(f), free(a), free(b);
    gd_plot *out = NULL;
    return pl_done(p, &out, NULL) ? NULL : out;
}

static int png_size(const char *path, int *w, int *h)
{
    unsigned char hd[24];
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(hd, 1, sizeof hd, f) : 0;
    if (f) fclose(f);
    if (n < 24 || memcmp(hd, "\x89PNG\r\n\x1a\n", 8) || memcmp(hd + 12, "IHDR", 4)) return 0;
    *w = (hd[16] << 24) | (hd[17] << 16) | (hd[18] << 8) | hd[19];
    *h = (hd[20] << 24) | (hd[21] << 16) | (hd[22] << 8) | hd[23];
    return 1;
}

static int pdf_pages(const char *path)
{
    char cmd[512], line[256];
    snprintf(cmd, sizeof cmd, "pdfinfo '%s' 2>/dev/null", path);
    FILE *f = popen(cmd, "r");
    int pages = -1;
    while (f && fgets(line, sizeof line, f))
        sscanf(line, "Pages: %d", &pages);
    if (f && pclose(f) != 0) pages = -1;
    return pages;
}

/* issue 38 M8: the figure is written as PNG and PDF (before: exit 2, "the write failed /
 * check the free space"); the SVG librsvg parses is small (the full SVG keeps every
 * number: 6 x 2 x 100 000 of them) */
TEST(many_points_png_and_pdf)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    gd_plot *p = big_figure();
    REQUIRE(p);
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    REQUIRE(m);
    CHECK(pl_write_svg_raster(p, m, NULL) == GD_OK);
    fclose(m);
    /* the full SVG is about 40 MB; drawn at a quarter pixel, far less is left */
    CHECK(len < 4000000);
    printf("  the SVG drawn for PNG/PDF: %zu bytes\n", len);
    free(buf);
    char path[300];
    gd_error err;
    gd_error_clear(&err);
    snprintf(path, sizeof path, "%s/big.png", d.dir);
    gd_status st = gd_plot_write(p, path, NULL, &err);
    CHECK(st == GD_OK);
    if (st) printf("  %s: %s (%s)\n", err.file, err.message, err.hint);
    int w = 0, h = 0;
    CHECK(png_size(path, &w, &h) && w == 1920 && h > 1000);
    snprintf(path, sizeof path, "%s/big.pdf", d.dir);
    st = gd_plot_write(p, path, NULL, &err);
    CHECK(st == GD_OK);
    if (st) printf("  %s: %s (%s)\n", err.file, err.message, err.hint);
    CHECK(pdf_pages(path) == 1);
    CHECK(count_entries(d.dir) == 2); /* nothing else left behind */
    gd_plot_free(p);
    scratch_close(&d);
}

/* Tables in PNG and PDF (issue 35: Campbell and report PNGs 8000 to 22874 px tall): a
 * table of 2000 rows is cut at 40 in the PNG (1920 x about 2 x 1000 px: the section
 * title, 41 rows and the line that says where the rest are), while the SVG keeps all. */
TEST(long_tables_are_cut_in_png)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    gd_plot *p = NULL;
    REQUIRE(gd_plot_new("table", &p, NULL) == GD_OK);
    pl_section *s = pl_section_add(p, "critical speeds");
    pl_panel *tb = pl_panel_add(p, s, PL_TABLE, "crossings", NULL, NULL);
    REQUIRE(s && tb);
    pl_table_init(p, tb, 2000, 3);
    for (int r = 0; r <= 2000; r++)
        for (int c = 0; c < 3; c++)
            pl_cell(p, tb, r, c, "%d.%d", r, c);
    gd_plot *doc = NULL;
    REQUIRE(pl_done(p, &doc, NULL) == GD_OK);
    char path[300];
    snprintf(path, sizeof path, "%s/t.png", d.dir);
    CHECK(gd_plot_write(doc, path, NULL, NULL) == GD_OK);
    int w = 0, h = 0;
    CHECK(png_size(path, &w, &h));
    /* 2 x (40 + 48 + 40 + 20 x 42) = about 1940 px; uncut it was 2 x 40 128 (at 1x: 40 128) */
    CHECK(w == 1920 && h > 1500 && h < 2500);
    printf("  PNG of a 2000-row table: %d x %d px\n", w, h);
    snprintf(path, sizeof path, "%s/t.svg", d.dir);
    CHECK(gd_plot_write(doc, path, NULL, NULL) == GD_OK);
    char *svg = read_file(path);
    CHECK(svg && strstr(svg, ">2000.2<") && !strstr(svg, "more rows"));
    free(svg);
    char *buf = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&buf, &len);
    REQUIRE(m);
    CHECK(pl_write_svg_raster(doc, m, NULL) == GD_OK);
    fclose(m);
    CHECK(buf && strstr(buf, ">40.2<") && !strstr(buf, ">41.0<") &&
          strstr(buf, "... 1960 more rows"));
    free(buf);
    gd_plot_free(doc);
    scratch_close(&d);
}

/* The command of issue 38 M8, on the 4-DOF torsional model (the cheapest FRF: the
 * figure, not the solve, is what failed) */
TEST(frf_of_100k_points_to_png)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result r;
    run(&d, &r,
        "frf examples/kumar2011_torsional.yaml --input torque:motor --output load.rz "
        "--output gear.rz --freq 1:5000:100000 --threads 1 --plot %s/p.png",
        d.dir);
    CHECK(r.code == 0);
    if (r.code) show(&r);
    char path[300];
    snprintf(path, sizeof path, "%s/p.png", d.dir);
    int w = 0, h = 0;
    CHECK(png_size(path, &w, &h) && w == 1920);
    run_free(&r);
    scratch_close(&d);
}

/* the plugin absent (GEARDYN_RASTER_PLUGIN at a missing file) or foreign (another
 * module, without the raster functions): exit 2 before any computing, the error names
 * the plot file, --plot, the plugin and the override; no file is left */
TEST(missing_plugin_is_a_located_error)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    char hdf5[600];
    snprintf(hdf5, sizeof hdf5, "%s", GD_CLI_PATH);
    char *slash = strrchr(hdf5, '/');
    REQUIRE(slash);
    snprintf(slash + 1, sizeof hdf5 - (size_t)(slash + 1 - hdf5), "geardyn-hdf5.so");
    const char *plugins[] = {"/nonexistent/geardyn-raster.so", hdf5};
    const char *why[] = {"No such file", "another version of geardyn"};
    for (int k = 0; k < 2; k++)
        for (int pdf = 0; pdf < 2; pdf++) {
            setenv("GEARDYN_RASTER_PLUGIN", plugins[k], 1);
            char path[300];
            snprintf(path, sizeof path, "%s/fig.%s", d.dir, pdf ? "pdf" : "png");
            run_result r;
            run(&d, &r, "modal examples/chen1998_gear_pair.yaml --plot %s", path);
            CHECK(r.code == 2);
            CHECK(contains(r.err, path) && contains(r.err, "--plot"));
            CHECK(contains(r.err, pdf ? "PDF plots need the plugin geardyn-raster.so"
                                      : "PNG plots need the plugin geardyn-raster.so"));
            CHECK(contains(r.err, plugins[k]) && contains(r.err, why[k]));
            CHECK(contains(r.err, "GEARDYN_RASTER_PLUGIN"));
            CHECK(r.out[0] == '\0');          /* refused before the modes were computed */
            CHECK(count_entries(d.dir) == 2); /* stdout.txt and stderr.txt only */
            if (r.code != 2 || !contains(r.err, why[k])) show(&r);
            run_free(&r);
            /* the library's own check, as a C program calls it */
            gd_error err;
            gd_error_clear(&err);
            CHECK(gd_plot_check_path(path, NULL, &err) == GD_EIO);
            CHECK_STR(err.file, path);
            CHECK_STR(err.field, "--plot");
        }
    unsetenv("GEARDYN_RASTER_PLUGIN");
    /* and found again without the override (the build tree: beside the program) */
    gd_error err;
    gd_error_clear(&err);
    char path[300];
    snprintf(path, sizeof path, "%s/fig.png", d.dir);
    CHECK(gd_plot_check_path(path, NULL, &err) == GD_OK);
    scratch_close(&d);
}

RUN_TESTS(T(decimation_keeps_the_drawing), T(many_points_png_and_pdf),
          T(long_tables_are_cut_in_png), T(frf_of_100k_points_to_png),
          T(missing_plugin_is_a_located_error))
