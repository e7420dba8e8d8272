/* Shared by testmodal and correlate: measured data read, the FRFs chosen, the band
 * option, and the EMA run (cli/testdata_cli.c). */
#ifndef GD_CLI_TESTDATA_H
#define GD_CLI_TESTDATA_H
#include <cjson/cJSON.h>

#include "geardyn/correlate.h"
#include "geardyn/ema.h"
#include "geardyn/testdata.h"

/* The FRFs of td (coherences and other ratios left out) into *frfs (malloc'd, *n);
 * GD_EINPUT when there is none. */
int gd_cli_td_frfs(const gd_testdata *td, const gd_td_function ***frfs, int *n);
/* --band F1:F2 (Hz) into opt; 0 or a usage error (2). */
int gd_cli_parse_band(const char *cmd, const char *text, gd_ema_options *opt);
/* The JSON of a mode set: modes[] with frequency_hz, damping_ratio and, for an LSCF,
 * the shape over the FRFs of the most common reference (normalised: largest 1). */
cJSON *gd_cli_ema_json(const gd_ema_result *r, int nfrf, const gd_td_function *const *frfs);
/* The text table of the modes. */
void gd_cli_ema_print(const gd_ema_result *r, const char *method);

#endif
