/* Helper shared by the mesh-stiffness tests: the TVMS of a pair, or NULL with the
 * error shown on stderr. Header-only (static inline): each test program is its own
 * executable. */
#ifndef GD_TEST_TVMS_SUPPORT_H
#define GD_TEST_TVMS_SUPPORT_H
#include <stdio.h>

#include "geardyn/mesh_stiffness.h"

static inline gd_tvms_result *run(const gd_gear_pair_geometry *g, const gd_tvms_options *o)
{
    gd_tvms_result *r = NULL;
    gd_error err;
    if (gd_tvms_compute(g, o, &r, &err)) {
        char buf[1024];
        gd_error_format(&err, buf, sizeof buf);
        fprintf(stderr, "  compute failed: %s\n", buf);
        return NULL;
    }
    return r;
}

#endif
