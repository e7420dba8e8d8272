/* One harmonic-balance point with a chosen Floquet method, shared by the Floquet tests
 * (test_floquet_reduced.c, test_floquet_krylov.c). Header-only (static inline): each test
 * program is its own executable. */
#ifndef GD_TEST_FLOQUET_SUPPORT_H
#define GD_TEST_FLOQUET_SUPPORT_H
#include <stdio.h>

#include "geardyn/periodic.h"
#include "model_support.h"

/* One point at W with H harmonics, no truncation estimate, by Floquet method m (steps:
 * monodromy_steps, 0 the default; count: floquet_count for Krylov; cutoff:
 * floquet_cutoff for reduced; 0 the defaults). NULL when it fails or does not converge;
 * the caller frees the result. */
static inline gd_periodic_result *floquet_point(const fx *f, const gd_transient_spec *spec,
                                                double W, int H, int steps, int m, int count,
                                                double cutoff)
{
    gd_periodic_options o;
    gd_periodic_options_init(&o);
    o.harmonics = H;
    o.estimate = 0;
    o.monodromy_steps = steps;
    o.floquet = m;
    o.floquet_count = count;
    o.floquet_cutoff = cutoff;
    gd_periodic_result *r = NULL;
    gd_error err;
    if (gd_periodic_run(f->s, spec, NULL, &W, 1, &o, NULL, 0, &r, &err)) {
        fprintf(stderr, "  periodic: %s\n", err.message);
        return NULL;
    }
    if (r->npoints != 1 || !r->points[0].converged) {
        gd_periodic_result_free(r);
        return NULL;
    }
    return r;
}

#endif
