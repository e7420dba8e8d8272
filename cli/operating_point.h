/* The operating point of the linear analyses (docs/bearings.md): `--operating-point
 * static|zero` and `--torque` for modal, campbell, frf and unbalance, and the statement
 * in their output of which state the model's laws were linearised about. */
#ifndef GD_CLI_OPERATING_POINT_H
#define GD_CLI_OPERATING_POINT_H
#include <cjson/cJSON.h>
#include <stddef.h>

#include "geardyn/system.h"
#include "options.h"

typedef struct gd_cli_operating {
    int kind;      /* 0 static (default), 1 zero: gd_operating_kind */
    double torque; /* N m input torque at the reference shaft's first node; 0: none */
} gd_cli_operating;

#define GD_CLI_ROWS_OPERATING(T, m)                                                                \
    GD_CLI_ROW("operating-point", GD_CLI_CHOICE, offsetof(T, m.kind), "STATE",                     \
               "state the nonlinear laws (bearings) are linearised about: static = the "           \
               "equilibrium under the model's mean loads, gravity and --torque (at each speed), "  \
               "zero = q = 0",                                                                     \
               .def = "static", .word = "static|zero"),                                            \
        GD_CLI_ROW("torque", GD_CLI_QUANTITY, offsetof(T, m.torque), "VALUE",                      \
                   "input torque of the operating point, N m, at the reference shaft's first "     \
                   "node (its train held at the output, as `static --torque`)",                    \
                   .def = "none", .qty = GD_QTY_TORQUE, .example = "20N*m")

/* Sets s's operating point from op. With check (one analysis speed), the static
 * equilibrium at speed must exist: otherwise the located error of `static`, with the
 * hint to use --operating-point zero. Returns an exit code. */
int gd_cli_operating_apply(gd_system *s, const gd_cli_operating *op, double speed, int check);
/* The speeds (of n) where the laws found no equilibrium (linearised at q = 0 there),
 * each solved again from rest: a warning on stderr naming them (with bad); returns
 * their count and, if bad is not NULL, flags them in bad (n ints). */
int gd_cli_operating_scan(const gd_system *s, const double *speeds, int n, int *bad);
/* The warning of gd_cli_operating_scan from flags the analysis already has (a Campbell
 * result's no_equilibrium; bad may be NULL: nothing to say). */
void gd_cli_operating_warn(const double *speeds, const int *bad, int n);
/* "operating point: ..." (text), nothing for a model without laws. */
void gd_cli_operating_print(const gd_system *s, const gd_cli_operating *op, int per_speed);
/* o.operating_point = {state, torque_n_m, laws, [no_equilibrium_speeds_rpm]} for a model
 * with laws (bad, n: the flags of gd_cli_operating_scan, may be NULL). */
void gd_cli_operating_json(cJSON *o, const gd_system *s, const gd_cli_operating *op,
                           const double *speeds, const int *bad, int n);

#endif
