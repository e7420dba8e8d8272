/* Gear mesh stiffness from geometry: involute geometry and contact ratios of spur and
 * helical pairs, and the time-varying mesh stiffness (TVMS) k(angle) by the potential
 * energy method with helical slicing (002_... Sec. 2), ISO 6336-1, the Cai-Hayashi
 * single-pair law (003_... Eq. 5) or a square wave; gear-body compliance in series
 * (003_... Eq. 6). See docs/mesh-stiffness.md.
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
 * gd_tvms_free; geometry and options are plain value structs. Every function is
 * reentrant and safe from any number of threads.
 */
#ifndef GEARDYN_MESH_STIFFNESS_H
#define GEARDYN_MESH_STIFFNESS_H
#include "geardyn/export.h"
#include <stddef.h>

#include "geardyn/error.h"

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
    /* gear body in series (003_... Eq. 6): either a torsional stiffness or a web */
    double body_torsional_stiffness; /* N m/rad; 0 = from the web, or rigid if no web */
    double web_thickness;            /* m; 0 = solid body */
    double web_inner_radius;         /* m; 0 = bore radius */
    double web_outer_radius;         /* m; 0 = root radius - 2 m_n */
} gd_gear_geometry;

typedef struct gd_gear_pair_geometry {
    gd_gear_geometry gear[2];     /* [0] driver, [1] driven */
    double normal_module;         /* m_n, m */
    double normal_pressure_angle; /* alpha_n, rad */
    double helix_angle;           /* beta >= 0, rad (0 = spur) */
    int hand;                     /* of the driver: +1 right, -1 left (driven is opposite) */
    double face_width;            /* b, m (common face width) */
    double center_distance;       /* a, m; 0 = from the profile shifts (zero backlash) */
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
} gd_gear_pair_derived;

/* Derives and validates. On bad geometry returns GD_EINPUT with err->field set to the
 * offending key relative to the geometry map (e.g. "driver.profile_shift"). */
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
    int body_compliance; /* 1: gear bodies in series (003_... Eq. 6), default 0 */
    int harmonics;       /* Fourier harmonics reported, default 5 */
    double quad_tol;     /* relative tolerance of the energy integrals, default 1e-10 */
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

#endif
