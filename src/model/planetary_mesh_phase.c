/* Each planet's mesh phase in a planetary set: the given phases, or [ParkerLin2004]'s from
 * the tooth counts and planet angles (gd_planet_mesh_phases, src/mesh_stiffness/), plus the
 * lag of every planet's ring mesh behind its sun mesh. docs/planetary.md, "Meshes as laws". */
#include <math.h>

#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"

double gd_planetary_mesh_phase(const gd_planetary *g, int ring, int n, int sun_direction)
{
    double ph = 0.0;
    if (g->mesh_phase[ring ? 1 : 0]) {
        ph = g->mesh_phase[ring ? 1 : 0][n];
    } else if (g->teeth[0] > 0) {
        double gs = 0.0, gr = 0.0;
        /* the set's assembly was checked by the builder; a refusal here (too few teeth
           for [ParkerLin2004]'s checks) leaves the planets in phase */
        if (gd_planet_mesh_phases(g->teeth[0], g->teeth[1], 1, &g->planet_angle[n],
                                  sun_direction >= 0 ? 1 : -1, &gs, &gr, NULL) == GD_OK)
            ph = ring ? gr : gs;
    }
    if (ring) ph += g->sun_ring_phase;
    ph -= floor(ph);
    return ph >= 1.0 ? 0.0 : ph;
}
