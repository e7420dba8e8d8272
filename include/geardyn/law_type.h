/* The nonlinear-law registry: one law, one file (docs/architecture.md, "Laws").
 *
 * A law is a force on a few DOFs that is not the linear k a a^T and c a a^T the system
 * assembles: a squeeze film damper, an applied load, a polynomial spring, regularised
 * friction, a user's own law. Each kind is one constant gd_law_type in one file under
 * src/laws/ (as an element kind is one gd_element_type): its parameters (names,
 * quantities, defaults, bounds: the model reader and the builder read and check them
 * from this table), the DOFs it acts on, its force and the rank-one structure of its
 * Jacobian, its excitation frequencies, its records and its linearisation. The time
 * integrators, the Craig-Bampton reduction, harmonic balance, the periodic fundamental,
 * the record parser of the CLI and the Python package loop over the table and never
 * switch on the kind.
 *
 * Local DOFs. An instance acts on ndofs DOFs dof[0..ndofs-1] (system DOF indices, -1: a
 * DOF that is absent or grounded, whose motion is zero). The type's `dirs` give the
 * direction of each local DOF at the instance's node and then at its second node (a
 * law between two nodes: [dirs at node, dirs at node2]); a type with ndirs = 0 acts in
 * one direction chosen per instance (`dir`). The law sees its local motion only: q and
 * q' of its local DOFs, and `rate`, their nominal speeds (a torsional DOF's total angle
 * is rate t + q).
 *
 * Jacobian. The generalised force f (added to the equations of motion's right-hand
 * side) has derivatives that are sums of rank-one terms with a structure fixed per
 * instance, df/dq = sum_k jq_k u_k w_k^T and df/dq' = sum_k jv_k u_k w_k^T, u_k and w_k
 * local vectors from `term`, jq_k and jv_k computed with the force. Harmonic balance
 * and Newton use exactly these (src/periodic/lowrank.c groups terms with one u).
 *
 * Ownership and threads: types are constants; an instance (gd_law) is a plain value the
 * caller owns (its `data` and `user` pointers are borrowed: they must outlive every
 * problem made from it). Every op is a pure function of its arguments (a law keeps
 * no state between calls; an instance's `mode` and `hold` are set by its caller, the
 * integrator), so one instance may be evaluated from any number of threads.
 */
#ifndef GEARDYN_LAW_TYPE_H
#define GEARDYN_LAW_TYPE_H
#include <stddef.h>

#include "geardyn/error.h"
#include "geardyn/export.h"
#include "geardyn/units.h"

#define GD_LAW_MAX_DOFS 12
/* 16 parameters and 25 terms: a rolling bearing from its geometry (14 values, its 5 x 5
 * stiffness as 25 rank-one terms; rolling_bearing_5dof.c). Raised from 12 and 8 in
 * library version 0.2.0: gd_law and gd_model_law grew, an ABI change. */
#define GD_LAW_MAX_PARAMS 16
#define GD_LAW_MAX_TERMS 25
#define GD_LAW_NAME_MAX 48
#define GD_LAW_MAX_SWITCHES 8

/* Flags of a type (gd_law_type.flags) or of one instance (gd_law_type.instance_flags). */
enum {
    /* the force is continuously differentiable in q and q' */
    GD_LAW_SMOOTH = 1u << 0,
    /* the force depends on time only, not on q or q' (a load of time): the
     * generalized-alpha integrator solves such steps without iterating */
    GD_LAW_TIME_ONLY = 1u << 1,
    /* the force grows with the displacement in the law's directions (a bearing, a
     * spring): `static` counts the law as holding those directions and solves the
     * equilibrium with it (docs/static.md) */
    GD_LAW_SUPPORT = 1u << 2,
    /* part of the force, k a a^T and c a a^T, is assembled in the system's K and C (a
     * gear mesh's linear stiffness and damping): the law's force is the rest, and the
     * integrators sum it after the linear terms (and before the other laws' terms in
     * the local form) */
    GD_LAW_ASSEMBLED = 1u << 3,
    /* instance: the force is linear and time-invariant (an assembled law whose stiffness
     * is not time-varying and has no switches): the generalized-alpha step is linear */
    GD_LAW_LINEAR = 1u << 4,
    /* instance: affine in q and q' within each mode (the problem's positions that the
     * law's tables are read at are prescribed): the generalized-alpha step is exact
     * once the modes it assumed hold */
    GD_LAW_PIECEWISE = 1u << 5,
    /* instance: the generalized-alpha tangent holds the law's term 0 (u = w) by a
     * rank-one update (an assembled law that differs from its assembled part) */
    GD_LAW_TANGENT = 1u << 6,
    /* instance: the law adds a configuration-dependent inertia on its DOFs
     * (gd_law_type.inertia: a cam's m_eq s'(theta)^2): the integrators that solve for
     * the accelerations add it to the mass matrix (CVODE's right-hand side by a
     * low-rank update; generalized-alpha and harmonic balance refuse it) */
    GD_LAW_INERTIA = 1u << 7,
    /* the law's own clock turns at the reference speed it was built for (a rolling
     * bearing's cage angle is its spin times t): a run-up or speed table refuses it */
    GD_LAW_CONSTANT_SPEED = 1u << 8,
    /* the law acts in those of its directions the model keeps: a direction the model's
     * `dofs:` leaves out everywhere (a rotor without its axial DOF) stays at zero motion
     * rather than being an error (a rolling bearing from geometry: radial, axial, tilt) */
    GD_LAW_MODEL_DIRS = 1u << 9
};

/* Bounds of a parameter. */
typedef enum gd_law_bound {
    GD_LAW_ANY = 0,     /* any finite value */
    GD_LAW_NONNEG = 1,  /* >= 0 */
    GD_LAW_POSITIVE = 2 /* > 0 */
} gd_law_bound;

/* One scalar parameter: its key in model files, its quantity (units accepted there),
 * its default (NAN: required) and its bound. */
typedef struct gd_law_param {
    const char *name;
    gd_qty qty;
    double def;
    gd_law_bound bound;
    const char *help; /* one line, for errors and docs */
} gd_law_param;

/* One output quantity of an instance (recorded by transient and periodic). */
typedef struct gd_law_record {
    const char *name; /* "force", "ecc": --record LAW:NAME */
    const char *unit; /* SI unit ("N", "m", "-") */
} gd_law_record;

typedef struct gd_law_type gd_law_type;

/* An instance of a law. */
typedef struct gd_law {
    const gd_law_type *type;
    char name[GD_LAW_NAME_MAX]; /* for records and messages */
    int ndofs;
    int dof[GD_LAW_MAX_DOFS];     /* system DOF indices; -1: absent or ground */
    double rate[GD_LAW_MAX_DOFS]; /* nominal speed of each local DOF, rad/s (set by the
                                     problem from its reference speed) */
    double spin[2]; /* nominal spin about +z of the shaft of node (and node2), rad/s: the
                       first local DOF of each side tells the node (set by the problem) */
    double value[GD_LAW_MAX_PARAMS]; /* SI, in the order of type->params */
    const void *data;                /* typed parameters of laws made in code (a load law with its
                                        table); borrowed */
    void *user; /* user laws: the user's pointer, passed back through the ops */
    /* Discrete state of a law with switches (gd_law_type.nswitches > 0), e.g. a mesh's
     * contact flank: the force uses this mode, which the integrator keeps frozen between
     * the located sign changes of the switch functions (0 at gd_law_init). */
    int mode;
    /* Homotopy of a law with switches, 0..1: its force in a mode other than
     * gd_law_type.hold_mode is blended with the force in that mode (frequency-domain
     * starts, gd_transient_hold_drive; 0 in integration). */
    double hold;
} gd_law;

/* The motion a law sees: time and its local q, q' (length ndofs). */
typedef struct gd_law_point {
    double t;
    const double *q, *v;
} gd_law_point;

struct gd_law_type {
    const char *name;    /* model-file `type:` and the registry key */
    const char *summary; /* one line */
    unsigned flags;      /* GD_LAW_* of every instance */
    /* flags of one instance (NULL: flags) */
    unsigned (*instance_flags)(const gd_law *law);
    const gd_law_param *params;
    int nparams;
    /* directions (gd_dof: 0 x .. 5 rz) of the local DOFs at each node; ndirs = 0: one
     * direction per instance */
    const int *dirs;
    int ndirs;
    int two_nodes; /* 1: the law acts between a node and node2 (or ground) */
    /* 1: each instance sets its own ndofs (1 .. GD_LAW_MAX_DOFS) and dof[] (a gear mesh:
     * its mesh vector's DOFs); dirs, ndirs and two_nodes then only describe the first */
    int var_dofs;
    /* Checks beyond the parameters' bounds (NULL: none): 0 ok, else writes the
     * offending parameter's name to *field and a message (what and the fix) to msg. */
    int (*check)(const gd_law *law, const char **field, char *msg, size_t cap);
    /* The rank-one structure: nterms terms, term k's local vectors u and w (length
     * ndofs, zeroed by the caller). */
    int nterms;
    void (*term)(const gd_law *law, int k, double *u, double *w);
    /* Adds the generalised force at x to f (length ndofs); jq, jv (length nterms, may
     * be NULL) receive the term coefficients of df/dq and df/dq'. */
    void (*force)(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv);
    /* Excitation frequencies (rad/s, > 0) the instance imposes by itself at its
     * nominal rates, written to w (at most cap); returns their count, or -1 with a
     * message in msg when it has none that is periodic (a table that is not). NULL:
     * none (an autonomous law). */
    int (*frequencies)(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg);
    const gd_law_record *records;
    int nrecords;
    double (*record)(const gd_law *law, int k, const gd_law_point *x);
    /* Linearisation about x (velocities usually zero): K = -df/dq, C = -df/dq' (ndofs x
     * ndofs, column-major, zeroed by the caller). NULL: none. */
    void (*linearize)(const gd_law *law, const gd_law_point *x, double *K, double *C);
    /* Configuration-dependent inertia of an instance flagged GD_LAW_INERTIA: adds the
     * force at x to f (as force does, without the Jacobian) and to m (length ndofs) the
     * diagonal mass the law puts on its local DOFs at x, so that its generalised force
     * is f - m a, a the DOF's absolute acceleration: q'' plus, in a run-up, its nominal
     * one (a cam's follower mass reduced to the camshaft, m_eq s'^2: [Benini2004] Eq.
     * 10's s'^2 dW/dt term). One evaluation for both, which the integrators call
     * instead of force. NULL: none. */
    void (*inertia)(const gd_law *law, const gd_law_point *x, double *f, double *m);

    /* Contact switches (all NULL / 0: a smooth law). A law with nswitches > 0 has a
     * discrete mode (gd_law.mode) its force uses; switch k's function g_k(x) changes
     * sign where the mode changes (an event the integrators locate: CVODE's roots,
     * generalized-alpha's check per step, the saltation of the monodromy). `switches`
     * writes g_0 .. g_{nswitches-1} at x to g (one evaluation of the law for all). */
    int nswitches;
    void (*switches)(const gd_law *law, const gd_law_point *x, double *g);
    /* The mode the motion x is in (independent of law->mode). */
    int (*mode_at)(const gd_law *law, const gd_law_point *x);
    /* The mode after the located crossings dir[k] (CVODE's directions: +1 g_k rising, -1
     * falling, 0 no crossing) from mode `mode`. */
    int (*mode_after)(const gd_law *law, int mode, const int *dir);
    /* The switch a change from mode `from` to `to` crosses (the saltation's surface). */
    int (*switch_of)(const gd_law *law, int from, int to);
    /* A switch value within tol of zero is on the switch, not a crossing the root
     * finding missed. */
    double (*switch_tol)(const gd_law *law);
    /* The mode of a static equilibrium at x from mode law->mode (modes held as smooth
     * laws continued beyond their intervals: a mesh whose drive-flank force pulls moves
     * to the coast flank); law->mode when it stays. NULL: a static start leaves the
     * mode alone. */
    int (*static_mode)(const gd_law *law, const gd_law_point *x);
    int hold_mode; /* the mode a hold blends with */
    /* (The mesh, gd_law_backlash_mesh, is the built-in law with switches: its modes are
     * gd_contact, its switches d_e - b and d_e + b.) */
};

/* The instance's flags (type->instance_flags or type->flags). */
GD_API unsigned gd_law_flags(const gd_law *law);
/* The instance's number of switches: type->nswitches, or 0 when the instance is
 * GD_LAW_SMOOTH (a mesh without backlash). */
GD_API int gd_law_nswitches(const gd_law *law);

/* The built-in types a model's `laws:` list takes, in registry order. The gear mesh,
 * gd_law_backlash_mesh, is a built-in type too, declared under `meshes:` (its data, a
 * gd_mesh_law_data of geardyn/laws.h, made by the transient problem from a gd_tr_mesh):
 * it is not in this list; nor is the cam torque, gd_law_cam_torque, declared under
 * `cam_torques:` (its data, the valve's gd_lift_law, from a gd_tr_cam). */
GD_API extern const gd_law_type *const gd_law_types[];
GD_API extern const int gd_nlaw_types;
GD_API extern const gd_law_type gd_law_sfd, gd_law_load, gd_law_polynomial_spring, gd_law_friction,
    gd_law_rolling_bearing, gd_law_rolling_bearing_5dof, gd_law_journal_bearing,
    gd_law_unilateral_spring, gd_law_backlash_mesh, gd_law_cam_torque, gd_law_churning_drag,
    gd_law_bearing_drag, gd_law_synchro_cone, gd_law_gear_release;
/* The built-in type named name, or NULL. */
GD_API const gd_law_type *gd_law_type_find(const char *name);

/* An instance of type with its parameters at their defaults (required ones NAN), no
 * DOFs (every dof -1, ndofs = the type's count) and name. */
GD_API void gd_law_init(gd_law *law, const gd_law_type *type, const char *name);
/* Checks a type's table (a user type before use: names, counts within the limits, ops
 * present) and an instance's parameters (finite, within bounds, the type's check).
 * GD_EINPUT names the parameter (field) and the fix. */
GD_API gd_status gd_law_type_validate(const gd_law_type *type, gd_error *err);
GD_API gd_status gd_law_check(const gd_law *law, gd_error *err);
/* Adds the force at x to f (ndofs) and its linearisation K = -df/dq, C = -df/dq' to K
 * and C (ndofs x ndofs, column-major; the type must have a linearize op): one evaluation
 * of the force where the linearisation is read off the law's terms, as a Newton
 * iteration wants both. */
GD_API void gd_law_force_tangent(const gd_law *law, const gd_law_point *x, double *f, double *K,
                                 double *C);
/* Index of parameter name in the type's table, or -1. */
GD_API int gd_law_param_index(const gd_law_type *type, const char *name);
/* Index of record name, or -1. */
GD_API int gd_law_record_index(const gd_law_type *type, const char *name);

#endif
