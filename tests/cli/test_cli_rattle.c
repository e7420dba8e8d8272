/* `geardyn transient --rattle` and the drag laws through the CLI (docs/rattle.md) on
 * examples/rattle_pair.yaml, an idler held on its drive flank by its churning drag and
 * driven with a 2nd-order speed fluctuation at 800 rpm:
 *  - the rattle onset over the fluctuation amplitude brackets the classic threshold
 *    (the idler's inertia torque J (r1/r2) A (2W)^2 against its drag torque T_d), with
 *    T_d read off the run's own drag record: no contact loss at 1.2 mrad, rattle at 1.5;
 *  - the metrics agree with the independent contact counters of the run and the
 *    effective mass is J2 / r2^2 (the input is prescribed);
 *  - bad input exits 2 with a located message and nothing written. */
#include <math.h>

#include "cli_support.h"
#include "harness.h"

#define PAIR "examples/rattle_pair.yaml"
#define RUN "transient " PAIR " --duration 1 --from 0.5 --rattle --record law:drag2:torque"

static const cJSON *first(const cJSON *o, const char *key)
{
    return cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(o, key), 0);
}

TEST(onset_brackets_the_inertia_drag_threshold)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *lo = run_json_args(&s, RUN " --set prescribed.0.amplitude=1.2mrad");
    cJSON *hi = run_json_args(&s, RUN " --set prescribed.0.amplitude=1.5mrad");
    REQUIRE(lo && hi);
    /* the threshold from the drag the run applied (its mean over the window) */
    double Td = jnum(first(lo, "records"), "mean");
    double W2 = 2 * M_PI * 26.6667, J = 5.8e-4, ratio = 30.0 / 40.0;
    double Astar = Td / (J * ratio * W2 * W2);
    CHECK(Astar > 1.2e-3 && Astar < 1.5e-3); /* 1.229e-3 */
    CHECK_REL(Td, 0.0150, 0.01);             /* the example's stated drag */
    CHECK(jnum(first(lo, "meshes"), "contact_losses") == 0);
    CHECK(jnum(first(hi, "meshes"), "contact_losses") > 10);
    const cJSON *r = first(cJSON_GetObjectItemCaseSensitive(hi, "rattle"), "meshes");
    REQUIRE(r);
    CHECK(jnum(cJSON_GetObjectItemCaseSensitive(r, "separated_fraction"), "mean") > 0.1);
    /* the metrics' impact counts are the run's contact counters */
    CHECK(jnum(r, "drive_impacts") == jnum(first(hi, "meshes"), "drive_impacts"));
    CHECK(jnum(r, "coast_impacts") == jnum(first(hi, "meshes"), "coast_impacts"));
    /* the idler alone moves: m_e = J2 / r2^2 */
    CHECK_REL(jnum(r, "effective_mass_kg"), 5.8e-4 / (0.04 * 0.04), 1e-12);
    cJSON_Delete(lo);
    cJSON_Delete(hi);
    scratch_close(&s);
}

/* Just above the threshold the teeth part and touch again within nanoseconds (chatter at
 * grazing): CVODE stopped there with "Root found at and very near t" until a crossing
 * back into the same contact state also restarted it (src/transient/run.c). The run now
 * completes, and the chatter's impact energy is tiny against the rattle's at 3 mrad. */
TEST(grazing_onset_runs_through)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *g = run_json_args(&s, "transient " PAIR " --duration 0.5 --from 0.25 --rattle "
                                 "--set prescribed.0.amplitude=1.3mrad");
    cJSON *full = run_json_args(&s, "transient " PAIR " --duration 0.5 --from 0.25 --rattle");
    REQUIRE(g && full);
    CHECK(jnum(first(g, "meshes"), "contact_losses") > 100);
    const cJSON *rg = first(cJSON_GetObjectItemCaseSensitive(g, "rattle"), "meshes");
    const cJSON *rf = first(cJSON_GetObjectItemCaseSensitive(full, "rattle"), "meshes");
    double ig = jnum(cJSON_GetObjectItemCaseSensitive(rg, "intensity_w"), "mean");
    double ifull = jnum(cJSON_GetObjectItemCaseSensitive(rf, "intensity_w"), "mean");
    CHECK(ig > 0 && ig < 0.01 * ifull); /* measured: 6.8e-6 W against 3.6e-3 W */
    cJSON_Delete(g);
    cJSON_Delete(full);
    scratch_close(&s);
}

TEST(rattle_metrics_in_json_and_text)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, RUN);
    REQUIRE(o);
    const cJSON *r = first(cJSON_GetObjectItemCaseSensitive(o, "rattle"), "meshes");
    REQUIRE(r);
    CHECK_STR(jstr(r, "name"), "m12");
    const cJSON *sep = cJSON_GetObjectItemCaseSensitive(r, "separated_fraction");
    /* at 3 mrad (2.4 x the threshold) the idler floats most of the time */
    CHECK(jnum(sep, "mean") > 0.5 && jnum(sep, "mean") < 1.0);
    CHECK(jnum(sep, "half_width") > 0 && jnum(sep, "half_width") < 0.1);
    double nd = jnum(r, "drive_impacts"), nc = jnum(r, "coast_impacts");
    CHECK(nd > 0 && nc > 0);
    /* rates are counts over the window (0.5 s) */
    CHECK_REL(jnum(cJSON_GetObjectItemCaseSensitive(r, "drive_impacts_per_s"), "mean"), nd / 0.5,
              1e-9);
    /* the histograms hold every impact */
    const cJSON *h = cJSON_GetObjectItemCaseSensitive(r, "impact_speed_histogram");
    double sd = 0, sc = 0;
    for (int k = 0; k < 16; k++) {
        sd += cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(h, "drive"), k)->valuedouble;
        sc += cJSON_GetArrayItem(cJSON_GetObjectItemCaseSensitive(h, "coast"), k)->valuedouble;
    }
    CHECK(sd == nd && sc == nc);
    /* intensity = m_e/2 * sum v^2 / window >= m_e/2 * (nd + nc) v_rms^2 / window: equal */
    double me = jnum(r, "effective_mass_kg"), vr = jnum(r, "impact_speed_rms_m_s");
    CHECK_REL(jnum(cJSON_GetObjectItemCaseSensitive(r, "intensity_w"), "mean"),
              0.5 * me * (nd + nc) * vr * vr / 0.5, 1e-9);
    cJSON_Delete(o);
    run_result t;
    run(&s, &t, RUN);
    CHECK(t.code == 0 && contains(t.out, "rattle over 0.5 s") && contains(t.out, "m12"));
    run_free(&t);
    /* --plot: the rattle section (metrics table, impact-speed histograms) after the records */
    char svg[600];
    snprintf(svg, sizeof svg, "%s/rattle.svg", s.dir);
    run(&s, &t, RUN " --plot '%s'", svg);
    CHECK(t.code == 0);
    run_free(&t);
    char *text = read_file(svg);
    CHECK(text && contains(text, "Rattle metrics") && contains(text, "m12: impact speeds") &&
          contains(text, "coast flank"));
    free(text);
    scratch_close(&s);
}

/* examples/gearbox_neutral_rattle.yaml: five idlers with needle-bearing and churning drag
 * on one input shaft behind the clutch damper. The first idler to leave its flank is 4th
 * gear's (its drag against its inertia torque at the input's amplitude, T / |k - J_eff
 * (2W)^2 + i c 2W|, J_eff with every idler reflected: T* = 1.020 N m; the others from
 * 1.41 N m on, from their drag records at 800 rpm, docs/rattle.md); its impacts then shake
 * the input and every idler rattles. 0.95 N m: no contact loss anywhere; 1.1 N m: all. */
TEST(gearbox_onset_brackets_the_first_idler_threshold)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *base = "transient examples/gearbox_neutral_rattle.yaml --duration 1 --from 0.5 "
                       "--rattle --set excitations.loads.firing.amplitude=";
    char args[300];
    snprintf(args, sizeof args, "%s0.95", base);
    cJSON *lo = run_json_args(&s, args);
    snprintf(args, sizeof args, "%s1.1", base);
    cJSON *hi = run_json_args(&s, args);
    REQUIRE(lo && hi);
    const cJSON *ml = cJSON_GetObjectItemCaseSensitive(lo, "meshes");
    const cJSON *mh = cJSON_GetObjectItemCaseSensitive(hi, "meshes");
    REQUIRE(cJSON_GetArraySize(ml) == 5 && cJSON_GetArraySize(mh) == 5);
    for (int i = 0; i < 5; i++) {
        CHECK(jnum(cJSON_GetArrayItem(ml, i), "contact_losses") == 0);
        CHECK(jnum(cJSON_GetArrayItem(mh, i), "contact_losses") > 10);
    }
    cJSON_Delete(lo);
    cJSON_Delete(hi);
    scratch_close(&s);
}

/* --rattle-extend runs again with the window the metrics ask for until they reach
 * --rattle-precision (or the limit). */
TEST(extend_until_the_metrics_are_known)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    cJSON *o = run_json_args(&s, "transient " PAIR " --duration 1 --from 0.5 --rattle "
                                 "--rattle-precision 0.15 --rattle-extend 20s");
    REQUIRE(o);
    const cJSON *r = first(cJSON_GetObjectItemCaseSensitive(o, "rattle"), "meshes");
    REQUIRE(r);
    CHECK(jnum(r, "window_s") > 0.5 && jnum(r, "window_s") < 19.5);
    CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(r, "converged")));
    CHECK(jnum(r, "relative_half_width") <= 0.15);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* `geardyn study --plot`: the rattle map's outputs over the first parameter (speed), one
 * curve per torque amplitude: 2 x 2 cases, the figure holds both curves per output. */
TEST(study_plot_draws_the_map)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char study[600], svg[600], args[2000];
    snprintf(study, sizeof study, "%s/map.yaml", s.dir);
    snprintf(svg, sizeof svg, "%s/map.svg", s.dir);
    write_file(study, "model: " GD_SOURCE_DIR "/examples/rattle_idle.yaml\n"
                      "analysis: {type: transient, duration: 0.5, from: 0.5}\n"
                      "parameters:\n"
                      "  - {name: speed_rpm, path: speed, unit: rpm, values: [700, 900]}\n"
                      "  - {name: amp, path: excitations.loads.firing.amplitude, unit: N*m,\n"
                      "     values: [0.25, 2]}\n"
                      "outputs: [rattle_intensity, separated_fraction]\n");
    snprintf(args, sizeof args, "study '%s' --out '%s/out' --quiet --plot '%s'", study, s.dir, svg);
    run_result r;
    run(&s, &r, "%s", args);
    CHECK(r.code == 0);
    run_free(&r);
    char *text = read_file(svg);
    CHECK(text && contains(text, "rattle_intensity") && contains(text, "amp=0.25") &&
          contains(text, "amp=2"));
    free(text);
    snprintf(args, sizeof args, "study '%s' --shard 0/2 --plot '%s'", study, svg);
    CHECK(run_fails_cleanly(&s, args, "--plot", "--shard"));
    scratch_close(&s);
}

TEST(rattle_and_drag_errors_exit_2)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_fails_cleanly(&s, RUN " --rattle-precision 2", "--rattle-precision", NULL));
    CHECK(run_fails_cleanly(&s, "transient " PAIR " --duration 1 --rattle-extend 5s",
                            "--rattle-extend needs --rattle", NULL));
    CHECK(run_fails_cleanly(&s, RUN " --rattle-extend 5s --periods 4", "--rattle-extend",
                            "--periods"));
    CHECK(run_fails_cleanly(&s, RUN " --rattle-extend 5parsecs", "--rattle-extend", NULL));
    CHECK(run_fails_cleanly(&s,
                            "transient " PAIR " --rattle --sweep-speeds 500:900rpm:3 "
                            "--poincare input",
                            "--rattle", "--sweep-speeds"));
    CHECK(run_fails_cleanly(&s, RUN " --set laws.drag2.viscosity=-0.04", "laws[0].viscosity",
                            "must not be negative"));
    CHECK(run_fails_cleanly(&s, RUN " --set laws.drag2.viscosity=0", "viscosity", "nu40"));
    char path[600], args[700];
    snprintf(path, sizeof path, "%s/bad.yaml", s.dir);
    write_file(path, "dofs: [rz]\nshafts:\n  - {name: s, nodes: [{name: m}]}\n"
                     "disks:\n  - {name: m, node: m, mass: 1, polar_inertia: 1e-3}\n"
                     "laws:\n  - {type: bearing_drag, node: m, f0: 3, pitch_diameter: 30 mm,\n"
                     "     viscosity: -0.04 Pa*s}\n");
    snprintf(args, sizeof args, "transient %s --duration 1", path);
    CHECK(run_fails_cleanly(&s, args, "bad.yaml:8:17: laws[0].viscosity", "must not be negative"));
    scratch_close(&s);
}

RUN_TESTS(T(onset_brackets_the_inertia_drag_threshold), T(grazing_onset_runs_through),
          T(rattle_metrics_in_json_and_text), T(extend_until_the_metrics_are_known),
          T(gearbox_onset_brackets_the_first_idler_threshold), T(study_plot_draws_the_map),
          T(rattle_and_drag_errors_exit_2))
