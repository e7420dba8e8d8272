/* Physical quantities in model files: SI numbers, or strings with a unit such as
 * "3000 rpm", "20 deg", "2.75e9 N/m", "25.4 mm". Plain numbers are SI (angles in rad,
 * speeds in rad/s). Frequencies and speeds are angular: "1 Hz" is 2*pi rad/s.
 *
 * Ownership and threads: pure functions of their arguments writing only to the
 * caller's buffers; safe from any thread.
 */
#ifndef GEARDYN_UNITS_H
#define GEARDYN_UNITS_H
#include "geardyn/error.h"
#include "geardyn/export.h"
#include <stddef.h>

typedef enum gd_qty {
    GD_QTY_DIMLESS,
    GD_QTY_LENGTH,
    GD_QTY_MASS,
    GD_QTY_TIME,
    GD_QTY_ANGLE,
    GD_QTY_ANGULAR_SPEED, /* rad/s; rpm and Hz accepted */
    GD_QTY_FORCE,
    GD_QTY_TORQUE,
    GD_QTY_STIFFNESS,     /* N/m */
    GD_QTY_DAMPING,       /* N s/m */
    GD_QTY_ROT_STIFFNESS, /* N m/rad */
    GD_QTY_ROT_DAMPING,   /* N m s/rad */
    GD_QTY_INERTIA,       /* kg m^2 */
    GD_QTY_DENSITY,       /* kg/m^3 */
    GD_QTY_PRESSURE,      /* Pa: elastic moduli */
    GD_QTY_VISCOSITY,     /* Pa s */
    GD_QTY_MASS_LENGTH,   /* kg m: unbalance */
    GD_QTY_COUNT_
} gd_qty;

/* Parses text as a quantity of kind qty into SI. Returns GD_OK, or GD_EINPUT with a
 * one-line reason in err->message (err may be NULL). */
GD_API gd_status gd_parse_quantity(const char *text, gd_qty qty, double *value, gd_error *err);

/* The SI unit written for a kind, e.g. "N/m". */
GD_API const char *gd_qty_si_unit(gd_qty qty);

#endif
