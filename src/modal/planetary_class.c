/* The class of a planetary set's part in a mode ([LinParker1999] Sec. 4, docs/planetary.md):
 * with equally spaced planets every mode is rotational (central members rotate only, all
 * planets move alike), translational (central members translate only) or a planet mode
 * (central members still). The motion is measured in [LinParker1999]'s coordinates, all
 * lengths: translations, and rotations as u = r theta (base radii; the carrier's planet
 * radius), planets in radial/tangential components; a part below 1e-6 of the set's sum of
 * squares counts as none (eigenvectors are exact to about 1e-12 of that). */
#include <math.h>

#include "geardyn/modal.h"

const char *const gd_planetary_class_names[GD_PCLASS_COUNT] = {"-", "rotational", "translational",
                                                               "planet", "mixed"};

#define PART_TOL 1e-6

/* Entry of (node, dof) in mode j: re, im (0 where the DOF is not active). */
static void entry(const gd_system *s, const gd_modal_result *r, int j, int node, gd_dof d,
                  double *re, double *im)
{
    int i = gd_system_dof(s, node, d);
    *re = *im = 0;
    if (i < 0) return;
    *re = r->shape_re[i + (size_t)j * s->ndof];
    if (r->shape_im) *im = r->shape_im[i + (size_t)j * s->ndof];
}

gd_planetary_class gd_modal_planetary_class(const gd_system *s, const gd_modal_result *r, int j,
                                            int set)
{
    const gd_model *m = s->model;
    const gd_planetary *g = &m->planetary[set];
    const double radius[3] = {g->base_radius[0], g->base_radius[1], g->carrier_radius};
    double trans = 0, rot = 0, planets = 0, xr, xi, yr, yi, tr, ti;
    for (int k = 0; k < GD_PLANETARY_NMEMBERS; k++) {
        int node = g->member[k].node;
        entry(s, r, j, node, GD_X, &xr, &xi);
        entry(s, r, j, node, GD_Y, &yr, &yi);
        entry(s, r, j, node, GD_RZ, &tr, &ti);
        trans += xr * xr + xi * xi + yr * yr + yi * yi;
        rot += radius[k] * radius[k] * (tr * tr + ti * ti);
    }
    /* planet n in (zeta, eta, r_p theta), and its difference from planet 1 */
    double p0[6] = {0}, diff = 0;
    for (int n = 0; n < g->nplanets; n++) {
        int node = g->first_planet + n;
        double c = cos(g->planet_angle[n]), sn = sin(g->planet_angle[n]), rp = g->base_radius[2];
        entry(s, r, j, node, GD_X, &xr, &xi);
        entry(s, r, j, node, GD_Y, &yr, &yi);
        entry(s, r, j, node, GD_RZ, &tr, &ti);
        double p[6] = {c * xr + sn * yr,  c * xi + sn * yi, -sn * xr + c * yr,
                       -sn * xi + c * yi, rp * tr,          rp * ti};
        for (int k = 0; k < 6; k++) {
            planets += p[k] * p[k];
            if (n == 0)
                p0[k] = p[k];
            else
                diff += (p[k] - p0[k]) * (p[k] - p0[k]);
        }
    }
    double total = trans + rot + planets;
    /* shapes are scaled to a largest entry of 1: a set this still is not in the mode */
    if (!(total > 1e-20)) return GD_PCLASS_NONE;
    if (trans + rot <= PART_TOL * total) return GD_PCLASS_PLANET;
    if (trans <= PART_TOL * total && diff <= PART_TOL * total) return GD_PCLASS_ROTATIONAL;
    if (rot <= PART_TOL * total) return GD_PCLASS_TRANSLATIONAL;
    return GD_PCLASS_MIXED;
}
