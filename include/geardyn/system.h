/* The system: a model turned into numbers once (like an FFTW plan). Global DOF
 * numbering over the active DOFs, sparse constant matrices, and the per-element data
 * later analyses need. Equation of motion at reference speed W:
 *     M q'' + (C + C_b(W) + W G) q' + (K + K_b(W)) q = f
 * where K_b, C_b are the speed-dependent terms (zero unless a bearing has a speed
 * table) and G is the gyroscopic matrix per unit reference speed (each shaft's signed
 * speed ratio folded in). Every matrix is assembled by looping over the element
 * registry (geardyn/elements.h).
 *
 * Ownership and threads: gd_system_build returns a system the caller frees with
 * gd_system_free; it borrows the model, which must outlive it and not change while it
 * lives. A built system is read-only: every function taking a const gd_system * may be
 * called from several threads at once. */
#ifndef GEARDYN_SYSTEM_H
#define GEARDYN_SYSTEM_H
#include "geardyn/export.h"
#include "geardyn/elements.h"
#include "geardyn/error.h"
#include "geardyn/model.h"
#include "geardyn/sparse.h"

/* One element of the model as the system sees it: its kind, its index among that
 * kind's instances, and the active DOF index of each local DOF (-1: not active or
 * ground). */
typedef struct gd_element_instance {
    const gd_element_type *type;
    int index;
    int nlocal;                   /* 6 x nodes */
    int dof[GD_ELEMENT_MAX_DOFS]; /* nlocal */
    unsigned terms;               /* GD_TERM_* */
    int component;                /* strain-energy component, or -1 */
    double *K;                    /* nlocal^2: the constant local stiffness (kept for the
                                     strain energy), NULL for speed-dependent elements */
} gd_element_instance;

typedef struct gd_system {
    const gd_model *model; /* borrowed: must outlive the system */
    int ndof;
    int *dof_node;    /* ndof: node of each DOF */
    gd_dof *dof_type; /* ndof: which of x..rz */
    int *node_dof;    /* nnodes * 6: active DOF index, or -1 */
    int *massless;    /* ndof: 1 where M has no diagonal term */
    int nmassless;
    gd_csc M, K, C, G;
    int has_speed_dependent; /* a bearing has a speed table */
    int has_damping;         /* C, a bearing table or a law may have damping terms */
    int has_gyroscopic;      /* G is not zero */
    int ncomponents;         /* nshafts + nbearings + nsprings + nmeshes (+ planetary),
                                then one per linearised law (nlaws) */
    int ninstances;          /* every element of every kind, in registry order */
    gd_element_instance *instances;
    double *instance_K; /* storage of the instances' K */
    /* laws of the registry with a linearisation (the model's `laws:`): their DOFs, with
       rates and spins per unit reference speed (src/system/law_state.c) */
    int nlaws;
    gd_law *laws;
    int law_block; /* sum of the laws' ndofs^2 */
    /* the operating point the laws are linearised about (gd_system_set_operating_point):
       its kind, the load f0 (ndof, NULL: the mean loads) and the held DOFs (ndof, NULL:
       none), owned by the system */
    int op_kind;
    double *op_f0;
    int *op_held;
} gd_system;

GD_API gd_status gd_system_build(const gd_model *model, gd_system **out, gd_error *err);
GD_API void gd_system_free(gd_system *sys);

/* Active DOF index of (node, dof), or -1. */
GD_API int gd_system_dof(const gd_system *sys, int node, gd_dof dof);
/* The instance of the model's law i (model->laws[i]) on the system's DOFs, with the
 * rates and spins per unit reference speed: the one maker every analysis uses (the
 * linear ones in gd_system_build, transient and periodic in the transient spec). A law
 * on a direction that is not an active DOF is a located error (file, line, laws[i], the
 * node and DOF). Thread-safe (reads sys only). */
GD_API gd_status gd_system_law_instance(const gd_system *sys, int i, gd_law *law, gd_error *err);
/* "node.dof" label of DOF i, e.g. "pinion.rz". */
GD_API void gd_system_dof_label(const gd_system *sys, int i, char *buf, int size);

/* Dense column-major n x n matrices at reference speed W: M, the total damping
 * D = C + C_b(W) + W G + C_L(W), and K + K_b(W) + K_L(W), where K_L and C_L are the
 * linearisations (K = -df/dq, C = -df/dq') of the model's laws (docs/laws.md) about
 * the static state at W (gd_system_law_state): a journal bearing's eight speed-dependent
 * coefficients, a rolling bearing's stiffness under its static load. Any pointer may be
 * NULL. */
GD_API void gd_system_dense(const gd_system *sys, double speed, double *M, double *D, double *K);

/* The static state about which the laws are linearised at reference speed W: q (ndof)
 * solves K(W) q = f0 + sum f_law(q) with the laws' velocities zero at t = 0, f0 the
 * static analysis's mean load (excitation loads at their mean and gravity). Returns 1
 * when found (also with no laws or no load: q = 0), 0 when no equilibrium was found (a
 * journal bearing at rest carries no load): q is then 0, the state the laws are
 * linearised about. */
GD_API int gd_system_law_state(const gd_system *sys, double speed, double *q);
/* The operating point of the linear analyses (docs/bearings.md). GD_OPERATING_STATIC
 * (the default): the laws are linearised about the static state at each speed, under
 * the load f0 (ndof; NULL: the mean loads and gravity of gd_system_law_state) with the
 * DOFs where held[i] != 0 kept at 0 (NULL: none; a gear train free in torsion is held
 * at one torsion DOF by the static analysis's torque balance, gd_static_operating_point
 * of geardyn/static.h). GD_OPERATING_ZERO: about q = 0 (gd_system_law_state returns 1
 * with q = 0). The system copies f0 and held. Not thread-safe against analyses running
 * on sys: set it before them. GD_ENOMEM, or GD_EINPUT for an unknown kind or a
 * non-finite load. */
typedef enum gd_operating_kind { GD_OPERATING_STATIC = 0, GD_OPERATING_ZERO = 1 } gd_operating_kind;
GD_API gd_status gd_system_set_operating_point(gd_system *sys, gd_operating_kind kind,
                                               const double *f0, const int *held, gd_error *err);
/* The same under a load vector f0 of the caller's (ndof): harmonic balance starts from it
 * under the time integrators' loads, which leave gravity out (docs/periodic.md). */
GD_API int gd_system_law_state_loads(const gd_system *sys, double speed, const double *f0,
                                     double *q);

/* The system's matrices at reference speed W, each on its own sparse pattern: M; K with
 * the speed-table bearings at W (K + K_b(W)); C with them (C + C_b(W)), without the
 * gyroscopic term; and G per unit reference speed, so the damping at W is C + W G (what
 * gd_system_dense returns as D without the laws: these are the linear system the time
 * integrators add the laws' nonlinear forces to, so the laws are not in them). Rows and columns are
 * the active DOFs (dof_node, dof_type); exact zeros are left out and rows are sorted within each
 * column. Each output is filled and owned by the caller, who frees it with gd_csc_free; any output
 * may be NULL. speed must be finite (GD_EINPUT otherwise). On failure the outputs are
 * left empty (zeroed). */
GD_API gd_status gd_system_matrices(const gd_system *sys, double speed, gd_csc *M, gd_csc *K,
                                    gd_csc *C, gd_csc *G, gd_error *err);

/* Component c -> its element kind (a type of the registry, geardyn/elements.h), its
 * index within the kind and its name; NULL (index -1, name "") when c is out of range.
 * The last nlaws components are the linearised laws (sys->laws): NULL, index the law's
 * place in sys->laws, name the law's. */
GD_API const gd_element_type *gd_system_component(const gd_system *sys, int c, int *index,
                                                  const char **name);

/* Mesh deformation vector of mesh k: d = sum a[j] q[dof[j]] over n entries (n <= 12). */
typedef struct gd_mesh_vector {
    int n;
    int dof[12];
    double a[12];
} gd_mesh_vector;
GD_API void gd_system_mesh_vector(const gd_system *sys, int mesh, gd_mesh_vector *out);

/* Modal strain energy of displacement u (complex: re, im; im may be NULL) at speed W,
 * split by motion type (by_motion[GD_NMOTIONS]) and by component (by_component
 * [ncomponents], may be NULL). Returns the total. The laws count with their stiffness
 * linearised about the static state at W (gd_system_law_state: one static solve per
 * call when the model has laws), each as its own component. */
GD_API double gd_system_strain_energy(const gd_system *sys, double speed, const double *re,
                                      const double *im, double *by_motion, double *by_component);
/* The same energy split both ways at once: table[c * GD_NMOTIONS + k] is component c's
 * energy in motion type k (ncomponents x GD_NMOTIONS). Returns the total. */
GD_API double gd_system_strain_energy_table(const gd_system *sys, double speed, const double *re,
                                            const double *im, double *table);
/* The shafts component c is grouped with ([JMSTHelical] Tables 4-7: "the gears are included
 * into the shafts"): a shaft is its own; a bearing, spring, mesh or law belongs to the
 * shafts of its nodes, half to each when they are two. Fills shafts[] and weights[]
 * (summing to 1) and returns how many (1 or 2; 0 for no such component). */
GD_API int gd_system_component_shafts(const gd_system *sys, int c, int shafts[2],
                                      double weights[2]);

#endif
