/* libFuzzer harness over the other inputs a user controls (`make fuzz
 * FUZZ_TARGET=fuzz_inputs`): the first byte picks what the rest is.
 *   0  a study file (docs/studies.md), its model `model.yaml` (the Chen gear pair) beside
 *      it: it must load or fail with a located error; a modal study's first case runs
 *   1  `--set` assignments, one per line, on the Chen gear pair: the model must load
 *      or fail located, and build and solve its modes when it loads
 *   2  a gear-pair file (docs/mesh-stiffness.md): geometry read, derived and, when it
 *      is valid, its mesh stiffness computed on a coarse grid
 *   3  periodic options and speeds as raw numbers (any bits: NaN, inf, 1e-300, INT_MAX)
 *      on the damped Mathieu pair: refused with GD_EINPUT or run; valid but costly
 *      settings (more than 8 harmonics, adaptive harmonics without a cap of at most 8,
 *      1024 samples or steps, 4 speeds, 30 Newton iterations) are skipped: the slowest allowed
 * before took 18 s of the 20 s limit No crash, undefined behaviour (float-to-int casts included),
 * leak or hang is allowed. The files go into a private temporary folder made on the first call (the
 * study file reader takes a path). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "geardyn/mesh_stiffness.h"
#include "geardyn/modal.h"
#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/periodic.h"
#include "geardyn/study.h"
#include "geardyn/system.h"
#include "geardyn/transient_model.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#ifndef FUZZ_SOURCE_DIR
#define FUZZ_SOURCE_DIR "."
#endif

static char g_dir[256];

static int copy_file(const char *from, const char *to)
{
    FILE *a = fopen(from, "rb"), *b = a ? fopen(to, "wb") : NULL;
    char buf[8192];
    size_t n;
    int ok = a && b;
    while (ok && (n = fread(buf, 1, sizeof buf, a)) > 0)
        ok = fwrite(buf, 1, n, b) == n;
    if (a) fclose(a);
    if (b && fclose(b)) ok = 0;
    return ok;
}

static const char *dir(void)
{
    if (!g_dir[0]) {
        snprintf(g_dir, sizeof g_dir, "/tmp/gd_fuzz_inputs_XXXXXX");
        if (!mkdtemp(g_dir)) abort();
        char to[300];
        snprintf(to, sizeof to, "%s/model.yaml", g_dir);
        if (!copy_file(FUZZ_SOURCE_DIR "/examples/chen1998_gear_pair.yaml", to)) abort();
        snprintf(to, sizeof to, "%s/mathieu.yaml", g_dir);
        if (!copy_file(FUZZ_SOURCE_DIR "/tests/plot/mathieu_pair.yaml", to)) abort();
    }
    return g_dir;
}

static void write_text(const char *path, const uint8_t *data, size_t size)
{
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size && fwrite(data, 1, size, f) != size) abort();
    fclose(f);
}

static void modes_of(gd_model *m)
{
    gd_error err;
    gd_system *sys = NULL;
    if (gd_system_build(m, &sys, &err) == GD_OK) {
        if (sys->ndof <= 60) {
            gd_modal_options opt;
            gd_modal_options_init(&opt);
            opt.speed = m->speed;
            gd_modal_result *res = NULL;
            if (gd_modal_solve(sys, &opt, &res, &err) == GD_OK) gd_modal_free(res);
        }
        gd_system_free(sys);
    }
}

static void study(const uint8_t *data, size_t size)
{
    char path[300];
    snprintf(path, sizeof path, "%s/study.yaml", dir());
    write_text(path, data, size);
    gd_study *s = NULL;
    gd_error err;
    if (gd_study_load(path, &s, &err) != GD_OK) return;
    if (!strcmp(gd_study_analysis(s), "modal") && gd_study_ncases(s) > 0) {
        gd_study_row row;
        if (gd_study_row_init(s, &row, &err) == GD_OK) {
            gd_study_run_case(s, 0, &row);
            char line[4096];
            gd_study_format_row(s, &row, line, sizeof line);
            gd_study_row_free(&row);
        }
    }
    gd_study_free(s);
}

static void sets(const uint8_t *data, size_t size)
{
    static gd_model_source *src;
    gd_error err;
    if (!src) {
        char path[300];
        snprintf(path, sizeof path, "%s/model.yaml", dir());
        if (gd_model_source_load(path, &src, &err)) abort();
    }
    char *text = malloc(size + 1);
    if (!text) return;
    memcpy(text, data, size);
    text[size] = '\0';
    const char *set[16];
    int n = 0;
    for (char *p = text; *p && n < 16;) {
        char *nl = strchr(p, '\n');
        if (nl) *nl = '\0';
        set[n++] = p;
        if (!nl) break;
        p = nl + 1;
    }
    /* a size limit asked for is allowed to be huge */
    int skip = 0;
    for (int i = 0; i < n; i++)
        skip |= strstr(set[i], "limits") != NULL;
    if (!skip) {
        gd_load_options opt = {n, set};
        gd_model *m = NULL;
        for (int i = 0; i < n; i++) {
            const char *eq = strchr(set[i], '=');
            char path[512];
            if (!eq || (size_t)(eq - set[i]) >= sizeof path) continue;
            memcpy(path, set[i], (size_t)(eq - set[i]));
            path[eq - set[i]] = '\0';
            int adds = 0;
            gd_model_source_check_path(src, path, &adds, &err);
        }
        if (gd_model_source_model(src, &opt, &m, &err) == GD_OK) {
            modes_of(m);
            gd_model_free(m);
        }
    }
    free(text);
}

static void gear_pair(const uint8_t *data, size_t size)
{
    char path[300];
    snprintf(path, sizeof path, "%s/pair.yaml", dir());
    write_text(path, data, size);
    gd_gear_pair_geometry g;
    gd_tvms_options t;
    char name[64];
    gd_error err;
    if (gd_gear_pair_load(path, NULL, NULL, &g, &t, name, sizeof name, &err) != GD_OK) return;
    gd_gear_pair_derived d;
    if (gd_gear_pair_derive(&g, &d, &err) != GD_OK) return;
    t.points = t.points > 32 ? 32 : t.points;
    t.slices = t.slices > 8 ? 8 : t.slices;
    gd_tvms_result *r = NULL;
    if (gd_tvms_compute(&g, &t, &r, &err) == GD_OK) {
        (void)gd_tvms_eval(r, 0.1);
        gd_tvms_free(r);
    }
}

/* An int and a double from the input (0 when it runs out): any bit pattern. */
static int take_int(const uint8_t **p, size_t *n)
{
    int32_t v = 0;
    if (*n >= 4) {
        memcpy(&v, *p, 4);
        *p += 4;
        *n -= 4;
    }
    return (int)v;
}

static double take_double(const uint8_t **p, size_t *n)
{
    double v = 0;
    if (*n >= 8) {
        memcpy(&v, *p, 8);
        *p += 8;
        *n -= 8;
    }
    return v;
}

static void periodic(const uint8_t *data, size_t size)
{
    static gd_model *m;
    static gd_system *sys;
    static gd_transient_model *tm;
    gd_error err;
    if (!m) {
        char path[300];
        snprintf(path, sizeof path, "%s/mathieu.yaml", dir());
        if (gd_model_load(path, &m, &err) || gd_system_build(m, &sys, &err) ||
            gd_transient_model_build(sys, &tm, &err))
            abort();
    }
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = take_int(&data, &size);
    o.subharmonic = take_int(&data, &size);
    o.samples = take_int(&data, &size);
    o.monodromy_steps = take_int(&data, &size);
    o.max_iter = take_int(&data, &size);
    o.adaptive = take_int(&data, &size) & 1;
    o.max_harmonics = take_int(&data, &size);
    o.stability = take_int(&data, &size) & 1;
    o.method = (gd_per_method)(take_int(&data, &size) & 1);
    o.tol = take_double(&data, &size);
    o.harmonic_tol = take_double(&data, &size);
    int nv = take_int(&data, &size);
    /* adaptive H with no cap (0: memory decides) may legitimately raise H into the
     * thousands: valid, and too slow for the 20 s limit (a 21 s input at a harmonic
     * tolerance of 1e-290) */
    if (o.harmonics > 8 || o.subharmonic > 4 || o.samples > 1024 || o.monodromy_steps > 1024 ||
        o.max_iter > 30 || o.max_harmonics > 8 || (o.adaptive && o.max_harmonics == 0) || nv > 4 ||
        nv < 0)
        return;
    double v[4];
    for (int i = 0; i < nv; i++)
        v[i] = take_double(&data, &size);
    gd_periodic_result *r = NULL;
    if (gd_periodic_run(sys, &tm->spec, NULL, v, nv, &o, NULL, 0, &r, &err) == GD_OK)
        gd_periodic_result_free(r);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    switch (data[0] & 3) {
    case 0:
        study(data + 1, size - 1);
        break;
    case 1:
        sets(data + 1, size - 1);
        break;
    case 2:
        gear_pair(data + 1, size - 1);
        break;
    default:
        periodic(data + 1, size - 1);
        break;
    }
    return 0;
}
