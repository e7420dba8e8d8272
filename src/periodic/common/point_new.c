/* A new point of any method's result (periodic_impl.h, gd_per_point_new): shared by
 * harmonic balance's points (points.c), shooting's (shooting.c) and reduced shooting's
 * (rshoot/rshoot.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

gd_periodic_point *gd_per_point_new(gd_periodic_result *r, int *cap_points, int dir,
                                    gd_per_kind method)
{
    if (r->npoints == *cap_points) {
        int cap = *cap_points ? 2 * *cap_points : 64;
        gd_periodic_point *p = realloc(r->points, (size_t)cap * sizeof *p);
        if (!p) return NULL;
        r->points = p;
        *cap_points = cap;
    }
    gd_periodic_point *p = &r->points[r->npoints++];
    memset(p, 0, sizeof *p);
    p->direction = dir;
    p->stable = -1;
    p->mu_max = NAN;
    p->method = method;
    p->stability_method = -1;
    p->residual = NAN;
    p->harmonic_ok = -1;
    p->harmonic_error_p2p = p->harmonic_error_amp = NAN;
    return p;
}
