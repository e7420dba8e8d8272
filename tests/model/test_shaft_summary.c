/* gd_model_shaft_summary (what `geardyn check` lists): every shaft's mass and polar
 * inertia are the rigid-body inertia the system's M gives it, 1^T M_xx 1 and
 * 1^T M_rzrz 1 over its nodes. A planetary set's members and planets carry their mass
 * on their nodes (the set's element): the planet and ring housing "shafts" showed 0 kg. */
#include <math.h>
#include <stdlib.h>

#include "geardyn/model_file.h"
#include "geardyn/system.h"
#include "harness.h"

/* 1^T M 1 over the DOF d of the nodes of shaft s (dense M, ndof^2, column-major). */
static double rigid_inertia(const gd_system *sys, const double *M, int s, gd_dof d)
{
    const gd_model *m = sys->model;
    const gd_shaft *sh = &m->shafts[s];
    double sum = 0;
    for (int a = 0; a < sh->nnodes; a++)
        for (int b = 0; b < sh->nnodes; b++) {
            int i = gd_system_dof(sys, sh->first_node + a, d);
            int j = gd_system_dof(sys, sh->first_node + b, d);
            if (i >= 0 && j >= 0) sum += M[i + (size_t)j * sys->ndof];
        }
    return sum;
}

static void check_model(gd_test_state *gd_ts_, const char *path, int *nplanet_shafts)
{
    gd_model *m = NULL;
    gd_system *sys = NULL;
    gd_error err;
    REQUIRE(gd_model_load(path, &m, &err) == GD_OK);
    REQUIRE(gd_system_build(m, &sys, &err) == GD_OK);
    const int n = sys->ndof;
    double *M = malloc((size_t)n * n * sizeof *M);
    REQUIRE(M);
    gd_system_dense(sys, 0, M, NULL, NULL);
    *nplanet_shafts = 0;
    for (int s = 0; s < m->nshafts; s++) {
        gd_shaft_summary ss;
        gd_model_shaft_summary(m, s, &ss);
        CHECK(ss.mass > 0);
        CHECK_REL(ss.mass, rigid_inertia(sys, M, s, GD_X), 1e-9);
        CHECK_REL(ss.polar_inertia, rigid_inertia(sys, M, s, GD_RZ), 1e-9);
        for (int k = 0; k < m->nplanetary; k++) {
            const gd_planetary *g = &m->planetary[k];
            int node = m->shafts[s].first_node;
            if (node >= g->first_planet && node < g->first_planet + g->nplanets) {
                CHECK_REL(ss.mass, g->planet_mass, 1e-12);
                ++*nplanet_shafts;
            }
        }
    }
    free(M);
    gd_system_free(sys);
    gd_model_free(m);
}

/* Lin & Parker's set (Table 1 of [LinParker1999]): sun 0.4 kg, ring 2.35 kg, carrier
 * 5.43 kg, planets 0.66 kg each. */
TEST(lin_parker_members_and_planets)
{
    int np = 0;
    check_model(gd_ts_, "examples/planetary_lin_parker.yaml", &np);
    CHECK(np == 4);
    gd_model *m = NULL;
    gd_error err;
    REQUIRE(gd_model_load("examples/planetary_lin_parker.yaml", &m, &err) == GD_OK);
    static const double mass[] = {0.4, 2.35, 5.43};
    for (int s = 0; s < 3; s++) {
        gd_shaft_summary ss;
        gd_model_shaft_summary(m, s, &ss);
        CHECK_REL(ss.mass, mass[s], 1e-12);
    }
    gd_model_free(m);
}

/* A reducer with a planetary stage on real shafts: elements, disks and the set's
 * members together. */
TEST(reducer_planetary_stage)
{
    int np = 0;
    check_model(gd_ts_, "examples/reducer_three_stage_planetary.yaml", &np);
    CHECK(np >= 3);
}

RUN_TESTS(T(lin_parker_members_and_planets), T(reducer_planetary_stage))
