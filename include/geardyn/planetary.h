/* Planetary gear sets: their kinematics and assembly (docs/planetary.md). The set itself is
 * model data (gd_planetary in geardyn/model.h, gd_model_add_planetary in geardyn/builder.h);
 * its matrices are the element kind gd_element_planetary (geardyn/elements.h); the mode
 * classes are gd_modal_planetary_class (geardyn/modal.h).
 *
 * Ownership and threads: the functions read the set and fill the caller's struct; they
 * keep nothing and may be called from any number of threads. */
#ifndef GEARDYN_PLANETARY_H
#define GEARDYN_PLANETARY_H
#include "geardyn/export.h"
#include "geardyn/model.h"

typedef struct gd_planetary_kinematics {
    /* the member whose speed is the unit: the sun, or the ring when the sun is held; -1
       for a differential (no member held: two inputs, no fixed ratio) */
    int input;
    /* speeds of sun, ring, carrier per unit input speed (the held member 0), from the
       Willis equation (w_s - w_c) Z_s = -(w_r - w_c) Z_r; NAN for a differential */
    double speed[GD_PLANETARY_NMEMBERS];
    double planet_speed; /* the planets' absolute speed per unit input speed */
    double teeth_ratio;  /* Z_r / Z_s: teeth, or pitch radii r_b / cos(alpha) without them */
    /* mesh frequency per unit input speed, rad/s per rad/s: Z_s |w_s - w_c| (NAN without
       teeth) */
    double mesh_order;
    int has_teeth;
    /* assembly ([Parker2000]): (Z_s + Z_r) psi_n / 2 pi for each planet, whole numbers when
       the set can be assembled (NAN without teeth); assembles 1 / 0, -1 without teeth */
    double assembly[GD_PLANETARY_MAX_PLANETS];
    int assembles;
    /* with equally spaced planets: Z_s / N (the phasing index of [Parker2000]) */
    double sun_teeth_per_planet;
} gd_planetary_kinematics;

GD_API void gd_planetary_kinematics_of(const gd_planetary *g, gd_planetary_kinematics *out);

#endif
