/* Probes: what a frequency or unbalance response is measured on (a DOF, the dynamic
 * force of a gear mesh, the force a bearing transmits), each a linear functional of the
 * complex amplitudes, built by the element kind that owns the quantity.
 *
 * Ownership and threads: probes and functionals are plain value structs; building a
 * functional reads the system only, so it is safe from any thread.
 */
#ifndef GEARDYN_PROBE_H
#define GEARDYN_PROBE_H
#include "geardyn/export.h"
#include "geardyn/system.h"

/* What a response is measured on. */
typedef enum gd_probe_kind {
    GD_PROBE_DOF,    /* displacement of an active DOF (m or rad) */
    GD_PROBE_MESH,   /* dynamic mesh force k d + c d' along the contact normal (N) */
    GD_PROBE_BEARING /* force the bearing transmits, K dq + C dq' in one direction (N or N m) */
} gd_probe_kind;

typedef struct gd_probe {
    gd_probe_kind kind;
    int index;  /* DOF index, mesh index or bearing index */
    gd_dof dir; /* bearing direction */
    char name[160];
} gd_probe;

/* A probe as a linear functional of the complex amplitudes q at frequency w:
 * value = sum_j (k[j] + i w c[j]) q[dof[j]]. */
typedef struct gd_functional {
    int n;
    int dof[24];
    double k[24], c[24];
    int is_force; /* a force, not a displacement */
} gd_functional;
/* The functional of a probe at reference speed W (bearing tables are evaluated there). */
GD_API void gd_probe_functional(const gd_system *sys, const gd_probe *p, double speed,
                                gd_functional *out);

#endif
