/* Gear mesh stiffness from geometry: involute geometry and contact ratios of spur and
 * helical pairs, and the time-varying mesh stiffness (TVMS) k(angle) by the potential
 * energy method with helical slicing ([JMSTHelical] Sec. 2), ISO 6336-1, the Cai-Hayashi
 * single-pair law ([Benini2004] Eq. 5) or a square wave; gear-body compliance in series
 * ([Benini2004] Eq. 6). See docs/mesh-stiffness.md.
 *
 * Conventions (all SI):
 *  - The driver is gear[0], the driven gear is gear[1].
 *  - Angle variable: the driver's rotation angle theta (rad). theta = 0 is the instant a
 *    tooth pair starts contact (at the start of active profile, on the front face).
 *    k(theta) is periodic with the mesh period 2*pi/z1 (one transverse base pitch of
 *    roll along the line of action).
 *  - Stiffness k (N/m) acts along the line of action normal to the tooth flank (normal
 *    plane). It is the scalar k in K = k a a^T where a is the unit contact normal. A
 *    rigid rotation theta1 of the driver moves the contact by rb1*cos(beta_b)*theta1
 *    along that normal, so the torsional stiffness is k*cos^2(beta_b)*rb1^2; the
 *    transverse-plane stiffness k_t = k*cos^2(beta_b) is also given. For spur gears
 *    both are the same.
 *
 * Ownership and threads: gd_tvms_compute returns a result the caller frees with
 * gd_tvms_free (gd_ltca_compute / gd_ltca_free, gd_ltca_map_compute / gd_ltca_map_free
 * likewise); geometry and options are plain value structs. Every function is
 * reentrant and safe from any number of threads.
 */
#ifndef GEARDYN_MESH_STIFFNESS_H
#define GEARDYN_MESH_STIFFNESS_H
#include "geardyn/export.h"
#include <stddef.h>

#include "geardyn/error.h"

/* ---- tooth micro-geometry (docs/mesh-stiffness.md, "Micro-geometry") ----
 * Every amount is material removed from the flank, in m, measured along the contact
 * normal (normal plane, the direction of k), so it adds directly to the initial
 * separation of a contact. Zero everywhere (gd_gear_pair_geometry_init) is the perfect
 * involute. */
typedef enum gd_relief_shape {
    GD_RELIEF_LINEAR = 0,   /* grows linearly with the roll length (or face position) */
    GD_RELIEF_PARABOLIC = 1 /* grows with its square: tangent to the flank at the start */
} gd_relief_shape;

/* A tip or root relief: 0 at the start, `amount` at the tip circle (tip relief) or at
 * the form circle (root relief), following the shape in the roll length
 * rho = sqrt(r^2 - r_b^2). The start is a diameter, or a roll angle rho/r_b when the
 * diameter is 0. */
typedef struct gd_profile_relief {
    double amount;           /* m, >= 0; 0 = none */
    double start_diameter;   /* m */
    double start_roll_angle; /* rad, used when start_diameter is 0 */
    gd_relief_shape shape;
} gd_profile_relief;

/* Lead modifications. The face coordinate y runs from the front face (y = 0, where a
 * helical contact line enters first) to the back face (y = b), the same for both gears. */
typedef struct gd_tooth_modifications {
    gd_profile_relief tip_relief, root_relief;
    double crowning;          /* C_b, m >= 0: C_b (2y/b - 1)^2, 0 at mid face */
    double end_relief;        /* m >= 0 at each face end, 0 at end_relief_length inside */
    double end_relief_length; /* m, in (0, b/2] when end_relief > 0 */
    gd_relief_shape end_relief_shape;
    /* f_Hb, m: the flank at the back face lies this much behind the one at the front
     * face (signed): f_Hb (y/b - 1/2) */
    double helix_slope_deviation;
} gd_tooth_modifications;

/* One gear of a pair. Coefficients are in units of the normal module. */
typedef struct gd_gear_geometry {
    int teeth;                 /* z >= 5 */
    double profile_shift;      /* x (coefficient), default 0 */
    double addendum_coef;      /* h_a*, default 1.0 */
    double dedendum_coef;      /* h_f* of the basic rack, default 1.25 */
    double fillet_radius_coef; /* rho_fP* of the basic rack tip, default 0.38 */
    double tip_radius;         /* m; 0 = derive r + (h_a* + x - k) m_n */
    double root_radius;        /* m; 0 = derive r - (h_f* - x) m_n */
    double bore_radius;        /* m; hub/bore radius (fillet foundation); 0 = 0.5 r_f */
    double E, poisson;         /* Pa, - */
    /* gear body in series ([Benini2004] Eq. 6): either a torsional stiffness or a web */
    double body_torsional_stiffness; /* N m/rad; 0 = from the web, or rigid if no web */
    double web_thickness;            /* m; 0 = solid body */
    double web_inner_radius;         /* m; 0 = bore radius */
    double web_outer_radius;         /* m; 0 = root radius - 2 m_n */
    gd_tooth_modifications mod;      /* micro-geometry; all 0 = none */
} gd_gear_geometry;

typedef struct gd_gear_pair_geometry {
    gd_gear_geometry gear[2];     /* [0] driver, [1] driven */
    double normal_module;         /* m_n, m */
    double normal_pressure_angle; /* alpha_n, rad */
    double helix_angle;           /* beta >= 0, rad (0 = spur) */
    int hand;                     /* of the driver: +1 right, -1 left (driven is opposite) */
    double face_width;            /* b, m (common face width) */
    double center_distance;       /* a, m; 0 = from the profile shifts (zero backlash) */
    /* 1: an internal pair - gear[1] (driven) is an internal gear (a ring: teeth pointing
     * inward, tip circle inside the reference circle) and gear[0] an external gear inside
     * it (a planet or pinion). The ring's profile_shift has the ISO 21771 sign (positive
     * thickens its teeth and moves its tip circle inward); its bore_radius is the rim's
     * outer radius (0 = root radius + 3 m_n). docs/mesh-stiffness.md, "Internal pairs". */
    int internal;
} gd_gear_pair_geometry;

/* Fills g with the defaults above (teeth = 0, steel E = 2.06e11 Pa, poisson 0.3). */
GD_API void gd_gear_pair_geometry_init(gd_gear_pair_geometry *g);

/* Quantities derived from the geometry. Contact positions s are measured along the
 * transverse line of action from N1, the tangent point on the driver's base circle. */
typedef struct gd_gear_pair_derived {
    double transverse_module, transverse_pressure_angle; /* m_t, alpha_t */
    double working_pressure_angle;                       /* alpha_wt */
    double base_helix_angle;                             /* beta_b */
    double center_distance, reference_center_distance;   /* a, a0 */
    double tip_shortening;                               /* k (coef): tip reduced by k m_n */
    double pitch_radius[2], base_radius[2], tip_radius[2], root_radius[2];
    double bore_radius[2];
    double form_roll[2];       /* roll length from the base circle to the form circle */
    double half_angle_base[2]; /* half tooth angle on the base circle, rad */
    double tip_clearance[2];   /* a - r_a(i) - r_f(other), m */
    double base_pitch_transverse, base_pitch_normal; /* m */
    double line_of_action;                           /* N1N2, m */
    double contact_start, contact_end;               /* s_A, s_E, m */
    double contact_length;                           /* g_alpha = s_E - s_A */
    double overlap_length; /* g_beta = b tan(beta_b), along the line of action */
    double contact_ratio_transverse, contact_ratio_face, contact_ratio_total;
    double mesh_period; /* 2 pi / z1, rad of driver rotation */
    double ratio;       /* z2 / z1 */
    /* internal pairs (gear_pair_geometry.internal = 1): both base-circle tangent points
     * lie on the same side of the contact, so the driven (ring) roll length at s is
     * s + line_of_action (external: line_of_action - s); tip_radius[1] < root_radius[1];
     * form_roll[1] is the ring's largest usable roll length (its form circle, outside);
     * bore_radius[1] the rim's outer radius. */
    int internal;
    double pitch_point; /* s of the operating pitch point C on the line of action, m */
    /* internal pairs: the trochoid-interference margin of [KHK] Eq. (5-6), rad (>= 0;
     * 0 for external pairs) */
    double trochoid_margin;
} gd_gear_pair_derived;

/* Derives and validates (the modifications too: a tip relief starting below the reference
 * circle - longer than the addendum -, a root relief starting above it or below the form
 * circle, negative crowning, amounts above a tenth of the module, ...). On bad geometry returns
 * GD_EINPUT with err->field set to the offending key relative to the geometry map (e.g.
 * "driver.profile_shift"). */
GD_API gd_status gd_gear_pair_derive(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                                     gd_error *err);

typedef enum gd_tvms_method {
    GD_TVMS_ENERGY = 0,  /* potential energy + slicing (default) */
    GD_TVMS_ISO6336,     /* ISO 6336-1 c_gamma_alpha, constant */
    GD_TVMS_SINGLE_PAIR, /* Cai-Hayashi single-pair parabola, superposed */
    GD_TVMS_SQUARE,      /* constant per-pair stiffness c' (rectangular wave) */
    GD_TVMS_METHOD_COUNT_
} gd_tvms_method;

/* "energy", "iso6336", "single-pair-law", "square"; NULL if out of range. */
GD_API const char *gd_tvms_method_name(gd_tvms_method m);
/* Sets *m for a known name: GD_OK, or GD_EINPUT naming the known methods (err may be
 * NULL). */
GD_API gd_status gd_tvms_method_parse(const char *name, gd_tvms_method *m, gd_error *err);

/* Work bounds of one stiffness table (gd_tvms_compute refuses more): samples stored,
 * and slice contact evaluations (defaults 360 x 50 = 18000). */
#define GD_TVMS_MAX_SAMPLES 1e7
#define GD_TVMS_MAX_SLICE_EVALS 2e7

typedef struct gd_tvms_options {
    gd_tvms_method method;
    int points;          /* samples per mesh cycle, default 360 */
    int cycles;          /* mesh cycles sampled, default 1 */
    int slices;          /* face-width slices (helical), default 50; spur needs 1;
                            at most GD_TVMS_MAX_SAMPLES points x cycles and
                            GD_TVMS_MAX_SLICE_EVALS points x slices */
    int body_compliance; /* 1: gear bodies in series ([Benini2004] Eq. 6), default 0 */
    int harmonics;       /* Fourier harmonics reported, default 5 */
    double quad_tol;     /* relative tolerance of the energy integrals, default 1e-10 */
    /* loaded tooth contact analysis (gd_ltca_compute; a model's `stiffness:
     * {from: contact_analysis}` sets contact_analysis = 1) */
    int contact_analysis;
    double load_torque;  /* N m on the driver, > 0 for a contact analysis */
    double misalignment; /* m, f_ma: relative tilt in the plane of action as the
                            separation at the back face minus the front face */
} gd_tvms_options;

GD_API void gd_tvms_options_init(gd_tvms_options *opt);

typedef struct gd_tvms_result {
    gd_tvms_method method;
    gd_gear_pair_derived geom;
    double mesh_period_rad; /* 2 pi / z1 */
    size_t n;               /* samples = points * cycles */
    size_t points;          /* samples per cycle */
    double *angle_rad;      /* driver angle theta_i = i * mesh_period / points */
    double *stiffness;      /* k(theta_i), N/m, normal plane (see top) */
    int *pairs_in_contact;  /* tooth pairs with any line of contact */
    int max_pairs;          /* columns of load_share */
    /* load_share[i * max_pairs + j]: share of tooth pair j, where j counts the whole mesh
     * cycles since that pair entered contact on the front face (j = 0 newest). Rows sum
     * to 1. Series body compliance does not change the shares. */
    double *load_share;
    double mean, max, min, peak_to_peak; /* N/m over the samples */
    double transverse_factor;            /* cos^2(beta_b): k_t = k * transverse_factor */
    int harmonics;
    /* k(theta) ~ mean + sum_h amp[h-1] cos(h z1 theta + phase[h-1]), h = 1..harmonics */
    double *harmonic_amplitude, *harmonic_phase;
    /* ISO 6336-1 values (N/m, normal plane, whole face width), for every method */
    double iso_single_stiffness;     /* c' b */
    double iso_mesh_stiffness_alpha; /* c_gamma_alpha b */
    double iso_mesh_stiffness_beta;  /* c_gamma_beta b */
    double body_stiffness;           /* series body stiffness, N/m; 0 if not used */
    int slices;                      /* slices used */
} gd_tvms_result;

GD_API gd_status gd_tvms_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                                 gd_tvms_result **out, gd_error *err);
GD_API void gd_tvms_free(gd_tvms_result *r);

/* k at any driver angle (rad), by periodic linear interpolation of the first cycle. */
GD_API double gd_tvms_eval(const gd_tvms_result *r, double driver_angle);

/* ---- loaded tooth contact analysis (contact_analysis.c) ----
 * At each driver angle the face-width slices of every tooth pair in contact are springs
 * k_i (the slice stiffness of the chosen law, normal plane) with an initial separation
 * e_i from both gears' modifications and the misalignment; the approach delta solves
 * sum_i k_i max(0, delta - e_i) = F, F = T / (r_b1 cos beta_b) the normal load.
 * Solved exactly (piecewise linear, springs sorted by e_i). Method iso6336 has no slice
 * law and is refused. Spur pairs are sliced too (opt->slices) for lead modifications. */

/* Per-position flags. */
#define GD_LTCA_PARTIAL_FACE 1 /* an axial slice with a contact carries no load */
#define GD_LTCA_EDGE_CONTACT 2 /* load on at most two slices: edge contact, not resolved */
#define GD_LTCA_NO_CONTACT 4   /* no contact at all (not expected: eps_gamma >= 1) */

typedef struct gd_ltca_result {
    gd_tvms_method method;
    gd_gear_pair_derived geom;
    double torque;       /* N m on the driver */
    double force;        /* normal load T / (r_b1 cos beta_b), N */
    double misalignment; /* m */
    double mesh_period_rad;
    size_t n, points; /* samples and samples per cycle, as gd_tvms_result */
    int slices, max_pairs;
    double slice_width;    /* b / slices, m */
    double body_stiffness; /* series body stiffness, N/m; 0 if not used */
    double *angle_rad;     /* driver angle, as gd_tvms_result */
    /* loaded static transmission error: the approach of the two gears along the contact
     * normal, m (divide by r_b1 cos beta_b for the driver's rotation lag) */
    double *ste;
    double *ste_unloaded;     /* no-load transmission error: the smallest separation, m */
    double *stiffness;        /* dF/d(delta) at the load, N/m along the contact normal */
    int *pairs_in_contact;    /* tooth pairs carrying load */
    double *pair_load;        /* n x max_pairs, N, columns as gd_tvms_result.load_share */
    double *line_load;        /* n x slices: load per unit face width of each slice, N/m */
    double *face_load_factor; /* n: max line load / (F / b), instantaneous */
    int *flags;               /* n: GD_LTCA_* bits */
    double *line_load_mean;   /* slices: line load averaged over the first cycle, N/m */
    /* K_Hbeta: max of line_load_mean / (F / b), the face load factor of ISO 6336-1 */
    double face_load_factor_cycle;
    double ste_mean, ste_peak_to_peak;                   /* m, over the first cycle */
    double stiffness_mean, stiffness_min, stiffness_max; /* N/m, first cycle */
    int flagged;                                         /* positions with a flag */
} gd_ltca_result;

/* Contact analysis at opt->load_torque (> 0) and opt->misalignment with the method,
 * points, cycles, slices, body_compliance and quad_tol of opt. Errors name the option
 * ("load", "method", ...) or the geometry field. */
GD_API gd_status gd_ltca_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                                 gd_ltca_result **out, gd_error *err);
GD_API void gd_ltca_free(gd_ltca_result *r);

/* Harris map: the contact analysis at nloads torques (each > 0), sharing the slice set. */
typedef struct gd_ltca_map {
    int nloads;
    size_t points;                  /* samples per cycle (the first cycle is used) */
    double *torque;                 /* nloads, N m */
    double *ste_peak_to_peak;       /* nloads, m */
    double *ste_mean;               /* nloads, m */
    double *stiffness_mean;         /* nloads, N/m */
    double *face_load_factor_cycle; /* nloads */
    int *flagged;                   /* nloads: positions with a flag */
    double *ste;                    /* nloads x points, m */
    double *ste_unloaded;           /* points, m */
} gd_ltca_map;

GD_API gd_status gd_ltca_map_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                                     const double *torques, int nloads, gd_ltca_map **out,
                                     gd_error *err);
GD_API void gd_ltca_map_free(gd_ltca_map *m);

/* ---- planetary mesh phasing ([ParkerLin2004]; planet_phasing.c) ----
 * Carrier frame; planets numbered counterclockwise at angles psi[n] (rad, from planet 0,
 * counterclockwise, psi[0] = 0 by convention, any value accepted); the sun turns
 * counterclockwise relative to the carrier when sun_direction = +1 (clockwise: -1),
 * the ring the other way. With the mesh period T (the same for all meshes),
 *   k_sn(t) = k_s0(t - gamma_s[n] T),  k_rn(t) = k_r0(t - gamma_r[n] T),
 *   gamma_s[n] = frac(+sun_direction Z_s psi_n / 2 pi),
 *   gamma_r[n] = frac(-sun_direction Z_r psi_n / 2 pi),   values in [0, 1).
 * A planet can only be assembled where (Z_s + Z_r) psi_n / 2 pi is a whole number
 * (then gamma_s[n] = gamma_r[n]): otherwise GD_EINPUT naming "planet_angles[n]" with the
 * nearest angle that assembles. Thread-safe, no allocation: gamma_s and gamma_r have
 * planets entries each (either may be NULL). */
GD_API gd_status gd_planet_mesh_phases(int sun_teeth, int ring_teeth, int planets,
                                       const double *psi, int sun_direction, double *gamma_s,
                                       double *gamma_r, gd_error *err);

/* gamma_rs in [0, 1): the ring-planet mesh of a planet lags its sun-planet mesh by
 * gamma_rs mesh periods, each mesh's event being a contact passing its operating pitch
 * point (on the front face):
 *   gamma_rs = frac( (Z_p - 1)/2 + [Z_p (inv a_ws + inv a_wr - 2 inv a_t)
 *                                   - 4 x_p tan a_n] / (2 pi) ),
 * a_ws, a_wr the working transverse pressure angles of the two meshes, a_t the
 * transverse pressure angle, x_p the planet's profile shift: 0 for an odd, 1/2 for an
 * even planet tooth count without profile shifts ([ParkerLin2004]; derivation in
 * docs/mesh-stiffness.md, "Planet mesh phasing"). sun_planet has the sun as driver and
 * the planet as driven gear; ring_planet has the planet as driver and the ring as the
 * internal driven gear (internal = 1). Both are derived (gd_gear_pair_derive) and must
 * share the planet (teeth, shift, module, pressure and helix angles) and the centre
 * distance (the carrier radius); errors name "sun_planet.<field>" or
 * "ring_planet.<field>". Thread-safe. To turn the pitch-point events into the angle
 * origin of gd_tvms_result (the start of contact), a pair passes its pitch point
 * (pitch_point - contact_start) / base_pitch_transverse mesh periods after it starts
 * contact. */
GD_API gd_status gd_planet_sun_ring_phase(const gd_gear_pair_geometry *sun_planet,
                                          const gd_gear_pair_geometry *ring_planet,
                                          double *gamma_rs, gd_error *err);

#endif
