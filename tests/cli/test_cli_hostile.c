/* Hostile command lines of issue 23, run as a program (GD_CLI_PATH) from the source
 * folder: runs that cannot finish are refused before they start (exit 2, the step limit
 * and the option that raises it named), extreme values are located input errors with
 * the bound, the periodic options' bounds are named, a periodic point whose monodromy
 * overflows says why it has no multipliers, and --reduce names a free rigid-body motion
 * instead of memory. Every run here takes well under a second. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli_support.h"
#include "harness.h"

#define CHEN "examples/chen1998_gear_pair.yaml"
#define MATHIEU "tests/plot/mathieu_pair.yaml"

/* Both ran until killed (1e30 s of a gear pair; 1e13 gen-alpha steps): now refused in
 * under a second (the bound is a time limit for the test: wall time is not asserted). */
TEST(runs_that_cannot_finish_are_refused)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    CHECK(run_refused(&s, "revolutions", "--max-steps",
                      "transient " CHEN " --speed 1000rpm --duration 1e30 --quiet"));
    CHECK(run_refused(&s, "1e+13 steps", "--max-steps",
                      "transient " CHEN
                      " --speed 1000rpm --duration 10s --step 1e-12 --method galpha "
                      "--quiet"));
    /* the limit can be raised: 0.01 s in steps of 1e-7 s is 1e5 steps, over a limit of
     * 1e4, within one of 2e5 */
    CHECK(run_refused(&s, "over the limit of 10000", NULL,
                      "transient " CHEN
                      " --speed 1000rpm --duration 10ms --step 1e-7 --method galpha "
                      "--max-steps 10000 --quiet"));
    run_result r;
    run(&s, &r,
        "transient " CHEN " --speed 1000rpm --duration 10ms --step 1e-7 --method galpha "
        "--max-steps 200000 --quiet");
    CHECK(r.code == 0);
    run_free(&r);
    CHECK(run_refused(&s, "--max-steps", "whole number",
                      "transient " CHEN " --duration 1ms --max-steps 0"));
    scratch_close(&s);
}

/* A study case over the step limit fails alone with the reason (the study goes on and
 * ends); it hung the study before. */
TEST(study_case_over_the_step_limit_fails_alone)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char path[256], text[1024];
    snprintf(path, sizeof path, "%s/st.yaml", s.dir);
    snprintf(text, sizeof text,
             "model: %s/" CHEN "\n"
             "analysis: {type: transient, duration: 1e30, speed: 1000 rpm}\n"
             "parameters:\n"
             "  - {name: k, path: meshes.mesh.stiffness, unit: N/m, values: [3e8, 4e8]}\n"
             "outputs: [mesh_force_rms]\n",
             GD_SOURCE_DIR);
    write_file(path, text);
    run_result r;
    run(&s, &r, "study '%s' --out '%s/o'", path, s.dir);
    char jp[256];
    snprintf(jp, sizeof jp, "%s/o/journal.csv", s.dir);
    char *j = read_file(jp);
    CHECK(j && count_lines(j) == 3 && contains(j, "input error") && contains(j, "max_steps"));
    if (!j) show(&r);
    free(j);
    run_free(&r);
    /* a case's own limit (max_steps) is read and used */
    snprintf(text, sizeof text,
             "model: %s/" CHEN "\n"
             "analysis: {type: transient, duration: 1 s, speed: 1000 rpm, max_steps: 10}\n"
             "parameters:\n"
             "  - {name: k, path: meshes.mesh.stiffness, unit: N/m, values: [3e8]}\n"
             "outputs: [mesh_force_rms]\n",
             GD_SOURCE_DIR);
    write_file(path, text);
    run(&s, &r, "study '%s' --out '%s/o2'", path, s.dir);
    snprintf(jp, sizeof jp, "%s/o2/journal.csv", s.dir);
    j = read_file(jp);
    CHECK(j && contains(j, "step limit of 10"));
    if (!j) show(&r);
    free(j);
    run_free(&r);
    scratch_close(&s);
}

TEST(extreme_values_are_located_input_errors)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* NaN rows before */
    CHECK(run_refused(&s, "--speeds", "1e6 rad/s", "unbalance " CHEN " --speeds 0:1e308rpm:3"));
    /* every mode 0 Hz (or 1e302 Hz) before */
    CHECK(run_refused(&s, "disks[0].mass", "below 1e-09 kg",
                      "modal " CHEN " --set 'disks.*.mass=1e-300'"));
    CHECK(run_refused(&s, "polar_inertia", "below 1e-15",
                      "modal " CHEN " --set 'disks.*.polar_inertia=1e-200'"));
    /* "report this geometry as a bug" (exit 1) before */
    CHECK(run_refused(&s, "geometry.face_width", "1000 normal modules",
                      "mesh-stiffness examples/helical_pair1.yaml --set "
                      "'meshes.*.geometry.face_width=1e300'"));
    /* a massless node (0) stays allowed */
    run_result r;
    run(&s, &r, "check " CHEN " --set 'disks.gear_a.diametral_inertia=0'");
    CHECK(r.code == 0);
    if (r.code) show(&r);
    run_free(&r);
    scratch_close(&s);
}

TEST(periodic_bounds_and_overflowed_monodromy)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    /* the message named only ">= 4" */
    CHECK(run_refused(&s, "--samples", "4 to 1048576",
                      "periodic " MATHIEU " --speeds 695:705:2 --samples 2147483647"));
    /* 1e-300 rad/s: a period of 3e299 s overflows the monodromy (Release exited 0 with
     * |mu| = nan and no word why; (int)ceil(log2(inf)) before that) */
    run_result r;
    run(&s, &r, "periodic " MATHIEU " --speeds 1e-300:210:2 --harmonics 4");
    CHECK(r.code == 0 && contains(r.out, "stability not computed") &&
          contains(r.out, "overflowed"));
    if (r.code) show(&r);
    run_free(&r);
    scratch_close(&s);
}

/* A rotor on radial bearings only, axial and torsional motion free: the interior DOFs'
 * stiffness is exactly singular. With 2 and 5 elements the reduction said "out of
 * memory"; with 6 or 60 it named the rigid-body motion. */
TEST(reduce_names_the_free_rigid_body_motion)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    for (int ne = 2; ne <= 6; ne += 3) {
        char path[256], text[1024];
        snprintf(path, sizeof path, "%s/free%d.yaml", s.dir, ne);
        snprintf(text, sizeof text,
                 "dofs: [x, y, z, rx, ry, rz]\n"
                 "materials:\n"
                 "  steel: {density: 7800, E: 2.0e11, poisson: 0.3}\n"
                 "shafts:\n"
                 "  - name: s\n"
                 "    material: steel\n"
                 "    elements_per_section: %d\n"
                 "    sections: [{length: 0.6, outer_diameter: 30 mm}]\n"
                 "    nodes: [{name: a, at: 0}, {name: b, at: 0.6}]\n"
                 "disks:\n"
                 "  - {name: d, node: a, mass: 2, polar_inertia: 1e-3}\n"
                 "bearings:\n"
                 "  - {name: A, node: a, k: 1e8, c: 200}\n"
                 "  - {name: B, node: b, k: 1e8, c: 200}\n"
                 "unbalances:\n"
                 "  - {node: a, amount: 1e-4}\n"
                 "speed: 1000 rpm\n",
                 ne == 2 ? 2 : 5);
        write_file(path, text);
        run_result r;
        run(&s, &r, "transient '%s' --duration 1ms --reduce 5kHz --quiet", path);
        CHECK(r.code == 2 &&
              contains(r.err, "free rigid-body motion: axial (z) and torsional (rz)") &&
              !contains(r.err, "memory"));
        if (r.code != 2) show(&r);
        run_free(&r);
    }
    scratch_close(&s);
}

#define STUDY "examples/studies/chen1998_mesh_stiffness.yaml"

/* A second run on a folder another run holds (flock(1) stands in for the first run,
 * holding DIR/.lock) stops at once with exit 2, naming the other run; before, two
 * --resume runs both redid every remaining case and shared results.h5.tmp. */
TEST(study_folder_is_locked_by_its_run)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    run_result r;
    run(&s, &r, "study " STUDY " --out '%s/st'", s.dir);
    REQUIRE(r.code == 0);
    run_free(&r);
    run(&s, &r, "study " STUDY " --out '%s/st' --resume", s.dir);
    CHECK(r.code == 0);
    run_free(&r);
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && flock '%s/st/.lock' '%s' study " STUDY " --out '%s/st' --resume "
             ">/dev/null 2>'%s/lock.err'",
             GD_SOURCE_DIR, s.dir, GD_CLI_PATH, s.dir, s.dir);
    int st = system(cmd);
    int code = st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    char ep[256];
    snprintf(ep, sizeof ep, "%s/lock.err", s.dir);
    char *err = read_file(ep);
    CHECK(code == 2 && contains(err, "another geardyn study run holds this folder"));
    if (code != 2) fprintf(stderr, "  exit %d: %s\n", code, err ? err : "");
    free(err);
    scratch_close(&s);
}

/* A write that stops short (a full disk; here a file size limit, whose short write
 * leaves errno alone as ENOSPC's does) names the cause and exits 1 as docs/studies.md
 * says: it said "DIR/journal.csv: Success". */
TEST(study_write_failure_names_the_cause)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "cd '%s' && sh -c \"trap '' XFSZ; ulimit -f 4; exec '%s' study " STUDY
             " --out '%s/st'\" >/dev/null 2>'%s/full.err'",
             GD_SOURCE_DIR, GD_CLI_PATH, s.dir, s.dir);
    int st = system(cmd);
    int code = st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    char ep[256];
    snprintf(ep, sizeof ep, "%s/full.err", s.dir);
    char *err = read_file(ep);
    CHECK(code == 1 && contains(err, "journal.csv: File too large") && !contains(err, "Success"));
    if (code != 1) fprintf(stderr, "  exit %d: %s\n", code, err ? err : "");
    free(err);
    scratch_close(&s);
}

static long inode_of(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)sb.st_ino : -1;
}

/* --out DIR is replaced as a whole (a new folder takes DIR's place: its inode changes),
 * the folder's other entries are carried over, and stages and plot temporaries left by
 * killed runs (a PID that no process has) are removed by the next run. Before, the
 * files moved one by one into the same folder (a kill between moves mixed old and new)
 * and the stages stayed. */
TEST(out_folder_replaced_whole_and_stale_stages_removed)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char dir[256], p[512];
    snprintf(dir, sizeof dir, "%s/m", s.dir);
    run_result r;
    run(&s, &r, "modal " CHEN " --out '%s'", dir);
    REQUIRE(r.code == 0);
    run_free(&r);
    long ino0 = inode_of(dir);
    snprintf(p, sizeof p, "%s/mine.txt", dir);
    write_file(p, "kept\n");
    snprintf(p, sizeof p, "%s/sub", dir);
    mkdir(p, 0777);
    /* stages of a dead process (PID 999999999 is above any pid_max), beside DIR and in
     * it, and an old unnamed one in DIR from two hours ago */
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-abcdef", s.dir);
    mkdir(p, 0777);
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-abcdef/modes.csv", s.dir);
    write_file(p, "half\n");
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-ghijkl", dir);
    mkdir(p, 0777);
    char cmd[1024];
    snprintf(
        cmd, sizeof cmd,
        "mkdir '%s/.geardyn-stage-Qx81aZ' && touch -d '2 hours ago' '%s/.geardyn-stage-Qx81aZ'",
        dir, dir);
    CHECK(system(cmd) == 0);
    snprintf(p, sizeof p, "%s/plot.svg.tmp-999999999-AbCdEf", s.dir);
    write_file(p, "<svg");
    run(&s, &r, "modal " CHEN " --out '%s' --plot '%s/plot.svg'", dir, s.dir);
    CHECK(r.code == 0);
    run_free(&r);
    CHECK(inode_of(dir) != ino0);
    snprintf(p, sizeof p, "%s/mine.txt", dir);
    char *t = read_file(p);
    CHECK(t && !strcmp(t, "kept\n"));
    free(t);
    snprintf(p, sizeof p, "%s/sub", dir);
    CHECK(file_exists(p));
    snprintf(p, sizeof p, "%s/modes.csv", dir);
    CHECK(file_exists(p));
    /* left: m/ and plot.svg (and the run's captured output) */
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-abcdef", s.dir);
    CHECK(!file_exists(p));
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-ghijkl", dir);
    CHECK(!file_exists(p));
    snprintf(p, sizeof p, "%s/.geardyn-stage-Qx81aZ", dir);
    CHECK(!file_exists(p));
    snprintf(p, sizeof p, "%s/plot.svg.tmp-999999999-AbCdEf", s.dir);
    CHECK(!file_exists(p));
    snprintf(p, sizeof p, "%s/plot.svg", s.dir);
    CHECK(file_exists(p));
    /* the entries of DIR: the two outputs and the two carried over, nothing else */
    CHECK(count_entries(dir) == 4);
    scratch_close(&s);
}

/* Issue 38 H1: --out through a symbolic link deleted the user's files. The run renamed
 * the link itself, carried the target's files into a new real folder and left the
 * stage as a link to the target, which every later run "removed as stale" by following
 * it. Now the link is followed (outputs land in its target, the user's files there stay
 * and the link stays a link), and a stale stage that is a link is removed as a link. */
TEST(out_through_a_symlink_keeps_the_users_files)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char real[256], link[256], p[512];
    snprintf(real, sizeof real, "%s/real", s.dir);
    snprintf(link, sizeof link, "%s/link", s.dir);
    REQUIRE(mkdir(real, 0777) == 0);
    snprintf(p, sizeof p, "%s/user.txt", real);
    write_file(p, "mine\n");
    REQUIRE(symlink(real, link) == 0);
    run_result r;
    for (int pass = 0; pass < 2; pass++) {
        run(&s, &r, "modal " CHEN " --out '%s'", link);
        CHECK(r.code == 0);
        run_free(&r);
        struct stat sb;
        CHECK(lstat(link, &sb) == 0 && S_ISLNK(sb.st_mode));
        snprintf(p, sizeof p, "%s/user.txt", real);
        char *t = read_file(p);
        CHECK(t && !strcmp(t, "mine\n"));
        free(t);
        snprintf(p, sizeof p, "%s/modes.csv", real);
        CHECK(file_exists(p));
        /* the scratch folder holds real/, link and the captured output only: no stage */
        DIR *d = opendir(s.dir);
        REQUIRE(d);
        struct dirent *e;
        int stages = 0;
        while ((e = readdir(d)))
            stages += !strncmp(e->d_name, ".geardyn-stage-", 15);
        closedir(d);
        CHECK(stages == 0);
    }
    /* a stale "stage" left by the old code: a link to a folder of the user's */
    char other[256];
    snprintf(other, sizeof other, "%s/other", s.dir);
    REQUIRE(mkdir(other, 0777) == 0);
    snprintf(p, sizeof p, "%s/precious.txt", other);
    write_file(p, "keep\n");
    snprintf(p, sizeof p, "%s/.geardyn-stage-999999999-zzzzzz", s.dir);
    REQUIRE(symlink(other, p) == 0);
    run(&s, &r, "modal " CHEN " --out '%s/fresh'", s.dir);
    CHECK(r.code == 0);
    run_free(&r);
    struct stat sb;
    CHECK(lstat(p, &sb) != 0); /* the link is gone */
    snprintf(p, sizeof p, "%s/precious.txt", other);
    char *t = read_file(p);
    CHECK(t && !strcmp(t, "keep\n")); /* its target untouched */
    free(t);
    /* a dangling link as --out: refused, nothing made */
    snprintf(p, sizeof p, "%s/dangling", s.dir);
    REQUIRE(symlink("/nonexistent/geardyn-folder", p) == 0);
    run(&s, &r, "modal " CHEN " --out '%s'", p);
    CHECK(r.code == 2 && contains(r.err, "--out") && contains(r.err, "symbolic link"));
    run_free(&r);
    scratch_close(&s);
}

/* report --out on a file that cannot be written: the option is --out (it said --plot)
 * and the reason is given (it said only "cannot write the plot"); nothing is left. */
TEST(report_write_failure_names_out_and_the_cause)
{
    scratch s;
    REQUIRE(scratch_open(&s));
    char cmd[1024];
    snprintf(
        cmd, sizeof cmd,
        "cd '%s' && sh -c \"trap '' XFSZ; ulimit -f 20; exec '%s' report tests/plot/study.yaml "
        "--speeds 0:3000rpm:3 --freq-points 20 --out '%s/r.svg'\" >/dev/null 2>'%s/r.err'",
        GD_SOURCE_DIR, GD_CLI_PATH, s.dir, s.dir);
    int st = system(cmd);
    int code = st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    char ep[256];
    snprintf(ep, sizeof ep, "%s/r.err", s.dir);
    char *err = read_file(ep);
    CHECK(code == 2 && contains(err, "--out:") && !contains(err, "--plot") &&
          contains(err, "File too large"));
    if (code != 2) fprintf(stderr, "  exit %d: %s\n", code, err ? err : "");
    free(err);
    CHECK(count_entries(s.dir) == 1); /* r.err only */
    scratch_close(&s);
}

RUN_TESTS(T(runs_that_cannot_finish_are_refused), T(study_case_over_the_step_limit_fails_alone),
          T(extreme_values_are_located_input_errors), T(periodic_bounds_and_overflowed_monodromy),
          T(reduce_names_the_free_rigid_body_motion), T(study_folder_is_locked_by_its_run),
          T(study_write_failure_names_the_cause),
          T(out_folder_replaced_whole_and_stale_stages_removed),
          T(report_write_failure_names_out_and_the_cause),
          T(out_through_a_symlink_keeps_the_users_files))
