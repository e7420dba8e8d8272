/* Element kinds: a type table in the style of GSL's gsl_interp_type. Every kind of
 * element (shaft element, disk, bearing, spring, gear mesh) is one constant
 * gd_element_type, defined in its own file under src/elements/, that knows its
 * instances in a model, their nodes, their local matrices at a speed, how their strain
 * energy splits into motion types and which output probes (forces) they offer, under
 * which name.
 * Assembly, modal strain energy, the speed-dependent terms and the FRF force probes
 * loop over the registry (gd_element_types) and never switch on the kind; so do the
 * probe syntax of the CLI, the study files and the Python package.
 *
 * Local DOFs: 6 per node in the order x, y, z, rx, ry, rz; a two-node element stacks
 * node 1 then node 2 (12 DOFs). A second node of -1 is ground: its 6 DOFs are dropped
 * when the element is assembled. Local matrices are row-major.
 *
 * Ownership and threads: the types are constant, statically allocated and never
 * freed; every function pointer is reentrant (it reads the model and writes only to
 * the caller's buffers), so one type may be used from any number of threads. */
#ifndef GEARDYN_ELEMENTS_H
#define GEARDYN_ELEMENTS_H
#include "geardyn/export.h"
#include "geardyn/model.h"

/* Motion types for modal strain energy. Shaft bending counts as lateral; tilt is the
 * energy of tilt springs (bearings' k_tilt, rx/ry springs, mesh tilt coupling). */
typedef enum gd_motion {
    GD_MOTION_LATERAL,
    GD_MOTION_TORSIONAL,
    GD_MOTION_AXIAL,
    GD_MOTION_TILT,
    GD_NMOTIONS
} gd_motion;
GD_API extern const char *const gd_motion_names[GD_NMOTIONS];

/* What an instance contributes (gd_element_type.terms). */
enum {
    GD_TERM_M = 1u << 0,
    GD_TERM_K = 1u << 1,
    GD_TERM_C = 1u << 2,
    GD_TERM_G = 1u << 3,
    /* K and C depend on the speed (a bearing speed table): they are evaluated per speed
     * and left out of the system's constant K and C */
    GD_TERM_SPEED = 1u << 4
};

#define GD_ELEMENT_MAX_DOFS 12

typedef struct gd_element_type {
    const char *name; /* "shaft", "disk", "bearing", "spring", "mesh" */
    /* Instances of this kind in a model. */
    int (*count)(const gd_model *m);
    /* Nodes of instance i (node[1] = -1: ground or a one-node element); returns the
     * number of local nodes, 1 or 2 (local DOFs: 6 per node). */
    int (*nodes)(const gd_model *m, int i, int node[2]);
    /* GD_TERM_* flags of instance i. */
    unsigned (*terms)(const gd_model *m, int i);
    /* Local matrices of instance i at reference speed W (rad/s): n x n with n = 6 x
     * nodes. G is per unit reference speed, the shaft's signed speed ratio included;
     * K and C of GD_TERM_SPEED instances are those at W. Any pointer may be NULL. */
    void (*matrices)(const gd_model *m, int i, double speed, double *M, double *K, double *C,
                     double *G);
    /* Local DOFs (acts[n], 0/1) that a GD_TERM_SPEED instance acts on at any speed, so
     * the system keeps them and reserves their sparse pattern. NULL for kinds that are
     * never speed-dependent. */
    void (*speed_pattern)(const gd_model *m, int i, int *acts);
    /* Motion type of each node DOF (x..rz) for the strain-energy split. */
    const gd_motion *motion;
    /* Strain energy 1/2 Re(u^H K u) of local displacement u (re, im; im may be NULL)
     * with local stiffness K, added into by_motion; returns the total. NULL: split by
     * DOF, each local DOF's share 1/2 Re(conj(u_a) (K u)_a) to motion[a % 6]. */
    double (*strain_energy)(const gd_model *m, int i, const double *K, const double *re,
                            const double *im, double *by_motion);
    /* Components (strain-energy groups) of this kind: how many, which one instance i
     * belongs to, and the name of component c. ncomponents NULL: stores no energy (a
     * disk). The system numbers the components kind after kind in registry order
     * (gd_system_component tells a component's kind). */
    int (*ncomponents)(const gd_model *m);
    int (*component)(const gd_model *m, int i);
    const char *(*component_name)(const gd_model *m, int c);
    /* Force output of instance i in direction dir at speed W, as rows over its local
     * DOFs: F = sum_a (k[a] + i w c[a]) u_a. NULL: the kind has no force probe. */
    void (*force_row)(const gd_model *m, int i, double speed, gd_dof dir, double *k, double *c);
    /* The force probe's vocabulary (geardyn/probe.h; docs/analyses.md): a probe on
     * instance NAME is written PROBE:NAME (probe_dirs 0: one force, along the kind's own
     * line) or PROBE:NAME.DIR (probe_dirs 1: the force in DIR = x, y, z in N, the moment
     * in rx, ry, rz in N m); probe_help says what it measures, for usage texts. The
     * instance is found by its component name, so a kind with a probe has one component
     * per instance (component(m, i) = i). probe NULL: no force probe. */
    const char *probe;
    int probe_dirs;
    const char *probe_help;
} gd_element_type;

/* The registry, in assembly order (shaft, disk, bearing, spring, mesh, planetary). */
GD_API extern const gd_element_type *const gd_element_types[];
GD_API extern const int gd_nelement_types;
GD_API extern const gd_element_type gd_element_shaft, gd_element_disk, gd_element_bearing,
    gd_element_spring, gd_element_mesh, gd_element_planetary;
/* The kind named name, or NULL. */
GD_API const gd_element_type *gd_element_type_find(const char *name);

#endif
