/* A bearing table file: a user's own rolling bearings by their geometry (no vendor
 * database), for the stiffness at load of geardyn/bearing_geometry.h (docs/bearings.md,
 * "Rolling bearings from geometry").
 *
 *   bearings:
 *     - {name: 6205, type: ball, elements: 9, element_diameter: 7.94 mm,
 *        pitch_diameter: 39.04 mm, contact_angle: 0 deg, clearance: 5 um}
 *     - {name: NU205, type: roller, elements: 13, element_diameter: 7.5 mm,
 *        pitch_diameter: 38.5 mm, roller_length: 7.5 mm}
 *
 * Keys: name, type (ball|roller), elements, element_diameter, pitch_diameter (required);
 * contact_angle (0), clearance (0; negative: a preload), roller_length (rollers without
 * contact_stiffness), inner_curvature and outer_curvature (0.52), modulus (206 GPa),
 * poisson (0.3), contact_stiffness (N/m^n; 0: from the geometry), phase (0). Units as in
 * model files. Errors are located at the entry and key.
 *
 * Ownership and threads: the caller's geometry is filled; nothing is kept. Reentrant. */
#ifndef GEARDYN_BEARING_TABLE_H
#define GEARDYN_BEARING_TABLE_H
#include <stddef.h>

#include "geardyn/bearing_geometry.h"
#include "geardyn/error.h"
#include "geardyn/export.h"

/* The bearing named name (NULL: the first) of the table file at path into g, its name
 * into name_out (size bytes, may be NULL). GD_EINPUT located in the file (an unknown
 * key, a missing value, a geometry gd_bearing_geometry_check refuses, no such name: the
 * names known), GD_EIO when the file cannot be read. */
GD_API gd_status gd_bearing_table_load(const char *path, const char *name, gd_bearing_geometry *g,
                                       char *name_out, size_t size, gd_error *err);

#endif
