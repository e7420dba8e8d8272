/* The periodic impact motion of an idler (docs/rattle.md, "A periodic impact solution"):
 * examples/rattle_pair.yaml with 0.5 mm of backlash on each flank and a mesh damping
 * ratio zeta = 0.2155 on the idler's contact (restitution e = exp(-zeta pi / sqrt(1 -
 * zeta^2)) = 0.500 of a linear spring-dashpot contact). Along the line of action the
 * idler is a ball under the "gravity" g = T_d r2 / J2 of its drag on a table, the driver's
 * drive flank, oscillating as r1 A cos(W t): the bouncing ball's period-1 orbit (one
 * impact per excitation period tau, flight tau) has the table's speed s' = g tau (1 - e)
 * / (2 (1 + e)) at impact and the impact speed g tau / (1 + e), for
 * Gamma = r1 A W^2 / g between pi (1 - e) / (1 + e) (1.047) and the period doubling at
 * sqrt((pi (1 - e)/(1 + e))^2 + (2 (1 + e^2) / (1 + e)^2)^2) (1.527). Started on that
 * orbit (just after an impact, from the library with a given state), the transient must
 * keep it: one drive-flank impact per period, none on the coast, every impact at the
 * closed-form speed. Beyond the period doubling (Gamma = 1.7) the same start leaves it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/model.h"
#include "geardyn/model_file.h"
#include "geardyn/rattle.h"
#include "geardyn/system.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "harness.h"

#define PAIR GD_SOURCE_DIR "/examples/rattle_pair.yaml"

typedef struct orbit_run {
    double v_mean, v_rms, v_max, drive_rate, coast_rate, e, g, tau;
} orbit_run;

/* Runs the pair at Gamma from the period-1 orbit's state just after its impact. */
static int run_orbit(double Gamma, orbit_run *out)
{
    const double W = 2 * M_PI * 26.6667, tau = 2 * M_PI / W, r1 = 0.03, r2 = 0.04, J2 = 5.8e-4;
    const double k = 2e8, c = 3670, me = J2 / (r2 * r2);
    double zeta = c / (2 * sqrt(k * me));
    double e = exp(-zeta * M_PI / sqrt(1 - zeta * zeta));
    /* the drag at the idler's nominal speed (the example's churning law) */
    gd_law L;
    gd_law_init(&L, &gd_law_churning_drag, "d");
    L.value[gd_law_param_index(L.type, "viscosity")] = 0.04;
    L.value[gd_law_param_index(L.type, "radius")] = 0.0425;
    L.value[gd_law_param_index(L.type, "face_width")] = 0.015;
    L.value[gd_law_param_index(L.type, "immersion")] = 0.02;
    L.value[gd_law_param_index(L.type, "oil_volume")] = 1.5e-3;
    double lq[2] = {0, 0}, lv[2] = {0, 0};
    L.rate[0] = 0.75 * 800 * M_PI / 30;
    gd_law_point lx = {0, lq, lv};
    double g = fabs(L.type->record(&L, 0, &lx)) * r2 / J2;
    double A = Gamma * g / (r1 * W * W);
    char amp[64];
    snprintf(amp, sizeof amp, "prescribed.0.amplitude=%.17g", A);
    const char *sets[3] = {amp, "meshes.m12.backlash.gap=0.5mm", "meshes.m12.damping=3670"};
    gd_load_options lo;
    gd_load_options_init(&lo);
    lo.set = sets;
    lo.nset = 3;
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_transient_model *tm = NULL;
    gd_transient *tr = NULL;
    gd_transient_result *res = NULL;
    gd_error err;
    int ok = 0;
    if (gd_model_load_opts(PAIR, &lo, &m, &err) || gd_system_build(m, &sys, &err) ||
        gd_transient_model_build(sys, &tm, &err) ||
        gd_transient_new(sys, &tm->spec, m->speed, &tr, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        goto done;
    }
    /* the line of action: d = d0(t) + a2 q2, d0 the driver's part; read off the record */
    gd_tr_record rec = {GD_REC_MESH_DEFLECTION, 0, 0};
    double y0[2] = {0, 0}, y1[2] = {1e-6, 0};
    /* impact phase: the table (driver flank, d units) s(t) = d0(t) - b, s' = g tau (1 - e) /
     * (2 (1 + e)) with the table rising (the stable one of the two phases: decelerating) */
    double sp = g * tau * (1 - e) / (2 * (1 + e)), ti = 0;
    {
        /* d0(t) = sigma r1 A cos(W t): sigma from the record at t = 0 */
        double d0 = gd_transient_record_value(tr, &rec, 0.0, y0);
        double sigma = d0 > 0 ? 1.0 : -1.0;
        /* s' = -sigma r1 A W sin(W t) = sp, with s'' = -sigma r1 A W^2 cos(W t) < 0 */
        double sn = -sp / (sigma * r1 * A * W);
        double ph = asin(sn); /* cos > 0 branch */
        if (-sigma * cos(ph) > 0) ph = M_PI - ph;
        if (ph < 0) ph += 2 * M_PI;
        ti = ph / W;
    }
    double d_t = gd_transient_record_value(tr, &rec, ti, y0);
    double a2 = (gd_transient_record_value(tr, &rec, ti, y1) - d_t) / 1e-6;
    /* just after the impact: d = b - 1 nm (apart), d' = s' - g tau / 2 (the idler leaves
     * the table at g tau / 2 relative to the ground: d = s - z + b, z' = +g tau / 2) */
    /* just after the impact: apart by 1 nm (d = b - 1e-9), the idler leaving the table at
     * g tau / 2 against the ground (d = s + b - z, z' = g tau / 2: a2 q2' = -g tau / 2) */
    const double b = 0.5e-3;
    double q2 = (b - 1e-9 - d_t) / a2, v2 = -g * tau / 2 / a2;
    double q0[2] = {0, 0}, v0[2] = {0, 0};
    int i2 = gd_system_dof(sys, gd_model_find_node(m, "g2"), GD_RZ);
    q0[i2] = q2;
    v0[i2] = v2;
    gd_transient_options opt;
    gd_transient_options_init(&opt);
    opt.t_start = ti;
    opt.t_end = ti + 60 * tau;
    opt.record_from = ti + 20 * tau;
    opt.init = GD_TR_INIT_GIVEN;
    opt.q0 = q0;
    opt.v0 = v0;
    opt.rtol = 1e-8;
    gd_tr_record r0 = {GD_REC_MESH_STATE, 0, 0};
    if (gd_transient_run(tr, &opt, &r0, 1, &res, &err)) {
        fprintf(stderr, "  %s\n", err.message);
        goto done;
    }
    gd_rattle_event *ev = malloc((size_t)(res->ncontact_events + 1) * sizeof *ev);
    int n = 0;
    for (int k2 = 0; ev && k2 < res->ncontact_events; k2++) {
        const gd_tr_contact_event *x = &res->contact_events[k2];
        ev[n++] = (gd_rattle_event){x->t, x->from, x->to, x->velocity};
    }
    gd_rattle_options ro;
    gd_rattle_options_init(&ro);
    ro.t0 = opt.record_from;
    ro.t1 = opt.t_end;
    ro.state0 = 0;
    gd_rattle_metrics rm;
    if (ev && !gd_rattle_metrics_eval(ev, n, &ro, &rm, &err)) {
        out->v_mean = rm.v_mean;
        out->v_rms = rm.v_rms;
        out->v_max = rm.v_max;
        out->drive_rate = rm.drive_rate.mean;
        out->coast_rate = rm.coast_rate.mean;
        out->e = e;
        out->g = g;
        out->tau = tau;
        ok = 1;
    }
    free(ev);
done:
    gd_transient_result_free(res);
    gd_transient_free(tr);
    gd_transient_model_free(tm);
    gd_system_free(sys);
    gd_model_free(m);
    return ok;
}

/* Inside the window (Gamma 1.1 and 1.45) the orbit holds at its closed-form impact speed;
 * past the period doubling at 1.527 (Gamma 1.6) the impacts alternate. Measured: 0.0258294
 * (1.1) and 0.0258799 (1.45) against 0.0258798 m/s (1.9e-3 and 1.5e-6: the 0.13 ms contact
 * and the drag's 1 % speed swing are left out of the closed form, most felt near the
 * lower bound; hence 5e-3); at 1.6 the largest impact speed is 4.3 % above the mean. */
TEST(period_one_bouncing_orbit_and_its_period_doubling)
{
    const double G[3] = {1.1, 1.45, 1.6};
    for (int k = 0; k < 3; k++) {
        orbit_run o;
        REQUIRE(run_orbit(G[k], &o));
        double v = o.g * o.tau / (1 + o.e);
        CHECK_REL(o.e, 0.5, 1e-3);
        CHECK_REL(o.drive_rate, 1 / o.tau, 1e-3); /* one impact per period */
        CHECK(o.coast_rate == 0);
        if (G[k] < 1.527) {
            CHECK_REL(o.v_mean, v, 5e-3);
            CHECK_REL(o.v_max, o.v_mean, 1e-4); /* every impact alike: period 1 */
        } else {
            CHECK(o.v_max > 1.02 * o.v_mean); /* period 2 */
        }
    }
}

RUN_TESTS(T(period_one_bouncing_orbit_and_its_period_doubling))
