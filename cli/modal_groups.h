/* `geardyn modal --group shaft` ([JMSTHelical] Tables 4-7): the strain energy of each mode per
 * shaft with its gears and bearings, and each shaft's energy by motion type. */
#ifndef GD_CLI_MODAL_GROUPS_H
#define GD_CLI_MODAL_GROUPS_H
#include <cjson/cJSON.h>
#include <stdio.h>

#include "geardyn/modal.h"
#include "geardyn/system.h"

/* Prints the shaft table (Table 4) and, per shaft, its motion-type table (Table 7).
 * 0, or the exit code after reporting an error. */
int gd_cli_print_shaft_tables(FILE *f, const gd_system *s, const gd_modal_result *r);
/* Adds "dominant_shaft" and "energy_by_shaft" {name: {share, lateral, torsional,
 * axial, tilt, dominant_motion}} to each mode object of the JSON array modes (motion
 * values are fractions of the shaft's own energy). 0, or the exit code. */
int gd_cli_shaft_json(cJSON *modes, const gd_system *s, const gd_modal_result *r);

#endif
