/* `geardyn mesh-stiffness --load / --load-range`: the loaded tooth contact analysis and
 * the Harris map of a gear pair (docs/mesh-stiffness.md, "Loaded contact analysis"). */
#ifndef GD_CLI_MESH_CONTACT_H
#define GD_CLI_MESH_CONTACT_H
#include "geardyn/mesh_stiffness.h"

/* Runs the contact analysis at opt->load_torque (nloads = 0) or the Harris map at the
 * nloads torques, and prints (text with CSV, or --json) or writes DIR (out). file and
 * mesh name the pair in the output. Returns the exit code (errors reported). */
int gd_cli_mesh_contact(const char *file, const char *mesh, const gd_gear_pair_geometry *g,
                        const gd_tvms_options *opt, const double *loads, int nloads, int json,
                        const char *out);

#endif
