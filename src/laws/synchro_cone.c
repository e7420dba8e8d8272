/* A synchroniser engaging an idler at a gear shift (docs/rattle.md, "Shifting"): from
 * the shift time t_s on, the cone's friction torque brings the idler to its shaft's
 * speed, then the sleeve locks it:
 *
 *   t < t_s              T = 0                      (mode 0: free)
 *   slipping             T = -T_c sgn(w)            (mode 1: cone friction)
 *   once w has crossed 0 T = -c_lock w              (mode 2: locked)
 *
 * with w the slip speed (rate + q') of the idler minus that of the shaft node, acting as T
 * on the idler and -T on the shaft. T_c = mu F R_c n / sin(alpha) is the cone torque of
 * the synchroniser's sleeve force F on n cones of mean radius R_c and half angle alpha
 * (the wedge multiplies the normal force by 1/sin(alpha): Naunheimer, Bertsche, Ryborz,
 * Lechner, Automotive Transmissions, 2nd ed., Springer 2011, Sec. 7.2 "synchronizer
 * torque"); the builder computes it from the synchroniser's `cone:`. Locked, the sleeve
 * and the dog teeth are a stiff viscous coupling: a law keeps no state, so the angle at
 * which the teeth met is not known to a spring (the slip that remains is T / c_lock:
 * 1e-2 rad/s at 10 N m with the default 1000 N m s/rad). Switches: t - t_s (mode 0 -> 1)
 * and w (mode 1 -> 2: the speeds have met); the locked mode stays. Local DOFs
 * [rz of the idler, rz of the synchroniser's node]. */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"

enum { SC_TIME, SC_TORQUE, SC_LOCK_DAMPING, SC_NPARAMS };
enum { SC_FREE, SC_SLIPPING, SC_LOCKED };

static const gd_law_param sc_params[SC_NPARAMS] = {
    {"time", GD_QTY_TIME, NAN, GD_LAW_NONNEG, "the shift's start t_s, s"},
    {"torque", GD_QTY_TORQUE, NAN, GD_LAW_POSITIVE,
     "cone friction torque T_c = mu F R_c n / sin(alpha), N m"},
    {"lock_damping", GD_QTY_ROT_DAMPING, 1000.0, GD_LAW_POSITIVE,
     "the locked coupling's viscous stiffness c_lock, N m s/rad"},
};

static const int sc_dirs[1] = {5}; /* rz */

static double slip(const gd_law *law, const gd_law_point *x)
{
    return law->rate[0] + x->v[0] - (law->rate[1] + x->v[1]);
}

static void sc_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    (void)k;
    u[0] = w[0] = 1.0;
    u[1] = w[1] = -1.0;
}

/* The torque on the idler in `mode`; *dc its derivative in the slip. */
static double sc_torque(const gd_law *law, int mode, double w, double *dc)
{
    *dc = 0;
    if (mode == SC_SLIPPING)
        return w > 0 ? -law->value[SC_TORQUE] : w < 0 ? law->value[SC_TORQUE] : 0;
    if (mode == SC_LOCKED) {
        *dc = -law->value[SC_LOCK_DAMPING];
        return -law->value[SC_LOCK_DAMPING] * w;
    }
    return 0;
}

static void sc_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    double dc, T = sc_torque(law, law->mode, slip(law, x), &dc);
    f[0] += T;
    f[1] -= T;
    if (jq) jq[0] = 0;
    if (jv) jv[0] = dc;
}

static const gd_law_record sc_records[] = {{"torque", "N m"}, {"slip", "rad/s"}, {"mode", "-"}};

static double sc_record(const gd_law *law, int k, const gd_law_point *x)
{
    double dc, w = slip(law, x);
    if (k == 0) return sc_torque(law, law->mode, w, &dc);
    return k == 1 ? w : law->mode;
}

/* switch 0: t - t_s; switch 1: the slip while slipping (else a constant: no events) */
static void sc_switches(const gd_law *law, const gd_law_point *x, double *g)
{
    g[0] = x->t - law->value[SC_TIME];
    g[1] = law->mode == SC_SLIPPING ? slip(law, x) : 1.0;
}

static int sc_mode_at(const gd_law *law, const gd_law_point *x)
{
    if (x->t < law->value[SC_TIME]) return SC_FREE;
    if (law->mode == SC_LOCKED) return SC_LOCKED; /* the teeth stay engaged */
    return slip(law, x) == 0 ? SC_LOCKED : SC_SLIPPING;
}

static int sc_mode_after(const gd_law *law, int mode, const int *dir)
{
    (void)law;
    if (mode == SC_FREE && dir[0] > 0) return SC_SLIPPING;
    if (mode == SC_SLIPPING && dir[1] != 0) return SC_LOCKED;
    return mode;
}

static int sc_switch_of(const gd_law *law, int from, int to)
{
    (void)law;
    (void)to;
    return from == SC_FREE ? 0 : 1;
}

static double sc_switch_tol(const gd_law *law)
{
    (void)law;
    return 1e-12;
}

const gd_law_type gd_law_synchro_cone = {
    .name = "synchro_cone",
    .summary = "a shift's synchroniser: cone friction torque from t_s until the speeds meet, "
               "then locked",
    .flags = 0,
    .params = sc_params,
    .nparams = SC_NPARAMS,
    .dirs = sc_dirs,
    .ndirs = 1,
    .two_nodes = 1,
    .nterms = 1,
    .term = sc_term,
    .force = sc_force,
    .records = sc_records,
    .nrecords = 3,
    .record = sc_record,
    .nswitches = 2,
    .switches = sc_switches,
    .mode_at = sc_mode_at,
    .mode_after = sc_mode_after,
    .switch_of = sc_switch_of,
    .switch_tol = sc_switch_tol,
    .hold_mode = SC_FREE,
};
