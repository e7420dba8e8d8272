/* Time integration of the nonlinear, time-varying system (docs/transient.md):
 *
 *   M q'' + (C + C_b(W) + W G) q' + (K + K_b(W)) q = f(t, q, q') - sum_m (F_m - k_m d_m - c_m d_m')
 * a_m
 *
 * at a constant reference speed W, where q are the system's DOFs (perturbations of the
 * nominal motion: a torsional DOF's total angle is ratio W t + q), d_m = a_m . q the
 * deformation of mesh m, k_m, c_m the linear mesh terms the system assembled (removed
 * for the meshes described here) and F_m the mesh force law (time-varying stiffness,
 * damping, static transmission error, backlash). f holds squeeze film damper forces,
 * unbalance forces, applied loads and cam inertial torques.
 *
 * Built once (gd_transient_new: matrices at the speed, sparse Cholesky of the mass,
 * mesh vectors, workspaces); gd_transient_run integrates with SUNDIALS CVODE (BDF or
 * Adams, Newton iteration with GMRES preconditioned by a sparse LU of M + g D + g^2 K)
 * and locates every contact change of a backlash mesh (CVodeRootInit on d -/+ b; the
 * contact state is frozen between located events, so the right-hand side is smooth on
 * every step). The right-hand side allocates nothing and assembles nothing.
 *
 * Prescribed DOFs are removed from the unknowns: their q, q', q'' come from their law,
 * and their inertia, damping and stiffness couplings act on the free DOFs as forces.
 * Tables and lift laws are borrowed: they must outlive the problem. One run (or
 * monodromy) at a time per problem (it holds the run's contact states); separate problems
 * may run in parallel.
 *
 * Ownership and threads: gd_transient_new returns a problem the caller frees with
 * gd_transient_free; the system, the spec's arrays and its tables are borrowed and must
 * outlive it. gd_transient_run returns a result freed with gd_transient_result_free.
 */
#ifndef GEARDYN_TRANSIENT_H
#define GEARDYN_TRANSIENT_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/law_type.h"
#include "geardyn/laws.h"
#include "geardyn/sparse.h"
#include "geardyn/system.h"

/* A mesh with a nonlinear or time-varying law. Its linear k a a^T and c a a^T are taken
 * out of K and C and the force F a is applied instead. Stiffness k(theta) of the driver's
 * angle theta = s (ratio W t + q_rz) + angle_offset, s = +1 when the driver turns about
 * +z (the mesh's driver_sense): from `tvms` (N/m, periodic in the mesh period) or the
 * constant `stiffness`. */
typedef struct gd_tr_mesh {
    int mesh;             /* model mesh index */
    const gd_table *tvms; /* k_drive(theta), N/m; NULL: constant `stiffness` */
    double stiffness;     /* N/m, used when tvms is NULL */
    double coast_scale;   /* k_coast = coast_scale * k_drive (per-flank stiffness); 0: one-sided
                             contact, no coast flank (separated beyond it) */
    double damping;       /* constant part of the contact damping, N s/m */
    double damping_per_k; /* c = damping + damping_per_k * k(theta), s */
    double damping_free;  /* damping while separated (c0), N s/m */
    int backlash;         /* 1: backlash law with gap b on each flank */
    double gap;           /* b, m */
    const gd_table *ste;  /* static transmission error e(theta), m (NULL: none) */
    double angle_offset;  /* rad, added to the driver angle for tvms and ste */
} gd_tr_mesh;
/* Defaults from the model: constant model stiffness and damping, coast_scale 1, no
 * backlash, no STE. */
GD_API void gd_tr_mesh_init(const gd_system *sys, int mesh, gd_tr_mesh *m);

/* Squeeze film damper between a journal node and ground (or a housing node), acting on
 * the x, y DOFs. */
typedef struct gd_tr_sfd {
    int node, node2; /* node2 = -1: ground */
    gd_sfd_params params;
} gd_tr_sfd;

/* Applied force or torque on one DOF; angle = the DOF's total angle (nominal + q). */
typedef struct gd_tr_load {
    int dof; /* active DOF index (gd_system_dof) */
    gd_load_law law;
} gd_tr_load;

/* One valve train on a camshaft torsional DOF ([Benini2004] Eq. 10). The cam angle is the
 * camshaft's rotation in its own sense, theta = s (ratio W t + q), W = s (ratio W + q');
 * the torque acts against the rotation. */
typedef struct gd_tr_cam {
    int dof;                /* camshaft rz DOF */
    const gd_lift_law *law; /* borrowed */
    double mass;            /* equivalent mass m_eq, kg */
    double phase;           /* rad of cam angle */
} gd_tr_cam;

/* A DOF whose motion is prescribed (removed from the unknowns). */
typedef struct gd_tr_prescribed {
    int dof;
    gd_prescribed_law law;
} gd_tr_prescribed;

typedef struct gd_transient_spec {
    const gd_tr_mesh *meshes;
    int nmeshes;
    const gd_tr_sfd *sfds;
    int nsfds;
    const gd_tr_load *loads;
    int nloads;
    const gd_tr_cam *cams;
    int ncams;
    const gd_tr_prescribed *prescribed;
    int nprescribed;
    /* Laws of the registry (include/geardyn/law_type.h): user laws and the laws a
     * model's `laws:` list declares, with system DOF indices. The dampers and loads
     * above are laws too (gd_law_sfd, gd_law_load): the problem makes their instances
     * itself (gd_transient_spec_laws). */
    const gd_law *laws;
    int nlaws;
    int unbalances;       /* 1: the model's unbalances, at their shafts' nominal speeds */
    int cam_acceleration; /* 1: keep the m_eq s'^2 dW/dt term of Eq. 10 (an angle-
                             dependent inertia, solved exactly by a low-rank update) */
} gd_transient_spec;

typedef struct gd_transient gd_transient;

/* Every law of a spec as registry instances, in the problem's order: one
 * gd_law_backlash_mesh per mesh (its gd_mesh_law_data in the same block), one gd_law_sfd
 * per damper, one gd_law_load per load, then spec->laws; their nominal rates set at the
 * reference speed (rad/s), every instance checked (gd_law_check). *out (length *n, NULL
 * when 0) is the caller's to free(). Errors: GD_EINPUT naming the law and field. */
GD_API gd_status gd_transient_spec_laws(const gd_system *sys, const gd_transient_spec *spec,
                                        double speed, gd_law **out, int *n, gd_error *err);

/* Builds the problem at reference speed W (rad/s). */
GD_API gd_status gd_transient_new(const gd_system *sys, const gd_transient_spec *spec, double speed,
                                  gd_transient **out, gd_error *err);
GD_API void gd_transient_free(gd_transient *tr);

/* The same problem reduced (Craig-Bampton): the DOFs the laws act on (meshes, dampers,
 * loads, unbalances, prescribed DOFs) stay physical; the others are replaced by their
 * fixed-interface modes below cutoff (rad/s) and the static constraint modes. Every
 * integrator runs it; records, q0/v0 and q_end/v_end stay in the system's DOFs. Not
 * with cam valve trains (GD_EINPUT). */
GD_API gd_status gd_transient_new_reduced(const gd_system *sys, const gd_transient_spec *spec,
                                          double speed, double cutoff, gd_transient **out,
                                          gd_error *err);
/* Size of the problem's coordinates; nkept: physical DOFs kept, nmodes: interior modes
 * (either may be NULL; an unreduced problem: all kept, 0 modes). */
GD_API int gd_transient_reduced_size(const gd_transient *tr, int *nkept, int *nmodes);

/* The same problem integrated on the condensed structure (docs/transient.md, "Condensed
 * transient"; geardyn/condense.h): the coordinates are the DOFs the laws (meshes, loads,
 * drag, dampers) and unbalances act on; the state is the structure's modes up to cutoff
 * (rad/s; 0: every mode, exact; < 0: the rule max(5 x the highest excitation frequency,
 * 2.5 x the highest mesh contact frequency sqrt(k / m_e))), the others entering as
 * their static correction. Runs with bdf or adams (auto: bdf), started at rest; records,
 * q_end and v_end in the system's DOFs. GD_EINPUT: prescribed DOFs, cams with their
 * inertia, nothing to condense onto; GD_ENUMERIC from the condensation (a stiffness
 * singular beyond its rigid modes, a rigid mode with damping to ground). */
GD_API gd_status gd_transient_new_condensed(const gd_system *sys, const gd_transient_spec *spec,
                                            double speed, double cutoff, gd_transient **out,
                                            gd_error *err);
typedef struct gd_tr_condensed_info {
    int ncoords, nstates;     /* coordinates (law DOFs), states */
    int nkept, ndiscarded;    /* elastic modes kept (a pair once), replaced by the correction */
    int nrigid;               /* rigid-body modes */
    double cutoff;            /* rad/s (0: every mode) */
    double first_discarded;   /* |lambda| of the lowest discarded mode, rad/s (INFINITY: none) */
    double excitation;        /* highest excitation frequency of the laws, rad/s (0: none) */
    double contact;           /* highest mesh contact frequency, rad/s (0: none) */
    double static_correction; /* largest entry of G */
    double estimate; /* truncation estimate of the receptance at `excitation` over its largest
                        entry (gd_condense_receptance; 0 when every mode is kept) */
} gd_tr_condensed_info;
/* The default of `transient` (docs/transient.md, "Condensed transient"): 1 when the
 * condensed transient pays for the (full) problem tr: at least GD_TRANSIENT_CONDENSE_DOFS DOFs,
 * laws and unbalances acting on at most one in GD_TRANSIENT_CONDENSE_FEW of them, a law
 * that is not linear as assembled (a linear model runs exactly by the lti method), and
 * nothing the condensed transient refuses (prescribed DOFs, cam inertia). why (len)
 * receives the reason either way. */
#define GD_TRANSIENT_CONDENSE_DOFS 100
#define GD_TRANSIENT_CONDENSE_FEW 4
GD_API int gd_transient_condense_pays(const gd_transient *tr, char *why, size_t len);
/* 1 and info filled when tr is condensed, else 0 (info zeroed). */
GD_API int gd_transient_condensed_info(const gd_transient *tr, gd_tr_condensed_info *info);

/* The state layout: y = [q_f; q_f'] over the nfree free DOFs (in increasing DOF order). */
GD_API int gd_transient_nstates(const gd_transient *tr);
/* The switch functions of the problem's laws (gd_law_nswitches: two per backlash mesh);
 * 0 when no law has a discrete mode. */
GD_API int gd_transient_nswitches(const gd_transient *tr);
/* The right-hand side y' = f(t, y) with the current contact states (for benchmarks and
 * tests). */
GD_API void gd_transient_rhs(gd_transient *tr, double t, const double *y, double *ydot);
/* Sets every backlash mesh's contact state from the deformation in y at time t. */
GD_API void gd_transient_set_contacts(gd_transient *tr, double t, const double *y);

/* ---- Local form of the forces (harmonic balance, variational equations) ----
 * With each backlash mesh's contact state taken from its deformation (not frozen), the
 * equations of the free DOFs are
 *   M_ff q'' + D_ff q' + K_ff q = f(t, q, q')
 * with M_ff, D_ff = C + W G, K_ff the linear matrices at the speed (meshes' model
 * stiffness and damping included) and f everything else: loads, unbalances, dampers, cam
 * torques, each described mesh's law minus its linear terms, the prescribed DOFs'
 * couplings. Its derivatives are sums of rank-one terms fixed when the problem is built,
 *   df/dq = sum_k sq_k(t) u_k w_k^T,   df/dq' = sum_k sv_k(t) u_k w_k^T,
 * u_k, w_k sparse over the free DOFs (a mesh: a a^T and a e_driver^T; a damper: its four
 * x-y pairs; a cam or an angle-dependent load: e e^T). Every law is the one the
 * integrator uses (gd_tr_mesh_law, gd_sfd_force_jacobian, gd_load_eval_grad). */
typedef struct gd_tr_term {
    int nu, nw;
    int u_idx[12], w_idx[12]; /* free DOF indices */
    double u[12], w[12];
} gd_tr_term;
/* The terms (owned by the problem). Not thread-safe on one problem. */
GD_API int gd_transient_terms(gd_transient *tr, const gd_tr_term **terms);
/* Views (borrowed, valid while tr lives) of M_ff, D_ff, K_ff (nfree x nfree). */
GD_API void gd_transient_matrices(const gd_transient *tr, gd_csc *M, gd_csc *D, gd_csc *K);
/* f (nfree) at (t, y = [q_f; q_f']) and the term derivatives sq, sv (gd_transient_terms'
 * count; either may be NULL). Sets the contact states from y (do not call during a run).
 * Cam torques with include_acceleration are not represented (the returned count of
 * gd_transient_terms is -1 then). */
GD_API void gd_transient_local(gd_transient *tr, double t, const double *y, double *f, double *sq,
                               double *sv);

typedef enum gd_tr_method {
    GD_TR_BDF = 0,
    GD_TR_ADAMS = 1,
    /* fixed-step generalized-alpha (Chung & Hulbert 1993): step, rho_inf; Newmark's
     * average acceleration at rho_inf = 1. rtol/atol and max_order are not used, nor
     * event location: contact changes are resolved to the step */
    GD_TR_GEN_ALPHA = 2,
    /* the method for the model and the accuracy asked (docs/transient.md): a linear
     * time-invariant model (no law, no cam, no prescribed DOF, every mesh linear; forced
     * by unbalances) by GD_TR_LTI, anything else by BDF; the result says which
     * (method_used, method_note) */
    GD_TR_AUTO = 3,
    /* linear time-invariant models only (GD_EINPUT otherwise): the unbalances' harmonic
     * response solved exactly, the free motion advanced by the (8,8) Pade approximant
     * of the exponential (order 16) at a step halved from the output interval until the
     * run agrees with the run at twice its step to rtol of every record's peak (and of
     * the end displacements); step, error_estimate in the result. max_step, step,
     * rho_inf, atol, locate_events are not used */
    GD_TR_LTI = 4
} gd_tr_method;
typedef enum gd_tr_init {
    GD_TR_INIT_REST = 0,   /* q = 0, q' = 0 on the free DOFs */
    GD_TR_INIT_STATIC = 1, /* static equilibrium under the loads at t_start (needs a
                              stiffness holding every free DOF) */
    GD_TR_INIT_GIVEN = 2   /* q0, v0 (length ndof; prescribed entries ignored) */
} gd_tr_init;

/* A speed profile of the reference shaft (docs/transient.md, "Run-up"): its speed
 * W(t), rad/s, and the angle phi(t) = integral from 0 to t of W, every shaft following
 * through its speed ratio (shaft s turns by ratio_s phi). GD_SPEED_RAMP: W = from until
 * t0, linear to `to` at t1, then `to`. GD_SPEED_TABLE: n >= 2 rows (t increasing, speeds
 * rad/s), linear between rows, held at the end rows. The speeds may not change sign.
 * Borrowed (the table's arrays too) for the run. */
typedef enum gd_speed_profile_kind { GD_SPEED_RAMP = 1, GD_SPEED_TABLE = 2 } gd_speed_profile_kind;
typedef struct gd_speed_profile {
    gd_speed_profile_kind kind;
    double from, to; /* ramp: rad/s */
    double t0, t1;   /* ramp: s, t1 > t0 */
    int n;           /* table rows */
    const double *t, *speed;
} gd_speed_profile;
/* GD_EINPUT naming the field when the profile is not as above. */
GD_API gd_status gd_speed_profile_check(const gd_speed_profile *p, gd_error *err);
/* The angle phi(t) (rad), speed W(t) (rad/s) and acceleration W'(t) (rad/s^2) at t (any
 * output may be NULL; a table costs O(rows)). Thread-safe. */
GD_API void gd_speed_profile_eval(const gd_speed_profile *p, double t, double *angle, double *speed,
                                  double *accel);

typedef struct gd_transient_options {
    double t_start, t_end;  /* s */
    double output_interval; /* s; 0: (t_end - record_from) / 1000 */
    double record_from;     /* records and statistics from this time (>= t_start) */
    double rtol;            /* default 1e-6 */
    double atol_q, atol_v;  /* absolute tolerances on q (m, rad) and q' (default 1e-12,
                               1e-9) */
    gd_tr_method method;    /* default GD_TR_BDF here (callers of the library keep their
                               numbers); geardyn transient, Python and studies default to
                               GD_TR_AUTO */
    gd_tr_init init;
    const double *q0, *v0;
    double max_step;   /* s; 0: none */
    long max_steps;    /* step limit (0: 50 million): CVODE's per output interval, and
                          a run that needs more (gen-alpha: span / step; BDF, Adams:
                          revolutions of the fastest DOF) is GD_EINPUT before it starts */
    int max_order;     /* 0: CVODE's (5 BDF, 12 Adams); 2 makes BDF A-stable, which
                          suits lightly damped stiff modes */
    int locate_events; /* 1 (default): root-finding on contact changes */
    double step;       /* GD_TR_GEN_ALPHA: largest step, s (0: output interval / 10); the
                          step is shortened to fit each output interval */
    double rho_inf;    /* GD_TR_GEN_ALPHA: spectral radius at infinite step, 0..1
                          (default 0.9); 1: no numerical dissipation */
    /* Optional progress report (NULL: none): called with the time reached, at every
     * output sample and about every 1/200 of the span before record_from. The library
     * prints nothing itself. */
    void (*progress)(double t, double t_start, double t_end, void *data);
    void *progress_data;
    /* Stroboscopic (Poincare) samples (NULL/0: none): the records and the state at these
     * times (increasing, within [t_start, t_end]), each reached as an output time of
     * CVODE (its interpolant at the order of the step), not read off the fixed-interval
     * samples. Borrowed for the run. */
    const double *sample_times;
    int nsample_times;
    /* Run-up (NULL: the constant reference speed of gd_transient_new, today's path
     * exactly): the nominal motion follows the profile; the gyroscopic term is W(t) G,
     * unbalance forces U (W^2 cos psi + W' sin psi, W^2 sin psi - W' cos psi) at each
     * shaft's angle psi, mesh stiffness, transmission error, cams, loads of angle and
     * the laws at the shafts' angles and speeds. Speed-table bearings stay at the
     * reference speed (the result's method_note says so). The inertia torque of the
     * nominal acceleration is taken as supplied by the drive (not applied: no wind-up).
     * Not with GD_TR_LTI (auto picks BDF), a reduced problem, a prescribed speed or
     * angle table, or a rolling-bearing law (GD_EINPUT). Borrowed for the run. */
    const gd_speed_profile *profile;
    /* GD_TR_BDF, GD_TR_ADAMS: 1 estimates the run's global error (CVODE controls only
     * the local error of each step, which does not bound it) by a second run at
     * tolerances 10 times tighter: error_estimate = their largest difference, relative
     * to each record's peak (contact states not compared; the end displacements' peak
     * when nothing is recorded), / 0.9 (the global error proportional to the
     * tolerance). The records are those of the run at rtol, unchanged. Costs that
     * second run (about 1.5 times the first). 0 (the default here: the library's
     * internal callers keep their cost): none, error_estimate -1. geardyn transient and
     * Python set 1. */
    int error_estimate;
} gd_transient_options;
GD_API void gd_transient_options_init(gd_transient_options *opt);

typedef enum gd_tr_record_kind {
    GD_REC_DISP = 0,        /* q[index] (m or rad, perturbation) */
    GD_REC_VEL,             /* q'[index] */
    GD_REC_ANGLE,           /* total angle of DOF index: nominal rate t + q */
    GD_REC_SPEED,           /* total speed of DOF index: nominal rate + q' */
    GD_REC_SPEED_RATIO,     /* total speed of index / total speed of index2 */
    GD_REC_MESH_FORCE,      /* force of model mesh index along its normal, N */
    GD_REC_MESH_DEFLECTION, /* d = a . q of model mesh index, m */
    GD_REC_MESH_STATE,      /* -1 coast, 0 separated, 1 drive */
    GD_REC_MESH_STIFFNESS,  /* k(theta), N/m */
    GD_REC_SFD_FX,          /* force on the journal of damper index (spec order), N */
    GD_REC_SFD_FY,
    GD_REC_SFD_ECCENTRICITY, /* e / c */
    GD_REC_LAW               /* record index2 (gd_law_type.records) of spec.laws[index] */
} gd_tr_record_kind;

typedef struct gd_tr_record {
    gd_tr_record_kind kind;
    int index, index2;
} gd_tr_record;
/* Records whose values change where a law of the problem changes mode (the contact state,
 * GD_REC_MESH_STATE, of each mesh law with switches), written to rec (at most cap); their
 * count. Floquet's steps are split where they change. */
GD_API int gd_transient_mode_records(const gd_transient *tr, gd_tr_record *rec, int cap);
/* Contact homotopy for frequency-domain solvers: with hold = h in (0, 1], every backlash
 * mesh's force off the drive flank becomes (1 - h) F(state) + h F(drive), so h = 1 is the
 * smooth problem with the teeth always in contact and h = 0 (the default, and what the
 * integrator always uses) the backlash law itself. Affects gd_transient_local and
 * gd_transient_record_value only. */
GD_API void gd_transient_hold_drive(gd_transient *tr, double hold);
/* Value of a record at (t, y = [q_f; q_f']) with the contact states from y (the local
 * form above; for frequency-domain solutions). */
GD_API double gd_transient_record_value(gd_transient *tr, const gd_tr_record *rec, double t,
                                        const double *y);
/* The values of nrec records at one state (one evaluation of the state for all; out of
 * length nrec). */
GD_API void gd_transient_record_values(gd_transient *tr, const gd_tr_record *rec, int nrec,
                                       double t, const double *y, double *out);
/* The free DOFs (indices into q_f) that gd_transient_record_value reads for rec, appended
 * to idx (at most cap; repeats possible): the DOF itself, a mesh's DOFs and its driver
 * angle, a damper's DOFs. Returns their count, or -1 when it cannot say (a reduced model,
 * whose recovered DOFs read every modal coordinate, or more than cap). Thread-safe. */
GD_API int gd_transient_record_dofs(const gd_transient *tr, const gd_tr_record *rec, int *idx,
                                    int cap);

/* The effective mass of spec mesh `mesh` along its line of action, kg: 1 / (a^T M_ff^-1 a)
 * with a the mesh vector on the free DOFs (a prescribed side has no motion to give: it
 * drops out), the mass an impact of the flanks moves before the stiffness acts (the
 * rattle intensity's m_e, geardyn/rattle.h; for two gears of inertia J1, J2 on base radii
 * r1, r2 alone on their nodes, 1 / (r1^2 / J1 + r2^2 / J2)). GD_EINPUT: no such mesh, a
 * reduced problem (its coordinates are not the mesh's), or a mesh on prescribed DOFs only.
 * Not thread-safe on one problem. */
GD_API gd_status gd_transient_mesh_mass(gd_transient *tr, int mesh, double *mass, gd_error *err);

/* min, max, mean, rms (root mean square of the value), peak-to-peak, standard deviation
 * over the recorded samples. */
typedef struct gd_tr_stats {
    double min, max, mean, rms, peak_to_peak, std;
} gd_tr_stats;

/* Contact history of a backlash mesh from record_from to t_end. */
typedef struct gd_tr_contact_stats {
    int contact_losses;                            /* drive -> separated */
    int coast_impacts;                             /* separated -> coast */
    int drive_impacts;                             /* separated -> drive (re-contact) */
    double separated_time, coast_time, drive_time; /* s */
} gd_tr_contact_stats;

/* One contact change of a backlash mesh at or after record_from (gd_transient_result's
 * log, in time order): an impact is a change from GD_CONTACT_SEPARATED to a flank, a
 * separation the change from a flank. velocity is the rate of the effective deflection
 * d_e = d - e(theta) at the change (m/s): the approach speed of the flanks, > 0 onto the
 * drive flank and < 0 onto the coast flank (src/signal/rattle.c reads the log). */
typedef struct gd_tr_contact_event {
    double t;
    int mesh;     /* spec mesh index (0 .. nmeshes - 1) */
    int from, to; /* gd_contact */
    double velocity;
} gd_tr_contact_event;

typedef struct gd_transient_result {
    int nout;  /* samples */
    double *t; /* nout */
    int nrecords;
    gd_tr_record *records;
    double *values; /* record r, sample k: values[r * nout + k] */
    gd_tr_stats *stats;
    int nmeshes; /* = spec nmeshes */
    gd_tr_contact_stats *contacts;
    /* every contact change of the meshes from record_from on (owned; NULL when none);
     * contact_events_lost counts changes left out when memory ran out */
    int ncontact_events, contact_events_lost;
    gd_tr_contact_event *contact_events;
    int ndof;
    double *q_end, *v_end; /* ndof, at t_end (prescribed DOFs from their law) */
    /* Poincare samples (options.sample_times): times, records (record r, sample k:
     * sample_values[r * nsamples + k]) and full q, v (sample k: sample_q[k * ndof + i]) */
    int nsamples;
    double *sample_t, *sample_values, *sample_q, *sample_v;
    /* solver statistics over the whole run */
    long steps, rhs_evals, lin_iters, prec_setups, events, reinits;
    double cpu_seconds;
    /* the method that ran (GD_TR_AUTO resolved) and what controlled its error:
     * GD_TR_LTI: the step of the run returned (s) and its estimated error, relative to
     * each record's peak: its largest difference to the run at half the step, or, where
     * the error is seen to fall as h^16, 1/65535 of that to the run at twice the step;
     * others: step 0 (adaptive or the given one), error_estimate -1 (CVODE: local
     * error control by rtol/atol), or with options.error_estimate its global estimate
     * (same measure as GD_TR_LTI's).
     * method_note: one line saying so, e.g. "auto: lti, step 1e-4 s, est. error 3e-7
     * <= rtol 1e-4" */
    gd_tr_method method_used;
    double step, error_estimate;
    char method_note[256];
} gd_transient_result;

GD_API gd_status gd_transient_run(gd_transient *tr, const gd_transient_options *opt,
                                  const gd_tr_record *records, int nrecords,
                                  gd_transient_result **out, gd_error *err);
GD_API void gd_transient_result_free(gd_transient_result *r);

/* Monodromy matrix of the variational equations about the motion that starts from
 * state y0 (length gd_transient_nstates, layout [q_f; q_f']) at time t0, over one
 * period T: phi (nstates x nstates, column-major) = d y(t0 + T) / d y0, integrated
 * with CVODE at opt's tolerances (contact states updated along the orbit); y_end
 * (may be NULL) receives y(t0 + T).
 * The variational equations Phi' = J Phi are integrated with the state as one system;
 * J v is a central directional difference of the right-hand side (contact states frozen;
 * step eps^(1/3) of each state's scale |y_i| + atol_i / rtol: error ~1e-11 relative),
 * and Phi jumps by the saltation matrix at every contact change of a backlash mesh.
 * Uses opt's rtol, atol_q, atol_v (also for Phi, scaled per column), method, max_step,
 * max_steps, max_order, locate_events; the other options are ignored. Cost: 1 + 2
 * nstates right-hand sides per evaluation of the augmented system of nstates (nstates
 * + 1) unknowns. Errors: GD_EINPUT (period <= 0, tolerances), GD_ENUMERIC (CVODE). */
GD_API gd_status gd_transient_monodromy(gd_transient *tr, double t0, double period,
                                        const double *y0, const gd_transient_options *opt,
                                        double *phi, double *y_end, gd_error *err);
/* The same with a counted limit: max_rhs (0: none) right-hand sides of the model (each
 * evaluation of the augmented system counts 1 + 2 nstates, a saltation update 2),
 * checked after every integrator step; past it, GD_ENUMERIC naming the time reached
 * within the period and the counts. *nrhs (may be NULL) receives the count spent, also on
 * failure. Deterministic: the count, not a clock, stops it (issue 33). */
GD_API gd_status gd_transient_monodromy_limited(gd_transient *tr, double t0, double period,
                                                const double *y0, const gd_transient_options *opt,
                                                long max_rhs, long *nrhs, double *phi,
                                                double *y_end, gd_error *err);

#endif
