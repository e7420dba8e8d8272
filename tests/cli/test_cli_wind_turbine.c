/* examples/wind_turbine_gearbox.yaml (after the NREL GRC 750 kW gearbox, [Oyague2011]) against
 * hand computations: the speed ratios from the teeth, the mesh frequencies of the three stages,
 * and the lowest torsional frequency against an independent two-inertia model of the train. */
#include "cli_support.h"
#include "harness.h"

#define WT "examples/wind_turbine_gearbox.yaml"

/* planetary stage with the ring held, carrier in, sun out: 1 + Z_r / Z_s; then 82 / 23 and
 * 88 / 22 (external meshes reverse the sense) */
static const double R_SUN = 1.0 + 99.0 / 21.0, R_INT = -(1.0 + 99.0 / 21.0) * 82.0 / 23.0,
                    R_HS = (1.0 + 99.0 / 21.0) * 82.0 / 23.0 * 88.0 / 22.0;
static const double RPM = 22.0; /* the rotor (carrier) speed of the file */

static double shaft_ratio(const cJSON *o, const char *name)
{
    const cJSON *sh;
    cJSON_ArrayForEach(
        sh, cJSON_GetObjectItemCaseSensitive(
                o, "shafts")) if (!strcmp(jstr(sh, "name"), name)) return jnum(sh, "speed_ratio");
    return NAN;
}

TEST(ratios_follow_the_teeth)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "check " WT);
    REQUIRE(o);
    CHECK_REL(shaft_ratio(o, "sun_shaft"), R_SUN, 1e-9);
    CHECK_REL(shaft_ratio(o, "intermediate_shaft"), R_INT, 1e-9);
    CHECK_REL(shaft_ratio(o, "hs_shaft"), R_HS, 1e-9);
    CHECK_REL(R_HS, 81.491, 1e-5); /* 81.491 */
    /* planets: (w_p - w_c) Z_p = -(w_s - w_c) Z_s, per unit carrier speed */
    CHECK_REL(shaft_ratio(o, "lss.planet1"), 1.0 - (R_SUN - 1.0) * 21.0 / 39.0, 1e-9);
    const cJSON *set = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "planetary_sets"), 0);
    REQUIRE(set);
    const cJSON *per = cJSON_GetObjectItemCaseSensitive(set, "speed_per_input");
    CHECK_REL(jnum(per, "carrier"), 21.0 / 120.0, 1e-12);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(set, "assembles")));
    /* the planetary mesh: Z_r |w_r - w_c| = 99 per carrier revolution, 36.3 Hz at 22 rpm */
    CHECK_REL(jnum(set, "mesh_order"), 99.0, 1e-12);
    CHECK_REL(jnum(set, "mesh_frequency_hz"), 99.0 * RPM / 60.0, 1e-9);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* The parallel stages' mesh orders in the Campbell diagram: 82 |w_sun| and 88 |w_int| per
 * unit reference speed, i.e. 171.8 Hz and 657.4 Hz at 22 rpm. */
TEST(parallel_mesh_frequencies)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "campbell " WT " --speeds 0:30rpm:3 --modes 4 --threads 1");
    REQUIRE(o);
    int seen_int = 0, seen_hs = 0;
    const cJSON *c;
    cJSON_ArrayForEach(c, cJSON_GetObjectItemCaseSensitive(o, "critical_speeds"))
    {
        const char *order = jstr(c, "order");
        if (contains(order, "mesh intermediate")) {
            CHECK_REL(jnum(c, "order_value"), 82.0 * R_SUN, 1e-9);
            seen_int = 1;
        }
        if (contains(order, "mesh high_speed")) {
            CHECK_REL(jnum(c, "order_value"), 88.0 * fabs(R_INT), 1e-9);
            seen_hs = 1;
        }
    }
    CHECK(seen_int && seen_hs);
    CHECK_REL(82.0 * R_SUN * RPM / 60.0, 171.81, 1e-4);
    CHECK_REL(88.0 * fabs(R_INT) * RPM / 60.0, 657.36, 1e-4);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* Polar inertia of a solid steel shaft (density 7850) of diameter d, length L. */
static double shaft_ip(double d, double L)
{
    return 7850.0 * M_PI * pow(d, 4) * L / 32.0;
}

/* Torsional stiffness G J / L of a solid steel shaft (E 210 GPa, poisson 0.3). */
static double shaft_kt(double d, double L)
{
    return 210e9 / 2.6 * M_PI * pow(d, 4) / 32.0 / L;
}

/* The lowest mode, the whole train swinging on the generator's electrical stiffness, from an
 * independent two-inertia model at the generator's speed: inertia 1 every body of the train
 * (rotor, shafts, gears, planets spinning and orbiting) reflected by its speed ratio squared,
 * inertia 2 the generator, between them the shafts' torsion G J / L in series (meshes rigid)
 * and the coupling, the electrical stiffness to ground. */
TEST(lowest_torsional_mode_against_a_two_inertia_model)
{
    double g2 = R_HS * R_HS, rs = R_SUN / R_HS, ri = R_INT / R_HS;
    double rp = (1.0 - (R_SUN - 1.0) * 21.0 / 39.0) / R_HS, rc = 1.0 / R_HS;
    double J1 = (3.2e5 + 60.0 + shaft_ip(0.4, 1.2)) / g2 +
                (0.36 + 38.0 + shaft_ip(0.16, 0.8)) * rs * rs +
                (0.25 + 4.4 + shaft_ip(0.18, 0.6)) * ri * ri + 0.021 + shaft_ip(0.11, 0.6) +
                3.0 * (3.98 * rp * rp + 163.0 * 0.302589 * 0.302589 * rc * rc);
    double J2 = 25.0, ke = 2000.0;
    double k =
        1.0 / (g2 / shaft_kt(0.4, 1.2) + 1.0 / (shaft_kt(0.16, 0.6) * rs * rs) +
               1.0 / (shaft_kt(0.18, 0.3) * ri * ri) + 1.0 / shaft_kt(0.11, 0.45) + 1.0 / 2e5);
    /* det(K - w^2 M) = J1 J2 w^4 - (J1 (k + ke) + J2 k) w^2 + k ke */
    double a = J1 * J2, b = -(J1 * (k + ke) + J2 * k), c = k * ke;
    double w2 = (-b - sqrt(b * b - 4 * a * c)) / (2 * a), f = sqrt(w2) / (2 * M_PI);
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "modal " WT " --modes 2 --speed 0");
    REQUIRE(o);
    const cJSON *m1 = cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "modes"), 0);
    REQUIRE(m1);
    /* 0.8017 Hz against 0.8035 Hz: the rest is the meshes' and bearings' compliance, which
     * the two-inertia model leaves out */
    CHECK_REL(jnum(m1, "frequency_hz"), f, 5e-3);
    CHECK(f > 0.79 && f < 0.82);
    cJSON_Delete(o);
    scratch_close(&s);
}

static int count_of(const char *text, const char *word)
{
    int n = 0;
    for (const char *at = strstr(text, word); at; at = strstr(at + 1, word))
        n++;
    return n;
}

/* The report of a planetary model: the set seen along its axis in the model section and each
 * mode's class in the modal table, for Lin & Parker's N = 4 set: 20 elastic modes, 5 rotational
 * (the sixth of their Table 2 is the rigid-body mode), 6 translational pairs, N - 3 = 1 planet
 * mode at each of 3 frequencies. */
TEST(report_draws_the_set_and_lists_classes)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[512];
    snprintf(path, sizeof path, "%s/lp.html", s.dir);
    run_result r;
    REQUIRE(run(&s, &r, "report examples/planetary_lin_parker.yaml --threads 1 --out '%s'", path) ==
            0);
    run_free(&r);
    char *html = read_file(path);
    REQUIRE(html);
    CHECK(contains(html, "planetary set 'lp' seen along its axis"));
    CHECK(contains(html, "planets (pitch circles)") && contains(html, "planet 4 at 270 deg"));
    CHECK(contains(html, "class (lp)"));
    CHECK(count_of(html, ">rotational<") == 5);
    CHECK(count_of(html, ">translational<") == 12);
    CHECK(count_of(html, ">planet<") == 3);
    CHECK(!contains(html, "cut at 3x the largest gear")); /* no disk beyond the gears here */
    free(html);
    /* the GRC rotor's solid-disk radius (6.5 m) squeezed the gearbox drawing to a blob: drawn
     * at 3x the ring's pitch radius, and the legend says so */
    snprintf(path, sizeof path, "%s/wt.html", s.dir);
    REQUIRE(run(&s, &r, "report " WT " --threads 1 --out '%s'", path) == 0);
    run_free(&r);
    REQUIRE((html = read_file(path)));
    CHECK(contains(html, "disks (solid-disk radius from J and m, cut at 3x the largest gear)"));
    free(html);
    scratch_close(&s);
}

/* planets.pin_errors_radial (docs/planetary.md): located errors, exit 2, nothing written. */
TEST(radial_pin_errors_bad_input)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_fails_cleanly(&s,
                            "static examples/planetary_lin_parker.yaml --set "
                            "'planetary_sets.lp.planets.pin_errors_radial=[1 um, 0]'",
                            "planets.pin_errors_radial: 2 pin errors for 4 planets",
                            "give one pin error per planet"));
    CHECK(run_fails_cleanly(&s,
                            "static examples/planetary_lin_parker.yaml --set "
                            "'planetary_sets.lp.planets.pin_errors_radial=[1 m, 0, 0, 0]'",
                            "pin_errors_radial[0]: pin error 1 m", "below the carrier radius"));
    scratch_close(&s);
}

/* The static study's load_sharing[k] output over a pin error (examples/studies/
 * wind_turbine_pin_error.yaml) against `geardyn static` with the same error set by --set. */
TEST(study_load_sharing_over_a_pin_error)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char dir[512], csv[600];
    snprintf(dir, sizeof dir, "%s/st", s.dir);
    run_result r;
    REQUIRE(run(&s, &r, "study examples/studies/wind_turbine_pin_error.yaml --out '%s'", dir) == 0);
    run_free(&r);
    snprintf(csv, sizeof csv, "%s/results.csv", dir);
    char *text = read_file(csv);
    REQUIRE(text);
    const char *errs[2] = {"0", "40 um"};
    int cases[2] = {0, 2};
    for (int i = 0; i < 2; i++) {
        char key[16], args[300];
        snprintf(key, sizeof key, "\n%d,", cases[i]);
        const char *row = strstr(text, key);
        REQUIRE(row);
        double e = 0, ks = 0;
        REQUIRE(sscanf(row + strlen(key), "%lf,%lf", &e, &ks) == 2);
        CHECK_ABS(e, 20e-6 * cases[i], 1e-12);
        snprintf(args, sizeof args,
                 "static " WT " --set 'planetary_sets.lss.planets.pin_errors=[%s, 0, 0]'", errs[i]);
        cJSON *o = run_json_args(&s, args);
        REQUIRE(o);
        const cJSON *set =
            cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, "planetary_sets"), 0);
        CHECK_REL(ks, jnum(set, "load_sharing_factor"), 1e-9);
        cJSON_Delete(o);
    }
    free(text);
    scratch_close(&s);
}

RUN_TESTS(T(study_load_sharing_over_a_pin_error), T(radial_pin_errors_bad_input),
          T(report_draws_the_set_and_lists_classes), T(ratios_follow_the_teeth),
          T(parallel_mesh_frequencies), T(lowest_torsional_mode_against_a_two_inertia_model))
