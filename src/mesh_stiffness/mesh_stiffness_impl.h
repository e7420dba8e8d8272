/* Internal pieces of the mesh-stiffness module, one concept per file. */
#ifndef GD_MS_INTERNAL_H
#define GD_MS_INTERNAL_H
#include <stddef.h>

#include "geardyn/mesh_stiffness.h"

#define GD_MS_PI 3.14159265358979323846

/* ---- involute_pair.c: pieces shared by external and internal pair geometry ---- */
double gd_ms_involute(double a);
double gd_ms_inverse_involute(double v);
/* GD_EINPUT with field, hint and message. */
gd_status gd_ms_geometry_fail(gd_error *err, const char *field, const char *hint, const char *msg);
/* Radii, form roll, base half angle and bore of external gear i (pitch and base radii,
 * transverse pressure angle and tip shortening already in d), with its checks. */
gd_status gd_ms_external_gear(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d, int i,
                              gd_error *err);
/* Path of contact (contact_start/end already in d), pitches and contact ratios. */
gd_status gd_ms_contact_ratios(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                               gd_error *err);

/* ---- internal_geometry.c: an external gear in an internal gear (ISO 21771 / [KHK]) ---- */
/* The rest of gd_gear_pair_derive for g->internal (transverse angles, pitch and base
 * radii already in d). */
gd_status gd_ms_internal_derive(const gd_gear_pair_geometry *g, gd_gear_pair_derived *d,
                                gd_error *err);
/* Half tooth angle of the ring at its base circle (may be negative: the ring's tooth
 * widens outward, psi(r) = this + inv(alpha(r))). */
double gd_ms_ring_half_angle_base(const gd_gear_pair_geometry *g, double at);

/* ---- quadrature.c: adaptive Gauss-Kronrod (7/15) ---- */
typedef double (*gd_ms_fn)(double x, void *ctx);
/* Integral of f over [a, b] to relative tolerance rtol; *neval (may be NULL) counts calls. */
double gd_ms_integrate(gd_ms_fn f, void *ctx, double a, double b, double rtol, int *neval);
/* Fixed n-point Gauss-Legendre (n = 4, 8, 16 or 32), for convergence tests. */
double gd_ms_gauss_legendre(gd_ms_fn f, void *ctx, double a, double b, int n);

/* ---- tooth_energy.c: one tooth as a non-uniform cantilever (Yang & Lin 1987,
 * Tian 2004, Chen & Shao 2011), plane stress, per unit face width ---- */
typedef struct gd_ms_tooth {
    double rb;     /* base radius (transverse) */
    double alpha2; /* half tooth angle on the base circle (ring: gd_ms_ring_half_angle_base) */
    double rf;     /* root radius */
    double rbore;  /* hub/bore radius (fillet foundation); ring: rim outer radius */
    double E, nu;
    int internal; /* 1: a ring's tooth (ring_tooth.c) */
} gd_ms_tooth;

/* Bending + shear + axial compliance (m/N times m of face width) of one tooth loaded at
 * the involute point of roll angle tc = (roll length)/rb. */
double gd_ms_tooth_beam_compliance(const gd_ms_tooth *t, double tc, double rtol, int *neval);
/* The same terms split: out[0] bending, out[1] shear, out[2] axial. Fixed Gauss rule
 * of n points when n > 0 (convergence tests), else adaptive to rtol. */
void gd_ms_tooth_beam_terms(const gd_ms_tooth *t, double tc, double rtol, int n, double out[3]);
/* Half tooth angle at the root circle (theta_f) of the cantilever model. */
double gd_ms_tooth_root_half_angle(const gd_ms_tooth *t);

/* ---- ring_tooth.c: a tooth as a cantilever along its centre line, integrated over the
 * pressure angle of the flank (external or internal teeth) ---- */
/* Bending, shear and axial compliance (out[0..2]) of tooth t loaded at roll angle tc, for
 * an external tooth whose root circle lies above its base circle, or a ring tooth. */
void gd_ms_radial_beam_terms(const gd_ms_tooth *t, double tc, double rtol, double out[3]);
/* Fillet-foundation compliance of a ring tooth (the ring's rim, see ring_tooth.c). */
double gd_ms_ring_fillet_compliance(const gd_ms_tooth *t, double tc);

/* ---- fillet_foundation.c: Sainsot, Velex & Duverger 2004 ---- */
double gd_ms_fillet_compliance(const gd_ms_tooth *t, double tc);
/* The formula itself: load angle a1, load height u_f, root thickness S_f, root half
 * angle theta_f, body ratio h = r_f / r_int, modulus E. */
double gd_ms_foundation_formula(double a1, double uf, double Sf, double thf, double h, double E);

/* ---- hertz.c: Yang & Lin 1987 line contact, per unit face width ---- */
double gd_ms_hertz_compliance(double E1, double nu1, double E2, double nu2);

/* ---- chebyshev.c: smooth functions on [a, b] tabulated at Chebyshev points ---- */
typedef struct gd_ms_cheb {
    int n;
    double a, b;
    double *x, *f; /* nodes (ascending) and values */
} gd_ms_cheb;
/* Tabulates f with n points, doubling n (up to nmax) until interpolation at the
 * midpoints between nodes matches f to rtol. Returns 0, or -1 when out of memory. */
int gd_ms_cheb_build(gd_ms_cheb *c, gd_ms_fn f, void *ctx, double a, double b, int n, int nmax,
                     double rtol);
double gd_ms_cheb_eval(const gd_ms_cheb *c, double x);
void gd_ms_cheb_free(gd_ms_cheb *c);

/* ---- stiffness laws: tooth-pair stiffness per unit face width (transverse plane,
 * N/m per m) as a function of the contact position s on the line of action ---- */
typedef double (*gd_ms_law_fn)(double s, const void *ctx);

/* ---- slicing.c: pairs and slices in contact ([JMSTHelical] Sec. 2.1, Eq. 1) ---- */
typedef struct gd_ms_slicing {
    const gd_gear_pair_derived *d;
    double face_width;
    int slices;
    gd_ms_law_fn law;
    const void *law_ctx;
    int nslots; /* load-share columns */
} gd_ms_slicing;
/* Transverse stiffness at driver angle theta; per-pair parts into pair_k[nslots]
 * (may be NULL); returns the sum. *npairs = tooth pairs with contact. */
double gd_ms_slicing_eval(const gd_ms_slicing *sl, double theta, double *pair_k, int *npairs);
/* One slice in contact: position s on the transverse line of action, axial position y
 * (middle of its active width, from the front face), transverse stiffness k. */
typedef struct gd_ms_contact {
    double s, y, width, k;
    int slot, slice;
} gd_ms_contact;
/* Most contacts gd_ms_slicing_contacts can list at any angle. */
int gd_ms_slicing_capacity(const gd_ms_slicing *sl);
/* gd_ms_slicing_eval that also lists the contacts into out (capacity entries, may be
 * NULL), *nout their count. A spur pair (no overlap) is cut into sl->slices slices too. */
double gd_ms_slicing_contacts(const gd_ms_slicing *sl, double theta, gd_ms_contact *out, int *nout,
                              double *pair_k, int *npairs);

/* ---- energy_law.c: tooth-pair compliance by the potential energy method ---- */
typedef struct gd_ms_energy_law {
    gd_ms_tooth tooth[2];
    double line_of_action; /* N1N2 */
    double hertz;          /* Hertz compliance per unit width */
    double rtol;
    gd_ms_cheb table; /* pair stiffness per unit width over [s_A, s_E] */
} gd_ms_energy_law;
/* Sets up the two teeth from the geometry; tabulates. Returns 0 or -1 (no memory). */
int gd_ms_energy_law_init(gd_ms_energy_law *e, const gd_gear_pair_geometry *g,
                          const gd_gear_pair_derived *d, double rtol);
/* Direct (untabulated) pair stiffness per unit width at contact position s. */
double gd_ms_energy_pair_stiffness(const gd_ms_energy_law *e, double s);
double gd_ms_energy_law_eval(double s, const void *ctx); /* tabulated */
void gd_ms_energy_law_free(gd_ms_energy_law *e);

/* ---- iso6336.c: ISO 6336-1:2006 Method B stiffness, per unit face width, N/m^2,
 * transverse plane ---- */
typedef struct gd_ms_iso {
    double c_th; /* theoretical single stiffness 1/q' */
    double C_M, C_R, C_B, E_factor;
    double c_single; /* c' */
    double c_gamma_alpha, c_gamma_beta;
} gd_ms_iso;
void gd_ms_iso6336(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d, gd_ms_iso *iso);

/* ---- single_pair_law.c: Cai & Hayashi 1994 ([Benini2004] Eq. 5) ---- */
typedef struct gd_ms_cai_law {
    double s_A, g_alpha; /* contact arc */
    double k_single;     /* k_m per unit width: ISO c' */
} gd_ms_cai_law;
/* Factor k_s/k_m at xi = x/(eps p) in [0, 1]: 0.55 at the ends, 1 in the middle. */
double gd_ms_cai_factor(double xi);
double gd_ms_cai_law_eval(double s, const void *ctx);

/* ---- square_wave.c: constant stiffness per tooth pair ---- */
double gd_ms_square_law_eval(double s, const void *ctx); /* ctx: const double *c_single */

/* ---- pair_law.c: the stiffness law of a method, set up for slicing ---- */
typedef struct gd_ms_pair_law {
    gd_ms_iso iso;
    gd_ms_cai_law cai;
    gd_ms_energy_law energy;
    int have_energy;
    gd_ms_law_fn fn;
    const void *ctx; /* points into this struct: do not move it after init */
} gd_ms_pair_law;
/* Returns 0, or -1 when out of memory. */
int gd_ms_pair_law_init(gd_ms_pair_law *p, const gd_gear_pair_geometry *g,
                        const gd_gear_pair_derived *d, gd_tvms_method method, double rtol);
void gd_ms_pair_law_free(gd_ms_pair_law *p);

/* ---- micro_geometry.c: initial separation from modifications and misalignment ---- */
typedef struct gd_ms_relief {
    double amount, from, to; /* roll lengths: 0 at `from`, amount at `to` */
    int shape;
} gd_ms_relief;
typedef struct gd_ms_mods {
    double line_of_action, face_width;
    gd_ms_relief tip[2], root[2]; /* per gear, in its own roll length */
    double crowning;              /* both gears summed */
    double end_amount[2], end_length[2];
    int end_shape[2];
    double slope; /* helix slope deviations and misalignment summed */
    int internal; /* the driven gear is a ring: its roll length is s + line_of_action */
} gd_ms_mods;
void gd_ms_mods_init(gd_ms_mods *m, const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                     double misalignment);
/* Initial separation (m, normal plane) of a contact at s on the line of action, face
 * position y. */
double gd_ms_mods_separation(const gd_ms_mods *m, double s, double y);
/* 1 when any gear has a modification. */
int gd_ms_mods_any(const gd_gear_pair_geometry *g);
/* Validates the modifications against the derived geometry (gd_gear_pair_derive). */
gd_status gd_ms_mods_check(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                           gd_error *err);

/* ---- loaded_tvms.c: a model mesh from the contact analysis ---- */
/* The TVMS result of g with the loaded stiffness k_L(theta) of gd_ltca_compute at
 * opt->load_torque, and ste (points values over the first cycle, malloc'd) the
 * transmission error delta - F0 / k_L the dynamics subtract from the deformation. */
gd_status gd_ms_loaded_tvms(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                            gd_tvms_result **tvms, double **ste, gd_error *err);

/* ---- body_compliance.c: [Benini2004] Eq. 6 ---- */
/* Torsional stiffness of gear body i (N m/rad), or 0 when rigid. */
double gd_ms_body_torsional_stiffness(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d,
                                      int i);
/* Series body stiffness along the normal line of action, N/m (0 when both rigid). */
double gd_ms_body_stiffness(const gd_gear_pair_geometry *g, const gd_gear_pair_derived *d);

/* ---- fourier.c ---- */
/* Harmonics 1..H of n samples over one period: x ~ mean + sum amp cos(h w t + phase). */
void gd_ms_fourier(const double *x, size_t n, int H, double *amp, double *phase);

/* ---- tvms.c: where gear-pair errors point ---- */
/* The ranges and work bounds of the options; errors name the option. */
gd_status gd_ms_check_options(const gd_tvms_options *o, gd_error *err);
/* mean, max, min, peak_to_peak and the harmonics of r's first cycle. */
void gd_ms_tvms_summarise(gd_tvms_result *r);
/* gd_gear_pair_derive and gd_tvms_compute name a field relative to the mesh's `geometry`
 * map (the options: its `stiffness` map). Prefixes err->field with mesh_path and that
 * map's key, and returns the key. */
const char *gd_gear_pair_error_prefix(gd_error *err, const char *mesh_path);

#endif
