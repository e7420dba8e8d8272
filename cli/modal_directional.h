/* `geardyn modal --directional` ([Kumar2011]): the directional eigenvalues, signed by
 * whirl, next to the real-coordinate modes. */
#ifndef GD_CLI_MODAL_DIRECTIONAL_H
#define GD_CLI_MODAL_DIRECTIONAL_H
#include <cjson/cJSON.h>
#include <stdio.h>

#include "geardyn/modal.h"

void gd_cli_print_directional(FILE *f, const gd_directional_result *d);
/* An array of {eigenvalue_real, eigenvalue_imag, frequency_hz (signed), whirl,
 * forward_fraction}. */
cJSON *gd_cli_directional_json(const gd_directional_result *d);

#endif
