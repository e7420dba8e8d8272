/* Probes: what a frequency or unbalance response is measured on (a DOF, the dynamic
 * force of a gear mesh, the force a bearing transmits), each a linear functional of the
 * complex amplitudes, built by the element kind that owns the quantity.
 *
 * Ownership and threads: probes and functionals are plain value structs; building a
 * functional reads the system only, so it is safe from any thread.
 */
#ifndef GEARDYN_PROBE_H
#define GEARDYN_PROBE_H
#include "geardyn/elements.h"
#include "geardyn/export.h"
#include "geardyn/system.h"

/* What a response is measured on: the displacement of an active DOF (element NULL,
 * index the DOF, m or rad), or the force of instance `index` of an element kind with a
 * force probe (geardyn/elements.h: the dynamic mesh force k d + c d' along the contact
 * normal, N; the force a bearing transmits, K dq + C dq', in direction dir, N or N m). */
typedef struct gd_probe {
    const gd_element_type *element; /* NULL: a DOF */
    int index;                      /* DOF index, or instance of the element kind */
    gd_dof dir;                     /* direction (kinds with probe_dirs) */
    char name[160];
} gd_probe;

/* The element kind whose probe prefix starts text ("mesh:..." -> gd_element_mesh),
 * *rest then pointing after the colon; NULL when none does. */
GD_API const gd_element_type *gd_probe_element(const char *text, const char **rest);
/* Instance of kind t named name (its component name), or -1. */
GD_API int gd_probe_instance(const gd_system *sys, const gd_element_type *t, const char *name);
/* The default force probes of a system, at most cap into out: every instance of every
 * kind with a probe, once for a one-force kind, in x and y for a directional kind where
 * its first node keeps that DOF (the one-force kinds first, then the directional ones,
 * each in registry order); their names are the probe syntax (mesh:NAME, bearing:NAME.x).
 * Returns the count. */
GD_API int gd_probe_defaults(const gd_system *sys, gd_probe *out, int cap);

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
