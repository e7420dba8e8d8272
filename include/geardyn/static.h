/* Static analysis: the equilibrium K q = f of a model under its mean loads
 * (docs/static.md). The loads are the model's excitation loads at their mean value, an
 * optional input torque, and gravity (`gravity:`) on every mass; K is the system's
 * stiffness at the reference speed (speed tables of bearings at that speed). Held DOFs
 * (q = 0) are the model's prescribed DOFs, and, for each gear train left free to turn
 * as a rigid body, one torsion DOF (the torque balance: the train's net torque is
 * reacted there). Any other free rigid-body motion (a shaft with no bearing) is an
 * input error naming it.
 *
 * Laws (docs/laws.md): the model's laws that carry a static load (GD_LAW_SUPPORT: a
 * journal or rolling bearing, a polynomial spring) hold their directions, and the
 * equilibrium K q = f + sum f_law(q) is solved by Newton's method (the laws at the
 * reference speed, velocities zero): a rotor on journal bearings settles at its
 * eccentricity. Each law's records at the equilibrium are in the result. When the laws
 * find no equilibrium (a journal bearing at speed 0 carries nothing), GD_EINPUT says so.
 *
 * Results: the displacement of every node, the reactions of the bearings, springs and
 * held DOFs, the force of every mesh and its misalignment: the relative tilt of the two
 * gears in and out of the plane of action and the ISO 6336-1 mesh misalignment f_sh
 * (the tilt in the plane of action times the face width).
 *
 * Ownership and threads: gd_static_run returns a result the caller frees with
 * gd_static_free; it owns every array. The system (and its model) is only read: several
 * runs may use one system at once from different threads. No global state.
 */
#ifndef GEARDYN_STATIC_H
#define GEARDYN_STATIC_H
#include "geardyn/export.h"
#include "geardyn/system.h"

typedef struct gd_static_options {
    double speed;        /* reference speed for the bearings' speed tables, rad/s; < 0 (the
                            default): the model's speed */
    double input_torque; /* N m, about the input node's shaft in its sense of rotation
                            (positive drives the train); 0: none (the default) */
    int input_node;      /* node the input torque acts on (rz); -1: the reference shaft's
                            first node */
    int hold_node;       /* node whose torsion holds its free train; -1: automatic: the
                            input when no input torque is given, else the last node of the
                            last shaft of the train (the output) */
    int loads;           /* 1 (default): the model's excitation loads at their mean */
    int gravity;         /* 1 (default): the model's gravity, if any */
} gd_static_options;

/* Reaction of a bearing or spring on the shaft at its node (the force it exerts on the
 * node; for a support between two nodes the other node receives the opposite). */
typedef struct gd_static_reaction {
    double force[3];  /* x, y, z: N */
    double moment[3]; /* about x, y, z: N m */
} gd_static_reaction;

/* One held DOF: the force (N) or torque (N m) the hold applies to keep it at 0. */
typedef struct gd_static_hold {
    int node;
    gd_dof dof;
    int prescribed; /* 1: a prescribed DOF of the model; 0: a torque-balance hold */
    double reaction;
} gd_static_hold;

typedef struct gd_static_mesh {
    double force;             /* along the contact normal, N (> 0: drive flanks loaded) */
    double on_driver[6];      /* force (N) and moment (N m) on the driver gear's node: F a */
    double on_driven[6];      /* the same on the driven gear */
    double tangential;        /* F cos(beta_b) cos(alpha_wt): circumferential, N */
    double radial;            /* F cos(beta_b) sin(alpha_wt), N */
    double axial;             /* F sin(beta_b), N */
    double tilt_in_plane;     /* relative tilt driver - driven turning the axes within the
                                 plane of action (rad): the one that misaligns the flanks */
    double tilt_out_of_plane; /* relative tilt out of the plane of action, rad */
    double face_width;        /* b, m; 0: unknown */
    double f_sh;              /* b tilt_in_plane: mesh misalignment from the deformations
                                 (ISO 6336-1 f_sh, signed), m; NAN when b is unknown */
    double f_beta_x;          /* ISO 6336-1 equivalent misalignment |f_sh| (no
                                 manufacturing part f_ma), m; NAN when b is unknown */
} gd_static_mesh;

#define GD_STATIC_LAW_RECORDS 8
/* A law at the static state: its records (fx, fy, ecc of a journal bearing...). */
typedef struct gd_static_law {
    const char *name; /* the law's name (owned by the model) */
    const char *type; /* its type's name (static) */
    int nrecords;     /* the type's records, at most GD_STATIC_LAW_RECORDS */
    const char *record_names[GD_STATIC_LAW_RECORDS]; /* static strings of the type */
    const char *record_units[GD_STATIC_LAW_RECORDS];
    double records[GD_STATIC_LAW_RECORDS];
} gd_static_law;

typedef struct gd_static_result {
    int ndof, nnodes, nbearings, nsprings, nmeshes, nholds;
    double speed;
    double *q; /* ndof: displacement of the active DOFs (m, rad) */
    double *f; /* ndof: the applied loads (N, N m) */
    double *u; /* nnodes x 6 (x, y, z, rx, ry, rz): node displacements (0 inactive) */
    gd_static_reaction *bearings; /* nbearings */
    double *springs;              /* nsprings: force or torque on node1 along its DOF */
    gd_static_mesh *meshes;       /* nmeshes */
    gd_static_hold *holds;        /* nholds */
    double *law_forces;           /* ndof: the laws' forces on the DOFs at the state (N, N m;
                                     0 without laws): K q = f + law_forces */
    int nlaws;                    /* the laws that took part in the equilibrium */
    gd_static_law *laws;          /* nlaws */
    /* with an input torque: its node (else -1) and the whole mean torque applied there
     * about the shaft in its sense of rotation, the input torque plus the model's own
     * loads at that node (issue 35: --torque adds to them) */
    int input_node;
    double input_torque_total;
} gd_static_result;

GD_API void gd_static_options_init(gd_static_options *opt);
/* GD_EINPUT: a free rigid-body motion other than a train's torsion (named in the
 * message), or bad options (node out of range). */
GD_API gd_status gd_static_run(const gd_system *sys, const gd_static_options *opt,
                               gd_static_result **out, gd_error *err);
GD_API void gd_static_free(gd_static_result *res);

/* The operating point of the linear analyses at the static state (docs/bearings.md):
 * sets sys's operating point (gd_system_set_operating_point of geardyn/system.h) to
 * the loads (mean loads, gravity, the input torque of opt) and the holds (prescribed
 * DOFs, one torsion DOF per free gear train) of gd_static_run under opt, so that
 * modal, campbell, frf and unbalance linearise the laws about that equilibrium at each
 * speed. With check, the equilibrium is solved at opt's speed (or the model's) and its
 * absence is the located GD_EINPUT of gd_static_run. Nothing to do without laws. Not
 * thread-safe against analyses on sys (it writes sys). */
GD_API gd_status gd_static_operating_point(gd_system *sys, const gd_static_options *opt, int check,
                                           gd_error *err);

/* Planet load sharing of planetary set `set` at the static state res of sys
 * (docs/planetary.md): each planet's sun-planet and ring-planet mesh forces along their
 * lines of action (N, > 0 compressing the teeth as a driving sun does) and its bearing's
 * force (N, the magnitude), and the load-sharing factor K_gamma = N max F_sun / sum F_sun (signed
 * in the sense of the sum; a negative F_sun: that planet's teeth would separate)
 * (ISO 6336-1 / AGMA 6123; 1 for equal sharing). The planets' pin errors
 * (gd_planetary.pin_error) load the static analysis. */
typedef struct gd_static_planetary_loads {
    int nplanets;
    double sun_force[GD_PLANETARY_MAX_PLANETS], ring_force[GD_PLANETARY_MAX_PLANETS];
    double bearing_force[GD_PLANETARY_MAX_PLANETS];
    double load_sharing;
} gd_static_planetary_loads;
GD_API gd_status gd_static_planetary(const gd_system *sys, const gd_static_result *res, int set,
                                     gd_static_planetary_loads *out, gd_error *err);

#endif
