/* Hostile input of issue 38 (all but H1, M2, M8 and periodic's L6, L7), run as a program
 * (GD_CLI_PATH) from the source folder. Each test failed on the code before the fix:
 * stdout on a full disk exited 0 (M6), runs with no shaft speed or with collapsed steps
 * ran until killed (M4), unknown speed units read as rad/s (M5), extreme loads gave inf
 * and NaN with exit 0 (M7), a failed run still wrote its --plot (L1), duplicate law names
 * gave two columns of one name (L2), mislocated messages (L3), "nan" in text tables (L4),
 * and SIGTERM during a multi-threaded --plot write left FILE.tmp-PID-XXXXXX (M3). */
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_support.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define DUFFING "examples/duffing.yaml"
#define ROTOR "tests/transient/runup_rotor.yaml"
#define HELICAL "examples/helical_pair1.yaml"

/* M6: every command with its stdout on a full disk. Each one printed a table or JSON
 * that went nowhere and exited 0; now exit 2 naming the failed write. */
TEST(stdout_on_a_full_disk_exits_2)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    const char *cmds[] = {
        "check " CHEN,
        "modal " CHEN,
        "modal " CHEN " --json",
        "static " CHEN,
        "campbell " CHEN " --speeds 0:1000rpm:3",
        "frf " CHEN " --freq 1:1000:5 --input gear_a.y --output gear_a.y",
        "unbalance examples/kumar2011_coupled.yaml --speeds 100:1000rpm:3",
        "transient " CHEN " --speed 1000rpm --duration 1ms",
        "periodic " CHEN " --speeds 500:900:3 --harmonics 4 --json",
        "mesh-stiffness " HELICAL,
        "mesh-stiffness " HELICAL " --load 100",
        "version",
        "--help",
    };
    char errp[300];
    snprintf(errp, sizeof errp, "%s/err.txt", s.dir);
    for (size_t k = 0; k < sizeof cmds / sizeof cmds[0]; k++) {
        char cmd[1024];
        snprintf(cmd, sizeof cmd, "cd '%s' && '%s' %s >/dev/full 2>'%s'", GD_SOURCE_DIR,
                 GD_CLI_PATH, cmds[k], errp);
        int st = system(cmd);
        int code = (st != -1 && WIFEXITED(st)) ? WEXITSTATUS(st) : -1;
        char *err = read_file(errp);
        int ok = code == 2 && contains(err, "writing to the standard output failed") &&
                 contains(err, "No space left on device");
        if (!ok) fprintf(stderr, "  %s: exit %d, stderr %.300s\n", cmds[k], code, err);
        CHECK(ok);
        free(err);
    }
    scratch_close(&s);
}

/* M4: a model driven at a fixed frequency turns no shaft: the step limit counted
 * revolutions only and these ran until killed. Refused up front now; a run whose steps
 * outgrow the limit ends with it named (it ran on per output interval before). */
TEST(runs_without_a_shaft_speed_are_bounded)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_refused(&s, "1.91e+29 revolutions or forcing periods", "--duration: 1e+30 s",
                      "transient " DUFFING " --duration 1e30 --quiet"));
    CHECK(run_refused(&s, "1.27e+11 revolutions or forcing periods", "max_steps",
                      "transient examples/nlvib_ex03.yaml --duration 1e12 --quiet"));
    /* 1000 s of Duffing takes 12306 CVODE steps (measured): within 20000, over 2000 */
    CHECK(run_refused(&s, "--max-steps: the integrator used the step limit of 2000 steps by t = ",
                      NULL, "transient " DUFFING " --duration 1000 --max-steps 2000 --quiet"));
    run_result r;
    run(&s, &r, "transient " DUFFING " --duration 1000 --max-steps 20000 --quiet");
    CHECK(r.code == 0);
    run_free(&r);
    /* a ball bearing of contact stiffness 1e308 N/m^1.5: CVODE's steps collapse at
     * t = 3.2e-4 s (1e5 steps without advancing, measured); the pace check ends it
     * after three windows of 20000 steps (about 2 s CPU) */
    char path[300];
    snprintf(path, sizeof path, "%s/rb.yaml", s.dir);
    write_file(path, "title: rotor on a ball bearing of hostile stiffness\n"
                     "dofs: [x, y]\n"
                     "shafts:\n  - name: s\n    nodes: [{name: m}]\n"
                     "disks:\n  - {name: m, node: m, mass: 2}\n"
                     "springs:\n  - {name: kx, node: m, dof: x, stiffness: 1e5}\n"
                     "  - {name: ky, node: m, dof: y, stiffness: 1e5}\n"
                     "laws:\n"
                     "  - {type: rolling_bearing, name: brg, node: m, elements: 8,\n"
                     "     contact_stiffness: 1e308, pitch_diameter: 40 mm,\n"
                     "     element_diameter: 8 mm, clearance: 5 um}\n"
                     "excitations:\n  loads:\n"
                     "    - {node: m, dof: y, mean: -200, amplitude: 0, frequency: 1 rad/s}\n");
    char args[600];
    snprintf(args, sizeof args, "transient '%s' --speed 1000rpm --duration 0.02 --quiet", path);
    CHECK(
        run_refused(&s, "steps at that pace, over the step limit of 50000000", "max_steps", args));
    scratch_close(&s);
}

/* M5: a --speed-table header's unit goes through the units module: rev/min is rpm,
 * units it does not know are refused (RPM and furlongs read as rad/s before: a
 * 0-6000 rpm run-up ran to 57,296 rpm). */
TEST(speed_table_units_are_parsed_or_refused)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[300], args[600];
    snprintf(path, sizeof path, "%s/sp.csv", s.dir);
    snprintf(args, sizeof args, "transient " ROTOR " --speed-table '%s' --duration 1ms", path);
    const char *bad[] = {"time, RPM\n", "time, furlongs\n", "t [s], speed [furlongs/s]\n",
                         "time_s, speed_rad\n"};
    for (int k = 0; k < 4; k++) {
        char text[200];
        snprintf(text, sizeof text, "%s0, 600\n0.05, 6000\n", bad[k]);
        write_file(path, text);
        CHECK(run_fails_cleanly(&s, args, "sp.csv:1", "names no speed unit"));
    }
    /* the same table in rpm, rev/min, Hz: 600 .. 6000 rpm whichever header */
    const char *good[] = {
        "time, rev/min\n0, 600\n0.05, 6000\n", "time_s, speed_rev_min\n0, 600\n0.05, 6000\n",
        "t [s], speed [rpm]\n0, 600\n0.05, 6000\n", "time, Hz\n0, 10\n0.05, 100\n",
        "# a comment\ntime speed_rpm\n0 600\n0.05 6000\n"};
    for (int k = 0; k < 5; k++) {
        write_file(path, good[k]);
        run_result r;
        run(&s, &r, "%s", args);
        CHECK(r.code == 0 && contains(r.out, "600 .. 6000 rpm"));
        if (r.code) show(&r);
        run_free(&r);
    }
    /* no unit: rad/s (62.83 .. 628.3 rad/s is 600 .. 6000 rpm) */
    write_file(path, "time, speed\n0, 62.83185307179586\n0.05, 628.3185307179586\n");
    run_result r;
    run(&s, &r, "%s", args);
    CHECK(r.code == 0 && contains(r.out, "600 .. 6000 rpm"));
    run_free(&r);
    /* L3: a folder read as "0 row(s)" */
    snprintf(args, sizeof args, "transient " ROTOR " --speed-table '%s' --duration 1ms", s.dir);
    CHECK(run_fails_cleanly(&s, args, "is a folder", NULL));
    scratch_close(&s);
}

/* M7: inf and NaN with exit 0, and a geometry "bug": now located input errors with the
 * bound. The bounds: a normal load of E b m_n (a tooth section strained by 1), a
 * misalignment of one normal module, a bore of a tenth of the root radius (Sainsot's
 * fit holds to a ratio of about 7), g of 1e6 m/s^2. */
TEST(extreme_loads_are_located_input_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* helical_pair1: E 2.06e11 Pa, b 20 mm, m_n 1.75 mm: 7.21e6 N */
    CHECK(run_refused(&s, "--load: a driver torque of 1e+308 N m", "E b m_n = 7.21e+06 N",
                      "mesh-stiffness " HELICAL " --load 1e308"));
    CHECK(run_refused(&s, "--load-range", "E b m_n",
                      "mesh-stiffness " HELICAL " --load-range 1:1e308:3"));
    CHECK(run_refused(&s, "--misalignment: 1e+308 m is over the normal module (0.00175 m)", NULL,
                      "mesh-stiffness " HELICAL " --load 100 --misalignment 1e308"));
    CHECK(run_refused(&s, "--misalignment: 1 m", "normal module",
                      "mesh-stiffness " HELICAL " --load 100 --misalignment 1"));
    CHECK(run_refused(&s, "geometry.driver.bore_radius", "tenth of the root radius",
                      "mesh-stiffness " HELICAL
                      " --set 'meshes.*.geometry.driver.bore_radius=1e-300'"));
    /* the file's contact-analysis load, through any command ("table values must be
     * finite", no file or key, before) */
    CHECK(run_refused(&s, "meshes[0].stiffness.load", "a driver torque of 1e+308 N m",
                      "modal examples/seed002/helical_two_stage_tip_relief.yaml --set "
                      "'meshes.*.stiffness.load=1e308'"));
    CHECK(run_refused(&s, "meshes[0].stiffness.misalignment", "normal module",
                      "mesh-stiffness examples/rig2018_pair_relief.yaml --set "
                      "'meshes.*.stiffness.misalignment=1'"));
    CHECK(
        run_refused(&s, "--torque: 1e+308 N m overflows", NULL, "static " CHEN " --torque 1e308"));
    CHECK(run_refused(&s, "unbalances: the response overflows at 10.472 rad/s", NULL,
                      "unbalance examples/kumar2011_coupled.yaml --speeds 100:1000rpm:3 --set "
                      "'unbalances.*.amount=1e308'"));
    CHECK(run_refused(
        &s, "gravity.g", "over 1e6 m/s^2",
        "static examples/rig2018.yaml --set 'gravity={direction: [0,-1,0], g: 1e308}'"));
    /* "LU pivot -7" before: the direction's norm overflowed; now the direction only */
    run_result r;
    run(&s, &r,
        "static examples/rig2018.yaml --set 'gravity={direction: [0,-1e308,0], g: 9.81}' --json");
    cJSON *o = r.code == 0 ? cJSON_Parse(r.out) : NULL;
    run_result r2;
    run(&s, &r2,
        "static examples/rig2018.yaml --set 'gravity={direction: [0,-1,0], g: 9.81}' --json");
    CHECK(o && r2.code == 0 && !strcmp(r.out, r2.out)); /* the same numbers, bit for bit */
    if (!o) show(&r);
    cJSON_Delete(o);
    run_free(&r);
    run_free(&r2);
    /* within the bounds: 200 N m and 5 um still run */
    run(&s, &r, "mesh-stiffness " HELICAL " --load 200 --misalignment 5um");
    CHECK(r.code == 0 && !contains(r.out, "nan") && !contains(r.out, "inf"));
    run_free(&r);
    scratch_close(&s);
}

/* L1: a run that cannot write its --out neither computes nor writes its --plot; --out
 * and --plot naming one path are refused before computing. */
TEST(failed_runs_write_no_plot)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char plot[300], args[700];
    snprintf(plot, sizeof plot, "%s/q.svg", s.dir);
    const char *cmds[] = {"modal " CHEN, "static " CHEN, "campbell " CHEN " --speeds 0:1000rpm:3"};
    for (int k = 0; k < 3; k++) {
        snprintf(args, sizeof args, "%s --out /proc/nope --plot '%s'", cmds[k], plot);
        CHECK(run_refused(&s, "/proc/nope", "is not a writable folder", args));
        CHECK(!file_exists(plot));
    }
    snprintf(args, sizeof args, "modal " CHEN " --out '%s/same.svg' --plot '%s/./same.svg'", s.dir,
             s.dir);
    CHECK(run_refused(&s, "name the same path", NULL, args));
    snprintf(plot, sizeof plot, "%s/same.svg", s.dir);
    CHECK(!file_exists(plot));
    scratch_close(&s);
}

/* L2: two laws of one name (two columns "law:cubic:force"); L3: mislocated messages;
 * L4: no "nan" in text tables (the JSON's null is "-"). */
TEST(names_messages_and_tables)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[300], args[600];
    snprintf(path, sizeof path, "%s/dup.yaml", s.dir);
    char *duff = NULL;
    {
        char p[300];
        snprintf(p, sizeof p, "%s/" DUFFING, GD_SOURCE_DIR);
        duff = read_file(p);
    }
    REQUIRE(duff);
    char *at = strstr(duff, "laws:\n");
    REQUIRE(at);
    char text[4096];
    snprintf(text, sizeof text,
             "%.*slaws:\n  - {type: polynomial_spring, name: cubic, node: m, dof: x, k3: 0.2}\n%s",
             (int)(at - duff), duff, at + 6);
    free(duff);
    write_file(path, text);
    snprintf(args, sizeof args, "transient '%s' --duration 1 --record law:cubic:force", path);
    CHECK(run_refused(&s, "laws[1].name: duplicate law name 'cubic' (first on line", NULL, args));
    /* L3: LAPACK's "info -5" for a viscosity of 1e308 */
    CHECK(run_refused(&s, "hold inf or NaN entries", "overflows",
                      "campbell examples/journal_rotor.yaml --speeds 100:1000rpm:3 --set "
                      "'laws.*.viscosity=1e308'"));
    /* L3: "speeds: values must be finite" for a --parameter continuation; then the
     * spacing 1e8 + (1e308 - 1e8) * 2 / 2 itself overflowed: the last value is 1e308 */
    run_result r;
    run(&s, &r,
        "periodic " CHEN " --speeds 500:500:1 --harmonics 4 --parameter "
        "'meshes.mesh.stiffness=1e8:1e308:3'");
    CHECK(r.code == 1 && contains(r.err, "meshes.mesh.stiffness = 5e+307: Newton did not") &&
          contains(r.err, "meshes.mesh.stiffness = 1e+308: Newton did not") &&
          !contains(r.err, "inf") && !contains(r.out, "inf"));
    run_free(&r);
    /* L4: the Campbell summary's min logdec of modes without one */
    run(&s, &r, "campbell examples/journal_rotor.yaml --speeds 100:3000rpm:4");
    CHECK(r.code == 0 && contains(r.out, "min logdec") && !contains(r.out, " nan"));
    run_free(&r);
    /* a mesh stiffness of 1e308 overflowed the factorisation, which looked singular: exit 0
     * with "-" in every row; now refused before the solve */
    CHECK(run_refused(&s, "beyond 1e150", "overflows",
                      "frf " CHEN " --freq 1:1000:3 --input gear_a.y --output gear_a.y --set "
                      "'meshes.*.stiffness=1e308'"));
    /* the FRF table at a frequency without a value (a rigid-body mode at 0 Hz): null in
     * the JSON, - in the table, exit 0 */
    run(&s, &r,
        "frf examples/kumar2011_torsional.yaml --freq 0:1000:3 --input motor.rz --output "
        "motor.rz");
    CHECK(r.code == 0 && contains(r.err, "null (JSON), - (tables)") && !contains(r.out, "nan") &&
          contains(r.out, "0             -           -"));
    if (r.code) show(&r);
    run_free(&r);
    scratch_close(&s);
}

/* the FILE.tmp-* entries in dir */
static int temporaries(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += strstr(e->d_name, ".tmp-") != NULL;
    closedir(d);
    return n;
}

/* M3: SIGTERM while a multi-threaded run writes its --plot. The mask was set in the
 * calling thread only: an OpenMP or OpenBLAS worker took the signal and the process
 * died mid-write, leaving FILE.tmp-PID-XXXXXX. The test waits for the temporary file to
 * appear and sends SIGTERM at once (each of several runs): the process ends by the
 * signal, after the figure is whole and renamed, and no temporary is left. */
TEST(sigterm_during_a_threaded_plot_write_leaves_no_partial_file)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char plot[300], cmd[2048];
    snprintf(plot, sizeof plot, "%s/fig.html", s.dir);
    int hit = 0, clean = 0, rounds = 0;
    for (int round = 0; round < 4 && hit < 2; round++, rounds++) {
        pid_t pid = fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            snprintf(
                cmd, sizeof cmd,
                "cd '%s' && OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive OPENBLAS_NUM_THREADS=2 "
                "exec '%s' campbell "
                "examples/rig2018.yaml --speeds 0:12000rpm:100 --modes 8 --threads 2 --plot '%s' "
                ">/dev/null 2>&1",
                GD_SOURCE_DIR, GD_CLI_PATH, plot);
            execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
            _exit(127);
        }
        /* poll for the temporary (the write of a 4 MB HTML file takes milliseconds) */
        int sent = 0;
        struct timespec nap = {0, 500000};
        for (int k = 0; k < 200000 && !sent; k++) {
            if (temporaries(s.dir) > 0) {
                kill(pid, SIGTERM);
                sent = 1;
            } else {
                int st;
                if (waitpid(pid, &st, WNOHANG) == pid) {
                    pid = -1;
                    break;
                }
                nanosleep(&nap, NULL);
            }
        }
        if (pid > 0) {
            if (!sent) kill(pid, SIGTERM);
            int st;
            waitpid(pid, &st, 0);
            if (sent) {
                hit++;
                int by_signal = WIFSIGNALED(st) && WTERMSIG(st) == SIGTERM;
                int ok = temporaries(s.dir) == 0 && by_signal;
                if (!ok)
                    fprintf(stderr, "  round %d: %d temporaries, status %d\n", round,
                            temporaries(s.dir), st);
                clean += ok;
            }
        }
        /* the next round starts without the figure or a leftover */
        char rm[600];
        snprintf(rm, sizeof rm, "rm -f '%s'/fig.html*", s.dir);
        if (system(rm) != 0) fprintf(stderr, "  could not clean %s\n", s.dir);
    }
    fprintf(stderr, "  signal during the write in %d of %d runs\n", hit, rounds);
    CHECK(hit >= 1); /* the test reached the window */
    CHECK(clean == hit);
    scratch_close(&s);
}

/* the .geardyn-stage-* entries in dir */
static int stages(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)))
        n += strncmp(e->d_name, ".geardyn-stage-", 15) == 0;
    closedir(d);
    return n;
}

/* M3, --out: a threaded run with --out and --plot killed by SIGTERM as soon as its stage
 * appears, and once later at random: no stage is left, the folder is the old one
 * (untouched) or the new one whole, and the figure whole or absent. With outdir's own
 * handler installed at its stage, a later --plot write lost the commit's deferral. */
TEST(sigterm_during_a_threaded_out_run_leaves_old_or_new)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char out[300], keep[400], cmd[2048];
    snprintf(out, sizeof out, "%s/res", s.dir);
    REQUIRE(mkdir(out, 0777) == 0);
    snprintf(keep, sizeof keep, "%s/mine.txt", out);
    write_file(keep, "kept\n");
    for (int round = 0; round < 2; round++) {
        pid_t pid = fork();
        REQUIRE(pid >= 0);
        if (pid == 0) {
            snprintf(
                cmd, sizeof cmd,
                "cd '%s' && OMP_NUM_THREADS=2 OMP_WAIT_POLICY=passive OPENBLAS_NUM_THREADS=2 "
                "exec '%s' campbell "
                "examples/rig2018.yaml --speeds 0:12000rpm:60 --modes 8 --threads 2 --out '%s' "
                "--plot '%s/fig.html' >/dev/null 2>&1",
                GD_SOURCE_DIR, GD_CLI_PATH, out, s.dir);
            execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
            _exit(127);
        }
        struct timespec nap = {0, 500000};
        int st, done = 0;
        /* round 0 and 2: at the stage's appearance; 1 and 3: 50 ms after it */
        for (int k = 0; k < 200000 && !done; k++) {
            if (stages(s.dir) > 0) {
                if (round % 2) {
                    struct timespec later = {0, 50000000};
                    nanosleep(&later, NULL);
                }
                kill(pid, SIGTERM);
                break;
            }
            if (waitpid(pid, &st, WNOHANG) == pid) done = 1;
            nanosleep(&nap, NULL);
        }
        if (!done) waitpid(pid, &st, 0);
        CHECK(stages(s.dir) == 0);
        CHECK(temporaries(s.dir) == 0);
        char *k = read_file(keep);
        CHECK(k && !strcmp(k, "kept\n")); /* the user's file stays, old folder or new */
        free(k);
        char csv[400];
        snprintf(csv, sizeof csv, "%s/campbell.csv", out);
        char *c = read_file(csv);
        if (c) CHECK(count_lines(c) > 50); /* a new folder is whole */
        free(c);
    }
    scratch_close(&s);
}

RUN_TESTS(T(stdout_on_a_full_disk_exits_2), T(runs_without_a_shaft_speed_are_bounded),
          T(speed_table_units_are_parsed_or_refused), T(extreme_loads_are_located_input_errors),
          T(failed_runs_write_no_plot), T(names_messages_and_tables),
          T(sigterm_during_a_threaded_plot_write_leaves_no_partial_file),
          T(sigterm_during_a_threaded_out_run_leaves_old_or_new))
