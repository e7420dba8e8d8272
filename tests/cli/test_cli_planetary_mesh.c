/* geardyn with a planetary set's meshes (docs/planetary.md): the phased mesh excitation as an
 * frf input on Lin & Parker's N = 4 set with Z_s = 21 (examples/planetary_phasing.yaml):
 * [Parker2000]'s rule, the suppressed classes' responses below 1e-9 of the excited class's;
 * `check` prints the meshes' phases and the geometry's contact ratios; bad inputs. */
#include "cli_support.h"
#include "harness.h"

#define PH "examples/planetary_phasing.yaml"
#define OUTS "--output sun.x --output sun.y --output sun.rz --output lp.p1.x --output lp.p1.y"

/* the largest magnitude of output k over the frequencies */
static double peak(const cJSON *o, int k)
{
    const cJSON *mg = cJSON_GetObjectItemCaseSensitive(
        cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "outputs"), k), "magnitude");
    double p = 0;
    for (int i = 0; i < cJSON_GetArraySize(mg); i++)
        p = fmax(p, cJSON_GetArrayItem(mg, i)->valuedouble);
    return p;
}

/* l Z_s mod N = 0: rotational only (the sun turns, does not translate); +-1: translational
 * only (it translates, does not turn); else planet modes only (the sun still, planets move). */
TEST(phasing_suppresses_classes)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const double rs = 38.7e-3; /* the sun's rotation as a length r_s theta */
    for (int l = 1; l <= 8; l++) {
        char args[512];
        snprintf(args, sizeof args,
                 "frf " PH " --input planetary:lp:sun_mesh:%d " OUTS " --freq 500Hz:8500Hz:5", l);
        cJSON *o = run_json_args(&s, args);
        REQUIRE(o);
        double tr = fmax(peak(o, 0), peak(o, 1)), rot = rs * peak(o, 2),
               pl = fmax(peak(o, 3), peak(o, 4));
        int c = (l * 21) % 4;
        fprintf(stderr, "  l = %d: translation %.3g m, rotation %.3g m, planet %.3g m\n", l, tr,
                rot, pl);
        if (c == 0) {
            CHECK(rot > 1e-12 && tr < 1e-9 * rot);
        } else if (c == 1 || c == 3) {
            CHECK(tr > 1e-12 && rot < 1e-9 * tr);
        } else {
            CHECK(pl > 1e-12 && tr < 1e-9 * pl && rot < 1e-9 * pl);
        }
        cJSON_Delete(o);
    }
    scratch_close(&s);
}

TEST(check_prints_phases_and_contact_ratios)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "check " PH);
    CHECK(r.code == 0);
    CHECK(contains(r.out, "phases 0.0000 0.2500 0.5000 0.7500"));
    run_free(&r);
    run(&s, &r, "check examples/planetary_mesh_laws.yaml");
    CHECK(r.code == 0);
    CHECK(contains(r.out, "contact ratio"));
    CHECK(contains(r.out, "law: TVMS, backlash"));
    CHECK(contains(r.out, "phases 0.0000 0.6667 0.3333"));
    if (r.code) show(&r);
    run_free(&r);
    cJSON *o = run_json_args(&s, "check examples/planetary_mesh_laws.yaml");
    REQUIRE(o);
    const cJSON *set = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "planetary_sets"), 0);
    const cJSON *ms = cJSON_GetObjectItemCaseSensitive(set, "meshes");
    REQUIRE(cJSON_GetArraySize(ms) == 2);
    double eps = jnum(cJSON_GetArrayItem(ms, 0), "contact_ratio");
    CHECK(eps > 1.4 && eps < 2.0);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* examples/planetary_phasing.yaml's set with more keys (%s) */
static void write_bad(scratch *s, const char *more, char *path, size_t size)
{
    char *base = read_file(PH), text[8192];
    snprintf(text, sizeof text, "%s%s", base ? base : "", more);
    free(base);
    snprintf(path, size, "%s/bad.yaml", s->dir);
    write_file(path, text);
}

/* examples/planetary_mesh_laws.yaml with `from` replaced by `to`: refused with `what` */
static int geometry_refused(scratch *s, const char *from, const char *to, const char *what)
{
    char *base = read_file("examples/planetary_mesh_laws.yaml"), text[8192], path[300], args[400];
    char *at = base ? strstr(base, from) : NULL;
    if (!at) {
        free(base);
        return 0;
    }
    snprintf(text, sizeof text, "%.*s%s%s", (int)(at - base), base, to, at + strlen(from));
    free(base);
    snprintf(path, sizeof path, "%s/geo.yaml", s->dir);
    write_file(path, text);
    snprintf(args, sizeof args, "check %s", path);
    return run_refused(s, what, "geo.yaml:", args);
}

TEST(bad_inputs)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    static const char *const BAD[][2] = {
        {"    geometry: {module: 3 mm, face_width: 30 mm}\n",
         "pressure_angle given with the tooth geometry"},
        {"    mesh_phases: {sun: [0, 0.25, 0.5]}\n", "3 phases for 4 planets"},
        {"    mesh_phases: {sun: [0, 0.25, 0.5, 1.2]}\n", "mesh phase 1.2 is not in [0, 1)"},
        {"    mesh_phases: {sun_ring: 1.5}\n", "sun-ring phase 1.5 is not in [0, 1)"},
        {"    mesh_laws: {sun: {backlash: {gap: -1 um}}}\n", "gap"},
        {"    mesh_laws: {sun: {stiffness: 3}}\n", "stiffness"},
    };
    for (size_t i = 0; i < sizeof BAD / sizeof BAD[0]; i++) {
        char path[300], args[400];
        write_bad(&s, BAD[i][0], path, sizeof path);
        snprintf(args, sizeof args, "check %s", path);
        CHECK(run_refused(&s, BAD[i][1], "bad.yaml:", args));
    }
    /* with the geometry: a sun shift that moves only the sun-planet centre distance; a
       carrier radius given too */
    CHECK(geometry_refused(&s, "face_width: 30 mm}",
                           "face_width: 30 mm, profile_shift: {sun: 0.3}}", "centre distance"));
    CHECK(geometry_refused(&s, "    geometry:", "    carrier_radius: 100 mm\n    geometry:",
                           "carrier radius given with the tooth geometry"));
    scratch_close(&s);
}

RUN_TESTS(T(phasing_suppresses_classes), T(check_prints_phases_and_contact_ratios), T(bad_inputs))
