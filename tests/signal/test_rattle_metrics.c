/* Rattle metrics (src/signal/rattle.c): Student's quantiles against published table
 * values, a periodic contact log whose metrics are known exactly, the coverage of the
 * batch-means intervals on Poisson impacts (an independent check of the interval, not of
 * the code's own formula), the 1/sqrt(duration) law behind the suggested window, and the
 * located errors. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/rattle.h"
#include "harness.h"

TEST(student_quantiles_match_tables)
{
    /* two-sided 95 % (p = 0.975) and 90 % (p = 0.95) values of any t table, 10 digits */
    CHECK_REL(gd_student_t_quantile(0.975, 9), 2.262157163, 1e-9);
    CHECK_REL(gd_student_t_quantile(0.975, 1), 12.70620474, 1e-9);
    CHECK_REL(gd_student_t_quantile(0.95, 4), 2.131846786, 1e-9);
    CHECK_REL(gd_student_t_quantile(0.995, 19), 2.860934606, 1e-9);
    /* the normal limit: z_0.975 = 1.959963985 (dof 1e7: t - z ~ z (1 + z^2) / (4 dof)) */
    CHECK_REL(gd_student_t_quantile(0.975, 1e7), 1.959963985, 1e-6);
    CHECK_REL(gd_student_t_quantile(0.025, 9), -2.262157163, 1e-9);
    CHECK(gd_student_t_quantile(0.5, 3) == 0.0);
    CHECK(isnan(gd_student_t_quantile(1.0, 3)) && isnan(gd_student_t_quantile(0.9, 0)));
}

TEST(periodic_log_metrics_are_exact)
{
    /* one period of 10 ms: drive contact lost at 2 ms, coast impact at 4 ms (0.05 m/s),
     * coast contact lost at 5 ms, drive impact at 8 ms (0.08 m/s): apart 5 of 10 ms */
    const int P = 100;
    gd_rattle_event ev[4 * 100];
    for (int k = 0; k < P; k++) {
        double t = 0.01 * k;
        ev[4 * k + 0] = (gd_rattle_event){t + 0.002, 1, 0, -0.01};
        ev[4 * k + 1] = (gd_rattle_event){t + 0.004, 0, -1, -0.05};
        ev[4 * k + 2] = (gd_rattle_event){t + 0.005, -1, 0, 0.02};
        ev[4 * k + 3] = (gd_rattle_event){t + 0.008, 0, 1, 0.08};
    }
    gd_rattle_options o;
    gd_rattle_options_init(&o);
    o.t0 = 0.0;
    o.t1 = 1.0;
    o.mass = 2.0;
    gd_rattle_metrics m;
    gd_error err;
    REQUIRE(gd_rattle_metrics_eval(ev, 4 * P, &o, &m, &err) == GD_OK);
    CHECK_REL(m.separated.mean, 0.5, 1e-12);
    CHECK_ABS(m.separated.half_width, 0.0, 1e-12); /* every batch holds 10 whole periods */
    CHECK_REL(m.drive_rate.mean, 100.0, 1e-12);
    CHECK_REL(m.coast_rate.mean, 100.0, 1e-12);
    CHECK(m.drive_impacts == 100 && m.coast_impacts == 100);
    /* (m 0.08^2 / 2 + m 0.05^2 / 2) per period, 100 periods per second */
    CHECK_REL(m.intensity.mean, (0.0064 + 0.0025) * 100.0, 1e-12);
    CHECK_REL(m.v_mean, 0.065, 1e-12);
    CHECK_REL(m.v_rms, sqrt((0.0064 + 0.0025) / 2), 1e-12);
    CHECK_REL(m.v_max, 0.08, 1e-15);
    /* bins of 0.08 / 16 (the largest speed): 0.08 in the last */
    CHECK(m.hist_drive[GD_RATTLE_BINS - 1] == 100);
    o.vmax = 0.096; /* bins of 6 mm/s: 0.05 in bin 8, 0.08 in bin 13 */
    REQUIRE(gd_rattle_metrics_eval(ev, 4 * P, &o, &m, &err) == GD_OK);
    CHECK_REL(m.bin_width, 0.006, 1e-15);
    CHECK(m.hist_coast[8] == 100 && m.hist_drive[13] == 100);
    CHECK(m.converged && m.precision < 1e-9 && m.suggested_duration == 1.0);
    CHECK_REL(m.t_quantile, 2.262157163, 1e-9);
    /* a window from mid-period: the state at 0.4005 s comes from the events before */
    o.t0 = 0.4005; /* in drive contact since the impact at 0.398 s */
    o.t1 = 0.5005;
    REQUIRE(gd_rattle_metrics_eval(ev, 4 * P, &o, &m, &err) == GD_OK);
    CHECK_REL(m.separated.mean, 0.5, 1e-9);
    CHECK(m.drive_impacts == 10 && m.coast_impacts == 10);
    /* no events: the state given holds throughout */
    o.state0 = 0;
    REQUIRE(gd_rattle_metrics_eval(NULL, 0, &o, &m, &err) == GD_OK);
    CHECK_REL(m.separated.mean, 1.0, 1e-12);
    CHECK(m.drive_impacts == 0 && m.precision < 1e-12 && m.converged);
}

/* xorshift64*: a fixed stream, so the test is deterministic */
static double uniform(unsigned long long *s)
{
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    return ((*s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

/* Poisson drive impacts of rate lambda over [0, T], separated for a uniform random
 * fraction of each gap before its impact (long-run separated fraction 1/2), speeds
 * exponential with mean 0.03 m/s. */
static int poisson_log(unsigned long long *s, double lambda, double T, gd_rattle_event *ev, int cap)
{
    int n = 0;
    double t = 0.0;
    for (;;) {
        double gap = -log(1.0 - uniform(s)) / lambda;
        if (t + gap > T || n + 2 > cap) break;
        ev[n++] = (gd_rattle_event){t + gap * uniform(s), 1, 0, -0.001};
        ev[n++] = (gd_rattle_event){t + gap, 0, 1, -0.03 * log(1.0 - uniform(s))};
        t += gap;
    }
    return n;
}

TEST(batch_means_intervals_cover_poisson_rates)
{
    /* 400 runs of Poisson impacts at 50 /s over 20 s: the 95 % interval of the rate must
     * hold 50 in about 95 % of the runs (binomial sd 1.1 %: 91 .. 99 % is 3.6 sd) */
    const int runs = 400, cap = 4000;
    gd_rattle_event *ev = malloc((size_t)cap * sizeof *ev);
    REQUIRE(ev);
    unsigned long long s = 0x9E3779B97F4A7C15ULL;
    gd_rattle_options o;
    gd_rattle_options_init(&o);
    o.t1 = 20.0;
    int cover = 0, cover_sep = 0;
    double prec_short = 0.0, prec_long = 0.0;
    for (int r = 0; r < runs; r++) {
        int n = poisson_log(&s, 50.0, 20.0, ev, cap);
        gd_rattle_metrics m;
        gd_error err;
        REQUIRE(gd_rattle_metrics_eval(ev, n, &o, &m, &err) == GD_OK);
        cover += fabs(m.drive_rate.mean - 50.0) <= m.drive_rate.half_width;
        cover_sep += fabs(m.separated.mean - 0.5) <= m.separated.half_width;
        prec_short += m.drive_rate.half_width / m.drive_rate.mean;
        /* the same stream over 4x the window: the half-width halves */
        if (r < 100) {
            gd_rattle_options o4 = o;
            o4.t1 = 80.0;
            gd_rattle_event *e4 = malloc(4 * (size_t)cap * sizeof *e4);
            REQUIRE(e4);
            int n4 = poisson_log(&s, 50.0, 80.0, e4, 4 * cap);
            REQUIRE(gd_rattle_metrics_eval(e4, n4, &o4, &m, &err) == GD_OK);
            prec_long += m.drive_rate.half_width / m.drive_rate.mean;
            free(e4);
        }
    }
    free(ev);
    CHECK(cover >= 0.91 * runs && cover <= 0.99 * runs);
    CHECK(cover_sep >= 0.91 * runs && cover_sep <= 0.99 * runs);
    /* mean relative half-widths: 1/sqrt(4) of the short one within 10 % (their sampling
     * spread over 100 and 400 runs is about 3 %) */
    CHECK_REL((prec_long / 100) / (prec_short / runs), 0.5, 0.1);
}

TEST(bad_input_is_located)
{
    gd_rattle_options o;
    gd_rattle_options_init(&o);
    gd_rattle_metrics m;
    gd_error err;
    o.t1 = 1.0;
    gd_rattle_event ev[2] = {{0.5, 1, 0, 0}, {0.4, 0, 1, 0.1}};
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    CHECK_STR(err.field, "events");
    ev[1].t = 0.6;
    ev[1].to = 2;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    ev[1].to = 1;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_OK);
    o.batches = 1;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    CHECK_STR(err.field, "batches");
    o.batches = 10;
    o.t1 = 0.0;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    CHECK_STR(err.field, "window");
    o.t1 = 1.0;
    o.mass = -1.0;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    o.mass = 0.0;
    o.confidence = 1.0;
    CHECK(gd_rattle_metrics_eval(ev, 2, &o, &m, &err) == GD_EINPUT);
    CHECK_STR(err.field, "confidence");
}

RUN_TESTS(T(student_quantiles_match_tables), T(periodic_log_metrics_are_exact),
          T(batch_means_intervals_cover_poisson_rates), T(bad_input_is_located))
