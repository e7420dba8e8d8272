/* Idlers, synchronisers, gear selection and shifts through the CLI (docs/rattle.md,
 * docs/model-format.md "idlers"):
 *  - examples/manual_5speed.yaml runs through check, modal and campbell, the idlers'
 *    orders named from their meshes ("1x idler gear2"), never as shafts;
 *  - a shift's synchronisation time equals the closed form t = |w0| / (T_c (1/J_A +
 *    1/J_B)) of the cone torque T_c = mu F R n / sin(alpha) between the two inertias;
 *  - bad selections, a fixed gear on a synchroniser and negative drag viscosity exit 2
 *    with a located message and nothing written. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_support.h"
#include "harness.h"

#define BOX "examples/manual_5speed.yaml"
#define PI 3.14159265358979323846

TEST(manual_5speed_runs_with_idler_orders_named)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    CHECK(run(&s, &r, "check " BOX) == 0);
    run_free(&r);
    cJSON *modal = run_json_args(&s, "modal " BOX " --modes 8");
    CHECK(modal != NULL);
    cJSON_Delete(modal);
    CHECK(run(&s, &r, "campbell " BOX " --speeds 600:1000rpm:3 --modes 4") == 0);
    CHECK(contains(r.out, "1x idler gear2"));
    CHECK(!contains(r.out, "1x idler2"));
    run_free(&r);
    /* the FE-shaft variant: 37 nodes of 6 DOFs, the same idlers and selection */
    cJSON *fe = run_json_args(&s, "check examples/manual_5speed_fe.yaml");
    REQUIRE(fe);
    CHECK(jnum(fe, "dofs") == 222 && jnum(fe, "gear") == 3);
    CHECK(cJSON_GetArraySize(cJSON_GetObjectItemCaseSensitive(fe, "idlers")) == 5);
    cJSON_Delete(fe);
    modal = run_json_args(&s, "modal examples/manual_5speed_fe.yaml --modes 12");
    CHECK(modal != NULL);
    cJSON_Delete(modal);
    scratch_close(&s);
}

/* The input (J_in = 2e-3) drives idlers a (J_a = 5e-4, base radii 20:40 mm) and b (J_b =
   3e-4, 30:30 mm) on the output (J_out = 0.05); gear 1 (a) engaged; the shift to b at
   0.01 s. Idler b turns at -W, the output at -W/2: slip w0 = -W/2. On b's side the input
   and the free idler a: J_A = J_b + J_in + J_a (1/2)^2; on the output's, J_B = J_out. */
static const char *SHIFT_MODEL =
    "dofs: [rz]\nspeed: 800 rpm\n"
    "shafts:\n  - {name: input, nodes: [{name: in}]}\n  - {name: output, nodes: [{name: out}]}\n"
    "disks:\n  - {name: in, node: in, mass: 2, polar_inertia: 2e-3}\n"
    "  - {name: out, node: out, mass: 5, polar_inertia: 0.05}\n"
    "idlers:\n  - {name: a, on: out, mass: 0.5, polar_inertia: 5e-4, radial_stiffness: 1e8}\n"
    "  - {name: b, on: out, mass: 0.4, polar_inertia: 3e-4, radial_stiffness: 1e8}\n"
    "synchronisers:\n  - {name: sy, node: out, idlers: [a, b], stiffness: 1e6, damping: 1,\n"
    "     cone: {mu: 0.1, force: 300 N, radius: 45 mm, angle: 8 deg}}\n"
    "gears: {1: a, 2: b}\ngear: 1\n"
    "meshes:\n"
    "  - {name: ma, driver: in, driven: a, base_radius: [20 mm, 40 mm], stiffness: 2e8,"
    " damping: 300}\n"
    "  - {name: mb, driver: in, driven: b, base_radius: [30 mm, 30 mm], stiffness: 2e8,"
    " damping: 300}\n";

TEST(shift_synchronises_in_the_closed_form_time)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[600], args[1200];
    snprintf(path, sizeof path, "%s/shift.yaml", s.dir);
    write_file(path, SHIFT_MODEL);
    double T = 0.02; /* the window after the shift */
    snprintf(args, sizeof args,
             "transient '%s' --shift 1:2@0.01 --duration 0.03 --from 0.01 --output-interval 1e-5 "
             "--record law:shift.cone:mode --record law:shift.cone:slip --record "
             "law:shift.cone:torque",
             path);
    cJSON *o = run_json_args(&s, args);
    REQUIRE(o);
    const cJSON *recs = cJSON_GetObjectItemCaseSensitive(o, "records");
    const cJSON *mode = cJSON_GetArrayItem(recs, 0), *slip = cJSON_GetArrayItem(recs, 1),
                *torque = cJSON_GetArrayItem(recs, 2);
    REQUIRE(mode && slip && torque);
    double W = 800 * PI / 30, Tc = 0.1 * 300 * 0.045 / sin(8 * PI / 180);
    double JA = 3e-4 + 2e-3 + 5e-4 * 0.25, JB = 0.05;
    /* 9.987 ms; had the old gear not been released, idler a would turn with the output
       (J_A = 2.3e-3, J_B = 0.0505: 9.50 ms, 5 % off) */
    double t_sync = 0.5 * W / (Tc * (1 / JA + 1 / JB));
    /* mode 1 while slipping, 2 once locked: its mean over the window gives the time */
    double measured = T * (2 - jnum(mode, "mean"));
    CHECK_REL(measured, t_sync, 0.01);
    /* the slip starts at -W/2 and the cone torque is T_c while it lasts */
    CHECK_REL(jnum(slip, "min"), -0.5 * W, 0.01);
    CHECK_REL(jnum(torque, "max"), Tc, 1e-9);
    cJSON_Delete(o);
    scratch_close(&s);
}

/* The 2nd-order amplitude (rad) of column 1 of a records.csv over whole periods of w from
   t0 on, by its Fourier coefficients (the slow shuffle mode of the driveline, 1.2 Hz, is
   orthogonal to it over the window to 1e-3 of its amplitude). */
static double order_amplitude(const char *csv, double w, double t0)
{
    char *text = read_file(csv);
    if (!text) return -1;
    double c = 0, sn = 0, period = 2 * PI / w, t_end = -1;
    int n = 0;
    /* the last whole period: from the file's last time */
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        double t, y;
        if (sscanf(line, "%lf,%lf", &t, &y) != 2) continue;
        t_end = t;
    }
    free(text);
    if (t_end < t0 + period) return -1;
    double t1 = t0 + floor((t_end - t0) / period) * period;
    text = read_file(csv);
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        double t, y;
        if (sscanf(line, "%lf,%lf", &t, &y) != 2 || t < t0 || t >= t1) continue;
        c += y * cos(w * t);
        sn += y * sin(w * t);
        n++;
    }
    free(text);
    return n ? 2 * hypot(c, sn) / n : -1;
}

static double record_mean(const cJSON *o, const char *name)
{
    const cJSON *r;
    cJSON_ArrayForEach(r, cJSON_GetObjectItemCaseSensitive(o, "records"))
    {
        if (!strcmp(jstr(r, "name"), name)) return jnum(r, "mean");
    }
    return NAN;
}

static double separated_s(const cJSON *o, const char *mesh)
{
    const cJSON *r;
    cJSON_ArrayForEach(r, cJSON_GetObjectItemCaseSensitive(o, "meshes"))
    {
        if (!strcmp(jstr(r, "name"), mesh)) return jnum(r, "separated_time_s");
    }
    return NAN;
}

/* The classic threshold (docs/rattle.md) for the four free idlers of 3rd gear: the input's
   2nd-order amplitude per N m from a run in contact (0.1 N m), each idler's drag (needle
   bearing at its slip against the output, churning) from the same run's records; the
   lowest T* = A* / (A / T) with A* = T_d / (J (r_p / r) W2^2). The transient: no idler
   leaves its flank at 0.40 N m, 2nd gear's does at 0.45 (T* = 0.433). */
TEST(manual_5speed_onset_brackets_the_threshold)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char args[1200], dir[600], csv[700];
    snprintf(dir, sizeof dir, "%s/lin", s.dir);
    snprintf(args, sizeof args,
             "transient " BOX " --duration 2 --from 0.5 --start static --output-interval 1e-4 "
             "--set excitations.loads.firing.amplitude=0.1 --record input.rz,law:* --out '%s'",
             dir);
    cJSON *lin = run_json_args(&s, args);
    REQUIRE(lin);
    snprintf(csv, sizeof csv, "%s/records.csv", dir);
    double W2 = 2 * 800 * PI / 30;
    double A = order_amplitude(csv, W2, 0.5) / 0.1; /* rad per N m */
    CHECK(A > 1e-3 && A < 2e-3);                    /* 1.35e-3 */
    const double J[4] = {9.039e-4, 6.472e-4, 5.06e-4, 2.891e-4};
    const double ratio[4] = {12.921 / 44.635, 19.968 / 42.286, 39.937 / 41.112, 44.635 / 36.413};
    const char *needle[4] = {"law:needle1:torque", "law:needle2:torque", "law:needle4:torque",
                             "law:needle5:torque"};
    const char *churn[4] = {"law:churn1:torque", "law:churn2:torque", NULL, NULL};
    double tstar = INFINITY;
    int first = -1;
    for (int i = 0; i < 4; i++) {
        double Td = fabs(record_mean(lin, needle[i]) + (churn[i] ? record_mean(lin, churn[i]) : 0));
        CHECK(Td > 1e-3 && Td < 0.05);
        double t = Td / (J[i] * ratio[i] * W2 * W2) / A;
        if (t < tstar) tstar = t, first = i;
    }
    CHECK(first == 1); /* 2nd gear's idler: its needle drag and churning nearly cancel */
    CHECK(tstar > 0.40 && tstar < 0.45);
    cJSON_Delete(lin);
    const char *free_meshes[4] = {"gear1", "gear2", "gear4", "gear5"};
    snprintf(args, sizeof args,
             "transient " BOX " --duration 1.5 --from 0.5 --start static --record input.rz "
             "--set excitations.loads.firing.amplitude=0.40");
    cJSON *lo = run_json_args(&s, args);
    snprintf(args, sizeof args,
             "transient " BOX " --duration 1.5 --from 0.5 --start static --record input.rz "
             "--set excitations.loads.firing.amplitude=0.45");
    cJSON *hi = run_json_args(&s, args);
    REQUIRE(lo && hi);
    for (int i = 0; i < 4; i++)
        CHECK(separated_s(lo, free_meshes[i]) == 0);
    CHECK(separated_s(hi, "gear2") > 0.05);
    /* the engaged gear and the final drive stay loaded */
    CHECK(separated_s(hi, "gear3") == 0 && separated_s(hi, "final_drive") == 0);
    cJSON_Delete(lo);
    cJSON_Delete(hi);
    scratch_close(&s);
}

TEST(selection_errors_exit_2_located)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_fails_cleanly(&s, "modal " BOX " --set gear=7", "gear 7 does not exist",
                            "select one of the gears"));
    CHECK(run_fails_cleanly(&s, "modal " BOX " --set synchronisers.sync34.engaged=idler4",
                            "two gears engaged on synchroniser 'sync34'", NULL));
    CHECK(run_fails_cleanly(&s, "modal " BOX " --set 'synchronisers.sync5.idlers=[input]'",
                            "'input' is not an idler", "fixed on its shaft"));
    CHECK(run_fails_cleanly(&s,
                            "transient " BOX " --duration 0.1 --set "
                            "laws.needle2.viscosity=-0.04",
                            "viscosity", "must not be negative"));
    CHECK(run_fails_cleanly(&s, "transient " BOX " --duration 0.1 --shift 3:9@0.05",
                            "gear 9 does not exist", NULL));
    CHECK(run_fails_cleanly(&s, "transient " BOX " --duration 0.1 --shift 3to4", "--shift",
                            "FROM:TO@TIME"));
    /* written in a file: file, line and field */
    char path[600], args[700];
    static char text[32768];
    snprintf(path, sizeof path, "%s/bad.yaml", s.dir);
    char *box = read_file(GD_SOURCE_DIR "/" BOX);
    REQUIRE(box);
    snprintf(text, sizeof text, "%s", box);
    free(box);
    /* sync5 engages the input shaft's node: a fixed gear */
    char *at = strstr(text, "idlers: [idler5]");
    REQUIRE(at);
    memcpy(at, "idlers: [flywhe]", 16);
    write_file(path, text);
    snprintf(args, sizeof args, "modal %s", path);
    CHECK(run_fails_cleanly(&s, args, "bad.yaml:", "synchronisers[2].idlers[0]"));
    scratch_close(&s);
}

RUN_TESTS(T(manual_5speed_runs_with_idler_orders_named),
          T(shift_synchronises_in_the_closed_form_time),
          T(manual_5speed_onset_brackets_the_threshold), T(selection_errors_exit_2_located))
