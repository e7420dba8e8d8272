/* Nonlinear and time-varying element laws for time integration (docs/transient.md).
 * Each law is a pure function of its arguments: no state, no allocation (except the
 * tables, created once). All quantities are SI: m, rad, s, N, N m, kg, Pa s.
 *
 *  - tables: y(x) by linear or cubic-spline interpolation, periodic (TVMS k(angle),
 *    static transmission error e(angle), valve lift s(cam angle), torque vs angle) or
 *    not (prescribed angle vs time);
 *  - harmonic series: mean + sum_h a_h cos(h nu x) + b_h sin(h nu x);
 *  - backlash mesh force ([Benini2004] Eqs. 2-4), contact on the drive and the coast flank;
 *  - squeeze film damper forces, short-bearing (Ocvirk) theory, pi and 2pi film, with a
 *    finite-length correction factor ([Chen1998], Barrett, Allaire & Gunter 1980);
 *  - cam inertial torque of a desmodromic valve train ([Benini2004] Eq. 10);
 *  - applied torque/force laws and prescribed motion laws.
 *
 * Ownership and threads: a gd_table is made by gd_table_new (or gd_table_from_tvms) and
 * freed by gd_table_free; the laws that point to a table borrow it. Every evaluation is
 * a pure function, safe from any number of threads on the same table.
 */
#ifndef GEARDYN_NONLINEAR_H
#define GEARDYN_NONLINEAR_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/law_type.h"
#include "geardyn/mesh_stiffness.h"

/* ---------------------------------------------------------------- tables */

typedef enum gd_interp {
    GD_INTERP_LINEAR = 0, /* piecewise linear: y' piecewise constant, y'' = 0 */
    GD_INTERP_SPLINE = 1  /* cubic spline: periodic if the table is, else natural */
} gd_interp;

/* y(x) sampled at n points x[0] < x[1] < ... < x[n-1].
 * Periodic (period > 0): x[n-1] - x[0] < period; x is wrapped into [x[0], x[0] + period)
 * and the interval from x[n-1] to x[0] + period closes the loop.
 * Not periodic (period = 0): beyond the ends the table is continued linearly with its
 * end slope (an angle-vs-time table keeps turning), y'' = 0 there. */
typedef struct gd_table {
    int n;
    double period; /* 0: not periodic */
    gd_interp interp;
    double *x, *y;
    double *m;      /* spline: second derivatives y''(x_i); NULL for linear */
    double uniform; /* > 0: constant spacing, for O(1) look-up */
} gd_table;

/* n >= 2 (spline: n >= 3). Copies x and y. */
GD_API gd_status gd_table_new(int n, const double *x, const double *y, double period,
                              gd_interp interp, gd_table **out, gd_error *err);
/* Periodic table of a mesh stiffness result: k(driver angle) over its first cycle. */
GD_API gd_status gd_table_from_tvms(const gd_tvms_result *r, gd_interp interp, gd_table **out,
                                    gd_error *err);
GD_API void gd_table_free(gd_table *t);
/* y(x); dy and d2y (may be NULL) receive y'(x) and y''(x). */
GD_API double gd_table_eval(const gd_table *t, double x, double *dy, double *d2y);

/* ---------------------------------------------------------------- harmonic series */

#define GD_HARMONICS_MAX 32
/* y(x) = mean + sum_{h=1..n} [cos_amp[h-1] cos(h order x) + sin_amp[h-1] sin(h order x)] */
typedef struct gd_harmonic {
    double mean;
    double order; /* base order nu (e.g. 1 for once per revolution, teeth for the mesh) */
    int n;        /* 0..GD_HARMONICS_MAX */
    double cos_amp[GD_HARMONICS_MAX], sin_amp[GD_HARMONICS_MAX];
} gd_harmonic;

GD_API double gd_harmonic_eval(const gd_harmonic *h, double x, double *dy, double *d2y);

/* ---------------------------------------------------------------- backlash mesh */

/* Contact state of a mesh: the flank in contact. */
typedef enum gd_contact {
    GD_CONTACT_COAST = -1,    /* inverse (coast) flank: d < -b */
    GD_CONTACT_SEPARATED = 0, /* |d| <= b: no tooth contact */
    GD_CONTACT_DRIVE = 1      /* direct (drive) flank: d > b */
} gd_contact;

/* Parameters at one instant (stiffnesses may vary with the mesh angle). */
typedef struct gd_backlash_params {
    double b;                /* gap on each flank at the nominal position, m (>= 0);
                                the total free play is 2 b */
    double k_drive, k_coast; /* contact stiffness on each flank, N/m */
    double c_drive, c_coast; /* damping while in contact, N s/m */
    double c_free; /* damping while separated ([Benini2004]: "other dissipative effects") */
} gd_backlash_params;

/* Flank from the deformation d (m) along the contact normal. */
GD_API gd_contact gd_backlash_state(double d, double b);
/* Mesh force F (N, positive pressing the drive flanks) for a given state, [Benini2004] Eqs. 2-4:
 *   drive:      F = k_drive (d - b) + c_drive d'
 *   separated:  F = c_free d'
 *   coast:      F = k_coast (d + b) + c_coast d'
 * The state is an argument so an integrator can keep it frozen between located events;
 * each branch is continued smoothly beyond its interval. k_coast = 0 is one-sided
 * contact: the coast state then acts as separated (F = c_free d'). */
GD_API double gd_backlash_force(const gd_backlash_params *p, gd_contact state, double d, double dd);
/* The same with the state from d (written to *state if not NULL). */
GD_API double gd_backlash_force_auto(const gd_backlash_params *p, double d, double dd,
                                     gd_contact *state);
/* Partial derivatives of gd_backlash_force in the given state (for Newton and variational
 * equations): g[0] = dF/dd, g[1] = dF/dd', g[2] = dF/dk and g[3] = dF/dc, where k, c are
 * the stiffness and damping of that state (k_drive/c_drive, k_coast/c_coast; while
 * separated k does not act and c is c_free). */
GD_API void gd_backlash_force_grad(const gd_backlash_params *p, gd_contact state, double d,
                                   double dd, double g[4]);
/* Mesh damping: constant plus proportional to the instantaneous stiffness,
 * c = c_const + c_per_k * k (c_per_k in s). */
GD_API double gd_mesh_damping(double c_const, double c_per_k, double k);

/* The typed data (gd_law.data) of a gd_law_backlash_mesh instance: the mesh law of
 * [Benini2004] Eqs. 2-5 with its time-varying stiffness k(theta) and static transmission
 * error e(theta) read at the driver's angle theta = angle_offset + sense (nominal + q_drv).
 * The instance's local DOFs are the mesh vector's (a, na of them: deflection d = a . q)
 * with the driver's rz among them (drv) or appended. Filled by the problem that owns it
 * (the transient problem from a gd_tr_mesh, in gd_transient_spec_laws' block); the
 * tables and nominal_ctx are borrowed. */
typedef struct gd_mesh_law_data {
    const gd_table *tvms; /* k_drive(theta), N/m; NULL: constant stiffness */
    const gd_table *ste;  /* e(theta), m; NULL: none */
    double stiffness;     /* N/m without tvms */
    double coast_scale;   /* k_coast = coast_scale k_drive; 0: one-sided contact */
    double damping;       /* constant part of the contact damping, N s/m */
    double damping_per_k; /* c = damping + damping_per_k k, s */
    double damping_free;  /* while separated, N s/m */
    int backlash;         /* 1: gap b on each flank, modes gd_contact */
    double gap;           /* b, m */
    double angle_offset;  /* rad */
    int na;               /* local DOFs 0..na-1 carry the mesh vector */
    double a[GD_LAW_MAX_DOFS];
    int drv;             /* local index of the driver's rz DOF, -1 absent */
    int sense;           /* +1: the driver turns about +z */
    double drv_rate;     /* driver's nominal speed about +z, rad/s */
    double k_lin, c_lin; /* the linear part the system assembled (GD_LAW_ASSEMBLED) */
    int angle_fixed;     /* 1: the driver's motion is prescribed (not a free DOF) */
    /* a run-up: the driver's nominal angle and speed at t are drv_ratio times these
     * (NULL: drv_rate t and drv_rate) */
    void (*nominal)(const void *ctx, double t, double *angle, double *speed);
    const void *nominal_ctx;
    double drv_ratio;
} gd_mesh_law_data;
/* Records of a gd_law_backlash_mesh, in its record order. */
enum { GD_MESH_REC_FORCE = 0, GD_MESH_REC_DEFLECTION, GD_MESH_REC_STATE, GD_MESH_REC_STIFFNESS };
/* The mesh law in mode `state` at local (t, q, v): the force F (N, pressing the drive
 * flanks), with d, dd the raw deflection and rate (a . q, a . q'), k the stiffness at
 * the angle, de the deflection minus the STE (the contact test) and grad = dF/dd,
 * dF/dd', dF/dq_drv, dF/dq_drv' (any output may be NULL). The law's hold applies. */
GD_API double gd_mesh_law_eval(const gd_law *law, int state, double t, const double *q,
                               const double *v, double *d, double *dd, double *k, double *de,
                               double grad[4]);

/* ---------------------------------------------------------------- squeeze film damper */

typedef enum gd_sfd_film {
    GD_SFD_PI_FILM = 0, /* cavitated: pressure only where the film is squeezed (p > 0) */
    GD_SFD_2PI_FILM = 1 /* uncavitated: full film, negative pressures kept */
} gd_sfd_film;

typedef struct gd_sfd_params {
    double viscosity; /* mu, Pa s */
    double radius;    /* journal radius R = D / 2, m */
    double length;    /* land length L, m */
    double clearance; /* radial clearance c, m */
    gd_sfd_film film;
    /* Finite-length correction factor multiplying the short-bearing forces:
     * > 0: this value; 0: gd_sfd_correction_factor(L / D); < 0: none (pure short bearing) */
    double correction;
    double max_eccentricity; /* eccentricity ratio is capped here (0: 0.995) */
} gd_sfd_params;

/* Finite-length correction of the short-bearing damper forces for L / D (see
 * docs/transient.md): eta = 3 / lambda^2 (1 - tanh(lambda) / lambda), lambda = L/D, the
 * exact ratio of the finite-length to the short-bearing force of the uncavitated film
 * at small eccentricity with the hyperbolic-cosine axial profile. eta -> 1 as L/D -> 0. */
GD_API double gd_sfd_correction_factor(double l_over_d);

/* Short-bearing film integrals over theta in [t1, t2] with h = c (1 + eps cos theta):
 * j[0] = int cos^2/(1+eps cos)^3, j[1] = int sin cos/(...)^3, j[2] = int sin^2/(...)^3,
 * closed forms through the eccentric anomaly (exact for any interval, 0 <= eps < 1). */
GD_API void gd_sfd_integrals(double eps, double t1, double t2, double j[3]);

/* Damper forces on the journal in the radial direction (along the eccentricity, from the
 * housing centre to the journal centre) and the tangential direction (+90 deg from it),
 * from e (m), e' (m/s) and the whirl speed phi' (rad/s). The journal does not spin. */
GD_API void gd_sfd_force_polar(const gd_sfd_params *p, double e, double edot, double phidot,
                               double *fr, double *ft);
/* Damper forces (N) on the journal at position (x, y) and velocity (vx, vy) relative to
 * the housing centre. */
GD_API void gd_sfd_force(const gd_sfd_params *p, double x, double y, double vx, double vy,
                         double *fx, double *fy);

/* Jacobian of gd_sfd_force: jq[2 i + j] = d f_i / d x_j and jv[2 i + j] = d f_i / d v_j
 * (i, j: 0 x, 1 y), in closed form (src/laws/sfd.c: the film integrals differentiated
 * in eps, the chain rule through the journal's polar frame); centred (e below 1e-9 c)
 * or at rest in the pi film, by central differences of gd_sfd_force (steps 1e-6 of the
 * clearance and of the velocity scale). One force law serves the integrator and the
 * frequency-domain solvers. fx, fy receive the forces. Thread-safe. */
GD_API void gd_sfd_force_jacobian(const gd_sfd_params *p, double x, double y, double vx, double vy,
                                  double *fx, double *fy, double jq[4], double jv[4]);

/* The damper as a law instance (gd_law_sfd, law_type.h): its parameters from a law's
 * values, and a law's values from parameters. */
GD_API void gd_sfd_params_of_law(const gd_law *law, gd_sfd_params *p);
GD_API void gd_sfd_law_values(const gd_sfd_params *p, gd_law *law);

/* ---------------------------------------------------------------- cam inertial torque */

typedef enum gd_lift_kind { GD_LIFT_TABLE = 0, GD_LIFT_HARMONIC = 1 } gd_lift_kind;

/* Valve lift s(theta) (m) vs cam angle theta (rad) over one cam revolution. */
typedef struct gd_lift_law {
    gd_lift_kind kind;
    const gd_table *table; /* periodic, period 2 pi (borrowed) */
    gd_harmonic harmonic;  /* for GD_LIFT_HARMONIC (order 1 for once per revolution) */
} gd_lift_law;

/* s, s' = ds/dtheta, s'' at cam angle theta. */
GD_API double gd_lift_eval(const gd_lift_law *law, double theta, double *ds, double *d2s);
/* [Benini2004] Eq. 10: torque (N m) the camshaft supplies to one valve train of equivalent
 * mass m_eq (kg) at camshaft angle theta, speed W and acceleration Wdot:
 *   T = m_eq s'(theta - phase) [s''(theta - phase) W^2 + s'(theta - phase) Wdot]
 * It acts on the camshaft against its rotation. */
GD_API double gd_cam_torque(const gd_lift_law *law, double m_eq, double phase, double theta,
                            double w, double wdot);

/* ---------------------------------------------------------------- torque / force laws */

typedef enum gd_load_kind {
    GD_LOAD_CONSTANT = 0,       /* mean */
    GD_LOAD_HARMONIC_TIME = 1,  /* mean + amplitude cos(frequency t + phase) */
    GD_LOAD_HARMONIC_ANGLE = 2, /* mean + amplitude cos(frequency angle + phase), frequency
                                   is an order per radian of the DOF's total angle */
    GD_LOAD_TABLE_ANGLE = 3     /* mean + table(angle + phase) */
} gd_load_kind;

typedef struct gd_load_law {
    gd_load_kind kind;
    double mean, amplitude, frequency, phase;
    const gd_table *table; /* borrowed */
} gd_load_law;

/* Value (N or N m) at time t and total DOF angle (rad; nominal rotation plus torsion). */
GD_API double gd_load_eval(const gd_load_law *law, double t, double angle);
/* The same, with d value / d angle in *dangle (may be NULL). */
GD_API double gd_load_eval_grad(const gd_load_law *law, double t, double angle, double *dangle);
/* The mean over a period: `mean`, plus for a table in angle its average over one period
 * (midpoint rule on 4096 points: ~1e-7 relative for linear and spline tables). */
GD_API double gd_load_law_mean(const gd_load_law *law);

/* ---------------------------------------------------------------- prescribed motion */

typedef enum gd_prescribed_kind {
    GD_PRESCRIBED_NOMINAL = 0, /* the DOF follows its nominal motion: q = 0 (a shaft turning
                              exactly at its speed, or a fixed lateral DOF) */
    GD_PRESCRIBED_SPEED = 1,   /* total angle = speed t: q = (speed - nominal rate) t */
    GD_PRESCRIBED_TABLE = 2,   /* total angle (or displacement) vs time from a table */
    GD_PRESCRIBED_HARMONIC = 3 /* q = amplitude cos(frequency t + phase) */
} gd_prescribed_kind;

typedef struct gd_prescribed_law {
    gd_prescribed_kind kind;
    double speed;                       /* rad/s, for GD_PRESCRIBED_SPEED */
    double amplitude, frequency, phase; /* for GD_PRESCRIBED_HARMONIC */
    const gd_table *table;              /* borrowed; total value vs time */
} gd_prescribed_law;

/* q, q', q'' of the DOF's perturbation coordinate at time t, where nominal_rate is the
 * DOF's nominal speed (speed ratio x reference speed for rz, 0 otherwise). */
GD_API void gd_prescribed_eval(const gd_prescribed_law *law, double t, double nominal_rate,
                               double *q, double *qd, double *qdd);
/* The excitation frequencies (rad/s) the motion imposes with the DOF's nominal speed
 * nominal_rate, written to w (at most cap): their count, or -1 with the reason in msg
 * when the motion is not periodic with the nominal motion (an angle table, or a speed
 * other than the nominal one). */
GD_API int gd_prescribed_frequencies(const gd_prescribed_law *law, double nominal_rate, double *w,
                                     int cap, char *msg, size_t cap_msg);

#endif
