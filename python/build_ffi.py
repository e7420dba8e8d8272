"""Builds geardyn._native, the cffi extension module over the C library.

cffi in API (out-of-line) mode: the declarations below are compiled against the public
headers (include/geardyn/geardyn.h), so the C compiler checks every struct layout and
enum value (`...` leaves the rest of a struct to the compiler); no download, only
Debian's python3-cffi, python3-dev and the C compiler. The module links the shared
library (-lgeardyn) and records where it is (rpath), so `import geardyn` needs no
environment variable.

usage: python3 python/build_ffi.py [--include DIR] [--libdir DIR]
       (defaults: the checkout's include/ and build/; `make python` passes BUILD)
"""
import argparse
import compileall
import os
import sys
import tempfile

import cffi

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)

CDEF = r"""
typedef enum { GD_OK, GD_EINPUT, GD_ENUMERIC, GD_ENOMEM, GD_EIO, ... } gd_status;
typedef struct gd_error {
    gd_status status;
    char file[...];
    int line, column;
    char field[...];
    char message[...];
    char hint[...];
} gd_error;
void gd_error_clear(gd_error *err);
const char *gd_status_name(gd_status status);
const char *gd_version(void);

typedef enum { GD_QTY_DIMLESS, GD_QTY_LENGTH, GD_QTY_MASS, GD_QTY_TIME, GD_QTY_ANGLE,
               GD_QTY_ANGULAR_SPEED, GD_QTY_FORCE, GD_QTY_TORQUE, GD_QTY_STIFFNESS,
               GD_QTY_DAMPING, GD_QTY_ROT_STIFFNESS, GD_QTY_ROT_DAMPING, GD_QTY_INERTIA,
               GD_QTY_DENSITY, GD_QTY_PRESSURE, GD_QTY_VISCOSITY, GD_QTY_MASS_LENGTH,
               ... } gd_qty;
gd_status gd_parse_quantity(const char *text, gd_qty qty, double *value, gd_error *err);

/* ---- model ---- */
typedef enum { GD_X, GD_Y, GD_Z, GD_RX, GD_RY, GD_RZ, GD_NODE_DOFS, ... } gd_dof;
typedef enum { GD_COUPLING_TORSIONAL, GD_COUPLING_LATERAL_TORSIONAL, GD_COUPLING_FULL,
               ... } gd_coupling;
extern const char *const gd_dof_names[];
extern const char *const gd_coupling_names[3];
unsigned gd_coupling_dof_mask(gd_coupling level);
typedef struct { int line, column; } gd_loc;
typedef struct { char name[...]; int shaft; double position; int named; ...; } gd_node;
typedef struct { char name[...]; int first_node, nnodes; double speed_ratio; ...; } gd_shaft;
typedef struct { char name[...]; int node, node2; ...; } gd_bearing;
typedef struct { char name[...]; int driver, driven; int teeth[2]; double stiffness;
                 ...; } gd_mesh;
typedef struct { char name[...]; int node; double amount, phase; ...; } gd_unbalance;
typedef struct { int node; double mass, inertia; double k_support; double k_torsion; }
    gd_planetary_body;
typedef struct { char name[...]; gd_planetary_body member[3]; int held; int nplanets;
                 int first_planet; double *planet_angle; int equally_spaced; int teeth[3];
                 double base_radius[3]; double carrier_radius; double pressure_angle[2];
                 double planet_mass, planet_inertia; double bearing_stiffness;
                 double mesh_stiffness[2]; double contact_ratio[2]; ...; } gd_planetary;
extern const char *const gd_planetary_member_names[3];
typedef struct gd_model {
    char file[...];
    int nshafts; gd_shaft *shafts;
    int nnodes; gd_node *nodes;
    int nbearings; gd_bearing *bearings;
    int nmeshes; gd_mesh *meshes;
    int nunbalances; gd_unbalance *unbalances;
    double speed;
    int nplanetary; gd_planetary *planetary;
    ...;
} gd_model;
/* kinematics and assembly of a set (planetary.h) */
typedef struct { int input; double speed[3]; double planet_speed; double teeth_ratio;
                 double mesh_order; int has_teeth; double assembly[...]; int assembles;
                 double sun_teeth_per_planet; } gd_planetary_kinematics;
void gd_planetary_kinematics_of(const gd_planetary *g, gd_planetary_kinematics *out);
gd_status gd_model_load(const char *path, gd_model **out, gd_error *err);
void gd_model_free(gd_model *model);
void gd_model_set_coupling(gd_model *model, gd_coupling level);
int gd_model_find_node(const gd_model *model, const char *name);
int gd_model_find_mesh(const gd_model *model, const char *name);
int gd_model_mesh_count(const gd_model *model);
const char *gd_model_mesh_name(const gd_model *model, int i);

typedef struct { int nset; const char *const *set; } gd_load_options;
void gd_load_options_init(gd_load_options *opt);
gd_status gd_model_load_opts(const char *path, const gd_load_options *opt, gd_model **out,
                             gd_error *err);
gd_status gd_model_load_string_opts(const char *yaml, const char *name,
                                    const gd_load_options *opt, gd_model **out, gd_error *err);

/* ---- builder ---- */
typedef enum { GD_INTERP_LINEAR, GD_INTERP_SPLINE, ... } gd_interp;
typedef struct { double kxx, kxy, kyx, kyy, kzz, ktilt, ktorsion;
                 double cxx, cxy, cyx, cyy, czz, ctilt, ctorsion; } gd_bearing_coeffs;
typedef struct { const char *name; double density, E, G, poisson; gd_loc loc;
                 const char *path; ...; } gd_material_spec;
typedef struct { double length, outer_diameter, inner_diameter; const char *material;
                 int elements; gd_loc loc; ...; } gd_section_spec;
typedef struct { const char *name; double at; gd_loc loc; ...; } gd_station_spec;
typedef struct { const char *name; const char *material; int nsections;
                 const gd_section_spec *sections; int nstations;
                 const gd_station_spec *stations; int elements_per_section;
                 double max_element_length; int has_speed_ratio; double speed_ratio;
                 gd_loc loc; const char *path; ...; } gd_shaft_spec;
typedef struct { const char *name; const char *node; double mass, polar_inertia,
                 diametral_inertia; int from_geometry; double outer_diameter,
                 inner_diameter, width; const char *material; gd_loc loc;
                 const char *path; ...; } gd_disk_spec;
typedef struct { const char *name; const char *node; const char *to;
                 gd_bearing_coeffs coeffs; int ntable; const double *table_speed;
                 const gd_bearing_coeffs *table; gd_loc loc; const char *path;
                 ...; } gd_bearing_spec;
typedef struct { const char *name; const char *node; const char *to; gd_dof dof;
                 double stiffness, damping; gd_loc loc; const char *path; ...; } gd_spring_spec;
typedef struct { const char *name; const char *driver; const char *driven; int teeth[2];
                 double base_radius[2]; double pitch_radius[2]; double module;
                 double pressure_angle; double helix_angle; int hand;
                 double line_of_centres; int driver_rotation; double stiffness;
                 double damping; gd_coupling coupling; gd_loc loc; const char *path;
                 ...; } gd_mesh_spec;
typedef struct { const char *name; const char *node; double amount, phase; gd_loc loc;
                 const char *path; ...; } gd_unbalance_spec;
gd_status gd_model_new(const char *name, gd_model **out, gd_error *err);
gd_status gd_model_finish(gd_model *m, gd_error *err);
void gd_material_spec_init(gd_material_spec *s);
void gd_section_spec_init(gd_section_spec *s);
void gd_station_spec_init(gd_station_spec *s);
void gd_shaft_spec_init(gd_shaft_spec *s);
void gd_disk_spec_init(gd_disk_spec *s);
void gd_bearing_spec_init(gd_bearing_spec *s);
void gd_spring_spec_init(gd_spring_spec *s);
void gd_mesh_spec_init(gd_mesh_spec *s);
void gd_unbalance_spec_init(gd_unbalance_spec *s);
gd_status gd_model_add_material(gd_model *m, const gd_material_spec *s, int *index, gd_error *err);
gd_status gd_model_add_shaft(gd_model *m, const gd_shaft_spec *s, int *index, gd_error *err);
gd_status gd_model_add_disk(gd_model *m, const gd_disk_spec *s, int *index, gd_error *err);
gd_status gd_model_add_bearing(gd_model *m, const gd_bearing_spec *s, int *index, gd_error *err);
gd_status gd_model_add_spring(gd_model *m, const gd_spring_spec *s, int *index, gd_error *err);
gd_status gd_model_add_mesh(gd_model *m, const gd_mesh_spec *s, int *index, gd_error *err);
gd_status gd_model_add_unbalance(gd_model *m, const gd_unbalance_spec *s, int *index,
                                 gd_error *err);
/* planetary sets (builder.h, docs/planetary.md): the constant-coefficient set; tooth
   geometry and mesh laws are read from files */
typedef struct { const char *node; double mass; double inertia; double k_support;
                 double k_torsion; } gd_planetary_member_spec;
typedef struct { const char *name; gd_planetary_member_spec member[3]; int held;
                 int nplanets; const double *planet_angles; double planet_mass, planet_inertia;
                 double bearing_stiffness; const double *pin_errors;
                 const double *pin_errors_radial;
                 double carrier_error[2]; int teeth[3]; double base_radius[3];
                 double carrier_radius; double pressure_angle[2]; double helix_angle;
                 double planet_tip_radius; double mesh_stiffness[2]; double mesh_damping[2];
                 int carrier_frame; int centrifugal_stiffness; gd_loc loc; const char *path;
                 ...; } gd_planetary_spec;
void gd_planetary_spec_init(gd_planetary_spec *s);
gd_status gd_model_add_planetary(gd_model *m, const gd_planetary_spec *s, int *index,
                                 gd_error *err);
gd_status gd_model_set_dofs(gd_model *m, unsigned dof_mask, gd_error *err);
gd_status gd_model_set_reference_shaft(gd_model *m, const char *shaft, int rotation,
                                       gd_loc loc, gd_error *err);
gd_status gd_model_set_speed(gd_model *m, double speed, gd_error *err);

/* ---- system ---- */
typedef struct { int n; int *colptr; int *rowind; double *values; } gd_csc;
void gd_csc_free(gd_csc *a);
typedef struct { const char *name; const char *probe; int probe_dirs; const char *probe_help;
                 ...; } gd_element_type;
extern const gd_element_type *const gd_element_types[];
extern const int gd_nelement_types;
typedef enum { GD_MOTION_LATERAL, GD_MOTION_TORSIONAL, GD_MOTION_AXIAL, GD_MOTION_TILT,
               GD_NMOTIONS, ... } gd_motion;
extern const char *const gd_motion_names[];
typedef struct gd_system {
    const gd_model *model;
    int ndof;
    int *dof_node;
    gd_dof *dof_type;
    int nmassless;
    int ncomponents;
    int nlaws;
    ...;
} gd_system;
gd_status gd_system_build(const gd_model *model, gd_system **out, gd_error *err);
void gd_system_free(gd_system *sys);
int gd_system_dof(const gd_system *sys, int node, gd_dof dof);
gd_status gd_system_matrices(const gd_system *sys, double speed, gd_csc *M, gd_csc *K,
                             gd_csc *C, gd_csc *G, gd_error *err);
typedef enum { GD_OPERATING_STATIC = 0, GD_OPERATING_ZERO = 1 } gd_operating_kind;
gd_status gd_system_set_operating_point(gd_system *sys, gd_operating_kind kind,
                                        const double *f0, const int *held, gd_error *err);
const gd_element_type *gd_system_component(const gd_system *sys, int c, int *index,
                                      const char **name);

/* ---- modal ---- */
typedef enum { GD_WHIRL_NONE, GD_WHIRL_FORWARD, GD_WHIRL_BACKWARD, GD_WHIRL_MIXED,
               ... } gd_whirl;
extern const char *const gd_whirl_names[4];
typedef enum { GD_MODAL_AUTO, GD_MODAL_UNDAMPED, GD_MODAL_DAMPED, ... } gd_modal_kind;
typedef struct { double speed; int nmodes; gd_modal_kind kind; int want_left; double tol;
                 ...; } gd_modal_options;
typedef struct {
    double lambda_re, lambda_im, omega_n, omega_d, frequency_hz, damping_ratio,
        log_decrement;
    int rigid_body, overdamped, unstable;
    gd_whirl whirl;
    double energy_share[...];
    gd_motion dominant_motion;
    int dominant_component;
    double residual, residual_floor;
    ...;
} gd_mode;
typedef struct {
    int ndof, nmodes, ncomponents;
    int damped;
    double speed;
    gd_mode *modes;
    double *shape_re, *shape_im;
    double *left_re, *left_im;
    double *energy_by_component;
    ...;
} gd_modal_result;
void gd_modal_options_init(gd_modal_options *opt);
gd_status gd_modal_solve(const gd_system *sys, const gd_modal_options *opt,
                         gd_modal_result **out, gd_error *err);
void gd_modal_free(gd_modal_result *res);
typedef enum { GD_PCLASS_NONE, GD_PCLASS_ROTATIONAL, GD_PCLASS_TRANSLATIONAL, GD_PCLASS_PLANET,
               GD_PCLASS_MIXED, GD_PCLASS_COUNT } gd_planetary_class;
extern const char *const gd_planetary_class_names[5];
gd_planetary_class gd_modal_planetary_class(const gd_system *sys, const gd_modal_result *r,
                                            int mode, int set);

/* ---- static (static.h) ---- */
typedef struct { double speed; double input_torque; int input_node; int hold_node;
                 int loads; int gravity; ...; } gd_static_options;
typedef struct { double force[3]; double moment[3]; } gd_static_reaction;
typedef struct { int node; gd_dof dof; int prescribed; double reaction; ...; } gd_static_hold;
typedef struct { double force; double on_driver[6]; double on_driven[6];
                 double tangential, radial, axial, tilt_in_plane, tilt_out_of_plane,
                 face_width, f_sh, f_beta_x; ...; } gd_static_mesh;
typedef struct { const char *name; const char *type; int nrecords;
                 const char *record_names[8]; const char *record_units[8];
                 double records[8]; ...; } gd_static_law;
typedef struct { int ndof, nnodes, nbearings, nsprings, nmeshes, nholds; double speed;
                 double *q; double *f; double *u; gd_static_reaction *bearings;
                 double *springs; gd_static_mesh *meshes; gd_static_hold *holds;
                 double *law_forces; int nlaws; gd_static_law *laws;
                 ...; } gd_static_result;
void gd_static_options_init(gd_static_options *opt);
gd_status gd_static_operating_point(gd_system *sys, const gd_static_options *opt, int check,
                                    gd_error *err);
gd_status gd_static_run(const gd_system *sys, const gd_static_options *opt,
                        gd_static_result **out, gd_error *err);
void gd_static_free(gd_static_result *res);
typedef struct { int nplanets; double sun_force[...], ring_force[...]; double bearing_force[...];
                 double load_sharing; } gd_static_planetary_loads;
gd_status gd_static_planetary(const gd_system *sys, const gd_static_result *res, int set,
                              gd_static_planetary_loads *out, gd_error *err);

/* ---- campbell ---- */
typedef enum { GD_EIG_AUTO, GD_EIG_DENSE, GD_EIG_SPARSE, ... } gd_eig_method;
typedef enum { GD_ORDER_SHAFT, GD_ORDER_USER, GD_ORDER_MESH, ... } gd_order_kind;
typedef struct { gd_order_kind kind; double order; char label[...]; ...; } gd_order;
typedef struct { int nspeeds; const double *speeds; int nmodes; gd_modal_kind kind;
                 gd_eig_method method; double shift; int norders; const double *orders;
                 int shaft_orders; int mesh_orders; double mac_min; int nthreads;
                 ...; } gd_campbell_options;
typedef struct { int mode; int order; double speed; double speed_rpm; double frequency_hz;
                 ...; } gd_critical_speed;
typedef struct { int id; gd_whirl whirl; gd_motion dominant_motion; ...; } gd_campbell_track;
typedef struct { int nspeeds, ntracks, ndof; double *speeds; gd_campbell_track *tracks;
                 gd_mode *modes; int norders; gd_order *orders; int ncritical;
                 gd_critical_speed *critical; double instability_onset;
                 int instability_track; int nrigid; int sparse; ...; } gd_campbell_result;
void gd_campbell_options_init(gd_campbell_options *opt);
gd_status gd_campbell_default_modes(const gd_system *sys, const gd_campbell_options *opt,
                                   int *nmodes, double *limit, gd_error *err);
gd_status gd_campbell(const gd_system *sys, const gd_campbell_options *opt,
                      gd_campbell_result **out, gd_error *err);
void gd_campbell_free(gd_campbell_result *r);

/* ---- probes, frf, unbalance ---- */
typedef struct { const gd_element_type *element; int index; gd_dof dir; char name[...]; ...; }
    gd_probe;
const gd_element_type *gd_probe_element(const char *text, const char **rest);
int gd_probe_instance(const gd_system *sys, const gd_element_type *t, const char *name);
int gd_probe_defaults(const gd_system *sys, gd_probe *out, int cap);
typedef enum { GD_FRF_RECEPTANCE, GD_FRF_MOBILITY, GD_FRF_ACCELERANCE, ... } gd_frf_quantity;
extern const char *const gd_frf_quantity_names[3];
typedef enum { GD_FRF_DIRECT, GD_FRF_MODAL, ... } gd_frf_method;
typedef struct { int nfreq; const double *freqs; double speed; int ninputs;
                 const int *inputs; int noutputs; const gd_probe *outputs;
                 gd_frf_quantity quantity; gd_frf_method method; int nmodes; int nthreads;
                 ...; } gd_frf_options;
typedef struct { int nfreq, ninputs, noutputs; double *freqs; double *re, *im;
                 int *singular; int nsingular; int nmodes_used; int nrigid;
                 ...; } gd_frf_result;
void gd_frf_options_init(gd_frf_options *opt);
gd_status gd_frf(const gd_system *sys, const gd_frf_options *opt, gd_frf_result **out,
                 gd_error *err);
void gd_frf_free(gd_frf_result *r);
gd_status gd_frf_load(const gd_system *sys, const gd_frf_options *opt, const double *load_re,
                      const double *load_im, gd_frf_result **out, gd_error *err);
gd_status gd_planetary_mesh_excitation(const gd_system *sys, int set, int harmonic, int ring,
                                       double *re, double *im, gd_error *err);
void gd_frf_directional(const gd_frf_result *r, int out_x, int out_y, double *fwd_re,
                        double *fwd_im, double *bwd_re, double *bwd_im);

typedef struct { int nspeeds; const double *speeds; int noutputs; const gd_probe *outputs;
                 int norbits; const int *orbit_nodes; int nthreads; ...; } gd_unbalance_options;
typedef struct { double major, minor; double angle; gd_whirl whirl; ...; } gd_orbit;
typedef struct { double order; int nunbalances; ...; } gd_unbalance_harmonic;
typedef struct { int nspeeds, noutputs, norbits, nharmonics; double *speeds;
                 gd_unbalance_harmonic *harmonics; double *re, *im; gd_orbit *orbits;
                 int *singular; ...; } gd_unbalance_result;
void gd_unbalance_options_init(gd_unbalance_options *opt);
gd_status gd_unbalance_response(const gd_system *sys, const gd_unbalance_options *opt,
                                gd_unbalance_result **out, gd_error *err);
void gd_unbalance_free(gd_unbalance_result *r);

/* ---- transient ---- */
typedef struct { const char *name; const char *unit; } gd_law_record;
typedef struct gd_law gd_law;
typedef struct { double t; const double *q, *v; } gd_law_point;
typedef struct { const char *name; const char *summary; unsigned flags; int nparams;
                 const int *dirs; int ndirs; int two_nodes; int nterms;
                 void (*term)(const gd_law *law, int k, double *u, double *w);
                 void (*force)(const gd_law *law, const gd_law_point *x, double *f, double *jq,
                               double *jv);
                 int nrecords; const gd_law_record *records;
                 double (*record)(const gd_law *law, int k, const gd_law_point *x);
                 ...; } gd_law_type;
struct gd_law { const gd_law_type *type; char name[48]; int ndofs; int dof[12];
                void *user; ...; };
enum { GD_LAW_SMOOTH = 1, GD_LAW_TIME_ONLY = 2 };
void gd_law_init(gd_law *law, const gd_law_type *type, const char *name);
gd_status gd_law_type_validate(const gd_law_type *type, gd_error *err);
gd_status gd_law_check(const gd_law *law, gd_error *err);
/* user laws written in Python (python/geardyn/laws.py): the type's ops call back */
extern "Python" void gd_py_law_term(const gd_law *law, int k, double *u, double *w);
extern "Python" void gd_py_law_force(const gd_law *law, const gd_law_point *x, double *f,
                                     double *jq, double *jv);
extern "Python" double gd_py_law_record(const gd_law *law, int k, const gd_law_point *x);
typedef struct { int mesh; int backlash; ...; } gd_tr_mesh;
typedef struct { int nmeshes; int nsfds; const gd_law *laws; int nlaws; int nprescribed; ...; }
    gd_transient_spec;
typedef struct gd_transient gd_transient;
typedef enum { GD_TR_BDF, GD_TR_ADAMS, GD_TR_GEN_ALPHA, GD_TR_AUTO, GD_TR_LTI, ... } gd_tr_method;
typedef enum { GD_TR_INIT_REST, GD_TR_INIT_STATIC, GD_TR_INIT_GIVEN, ... } gd_tr_init;
typedef enum { GD_SPEED_RAMP = 1, GD_SPEED_TABLE = 2 } gd_speed_profile_kind;
typedef struct { gd_speed_profile_kind kind; double from, to; double t0, t1; int n;
                 const double *t, *speed; } gd_speed_profile;
gd_status gd_speed_profile_check(const gd_speed_profile *p, gd_error *err);
void gd_speed_profile_eval(const gd_speed_profile *p, double t, double *angle,
                           double *speed, double *accel);
typedef struct { double t_start, t_end; double output_interval; double record_from;
                 double rtol; double atol_q, atol_v; gd_tr_method method; gd_tr_init init;
                 const double *q0, *v0; double max_step; long max_steps; int max_order;
                 int locate_events; double step; double rho_inf;
                 const gd_speed_profile *profile; int error_estimate; ...; } gd_transient_options;
typedef enum { GD_REC_DISP, GD_REC_VEL, GD_REC_ANGLE, GD_REC_SPEED, GD_REC_SPEED_RATIO,
               GD_REC_MESH_FORCE, GD_REC_MESH_DEFLECTION, GD_REC_MESH_STATE,
               GD_REC_MESH_STIFFNESS, GD_REC_SFD_FX, GD_REC_SFD_FY,
               GD_REC_SFD_ECCENTRICITY, GD_REC_LAW, ... } gd_tr_record_kind;
typedef struct { gd_tr_record_kind kind; int index, index2; } gd_tr_record;
typedef struct { double min, max, mean, rms, peak_to_peak, std; } gd_tr_stats;
typedef struct { int contact_losses; int coast_impacts; int drive_impacts;
                 double separated_time, coast_time, drive_time; } gd_tr_contact_stats;
typedef struct { int nout; double *t; int nrecords; gd_tr_record *records; double *values;
                 gd_tr_stats *stats; int nmeshes; gd_tr_contact_stats *contacts; int ndof;
                 double *q_end, *v_end; long steps, rhs_evals, lin_iters, prec_setups,
                 events, reinits; double cpu_seconds; double step, error_estimate;
                 char method_note[...]; ...; } gd_transient_result;
typedef struct { gd_transient_spec spec; gd_tr_mesh *meshes; int *sfd_bearing;
                 ...; } gd_transient_model;
gd_status gd_transient_model_build(const gd_system *sys, gd_transient_model **out,
                                   gd_error *err);
void gd_transient_model_free(gd_transient_model *tm);
gd_status gd_transient_new(const gd_system *sys, const gd_transient_spec *spec, double speed,
                           gd_transient **out, gd_error *err);
/* the transient condensed onto the laws' DOFs (`transient --condense`, docs/transient.md) */
gd_status gd_transient_new_condensed(const gd_system *sys, const gd_transient_spec *spec,
                                     double speed, double cutoff, gd_transient **out,
                                     gd_error *err);
typedef struct { int ncoords, nstates; int nkept, ndiscarded; int nrigid; double cutoff;
                 double first_discarded; double excitation; double contact;
                 double static_correction; double estimate; } gd_tr_condensed_info;
int gd_transient_condensed_info(const gd_transient *tr, gd_tr_condensed_info *info);
int gd_transient_condense_pays(const gd_transient *tr, char *why, size_t len);
void gd_transient_free(gd_transient *tr);
int gd_transient_nstates(const gd_transient *tr);
void gd_transient_options_init(gd_transient_options *opt);
gd_status gd_transient_run(gd_transient *tr, const gd_transient_options *opt,
                           const gd_tr_record *records, int nrecords,
                           gd_transient_result **out, gd_error *err);
void gd_transient_result_free(gd_transient_result *r);
/* order tracking of a run-up (geardyn/waterfall.h) */
typedef enum { GD_WINDOW_HANN = 0, GD_WINDOW_RECT = 1 } gd_window;
typedef struct { int nsamples; double dt; gd_window window; int n; double df; double *freq;
                 double *amplitude; } gd_spectrum;
typedef struct { int nspeeds; double *speeds; gd_spectrum **spectra; int norders;
                 gd_order *orders; double *order_amplitude; double *order_frequency;
                 int tracked; double revs_per_block; ...; } gd_waterfall;
typedef struct { double revs_per_block; int samples_per_rev; double overlap;
                 gd_window window; } gd_order_track_options;
void gd_order_track_options_init(gd_order_track_options *opt);
gd_status gd_waterfall_order_track(const gd_system *sys, const double *t, const double *x,
                                   const double *angle, int n,
                                   const gd_order_track_options *opt, gd_waterfall **out,
                                   gd_error *err);
void gd_waterfall_free(gd_waterfall *w);

/* ---- periodic (harmonic balance) ---- */
typedef enum { GD_PER_ARCLENGTH, GD_PER_SEQUENTIAL, ... } gd_per_method;
typedef enum { GD_PER_HB = 0, GD_PER_SHOOTING = 1, GD_PER_AUTO = 2, GD_PER_MULTIFREQ = 3, GD_PER_REDUCED_SHOOTING = 4 } gd_per_kind;
const char *gd_per_kind_name(gd_per_kind k);
typedef struct { int harmonics; int adaptive; double harmonic_tol; int max_harmonics;
                 int subharmonic; int samples; double tol; int max_iter; int stability;
                 int monodromy_steps; gd_per_method method; int both_directions;
                 int max_steps; int solver; gd_per_kind kind; double shoot_rtol;
                 double shoot_budget; double floquet_budget; int shoot_stability;
                 ...; } gd_periodic_options;
typedef struct { double mean, rms, peak_to_peak; double *amplitude, *phase_deg;
                 ...; } gd_per_record_stats;
typedef struct { double speed; double parameter; int direction; int converged;
                 char reason[...]; int harmonics; double omega; double residual;
                 int iterations; int stable; double mu_max; int nmult; double *mu_re, *mu_im;
                 int nfree; double *coef; gd_per_record_stats *records;
                 ...; } gd_periodic_point;
typedef enum { GD_BIF_FOLD, GD_BIF_PERIOD_DOUBLING, GD_BIF_NEIMARK_SACKER,
               GD_BIF_BRANCH_POINT, ... } gd_bifurcation_type;
typedef struct { gd_bifurcation_type type; double speed, parameter; int direction;
                 double mu_re, mu_im; ...; } gd_bifurcation;
typedef struct { int npoints; gd_periodic_point *points; int nbifurcations;
                 gd_bifurcation *bifurcations; int nrecords; int steps; double cpu_seconds;
                 gd_per_kind method; char method_note[...]; ...; } gd_periodic_result;
typedef struct gd_periodic_param { const char *name; double speed; int load_frequency; ...; }
    gd_periodic_param;
void gd_periodic_options_init(gd_periodic_options *opt);
const char *gd_bifurcation_name(gd_bifurcation_type t);
gd_status gd_periodic_run(const gd_system *sys, const gd_transient_spec *spec,
                          const gd_periodic_param *param, const double *values, int nvalues,
                          const gd_periodic_options *opt, const gd_tr_record *records,
                          int nrecords, gd_periodic_result **out, gd_error *err);
void gd_periodic_result_free(gd_periodic_result *r);

/* ---- mesh stiffness ---- */
typedef enum { GD_TVMS_ENERGY, GD_TVMS_ISO6336, GD_TVMS_SINGLE_PAIR, GD_TVMS_SQUARE,
               ... } gd_tvms_method;
typedef struct { int teeth; ...; } gd_gear_geometry;
typedef struct { gd_gear_geometry gear[2]; double normal_module; double helix_angle;
                 ...; } gd_gear_pair_geometry;
typedef struct { gd_tvms_method method; int points; int cycles; int slices;
                 int body_compliance; int harmonics; double quad_tol;
                 int contact_analysis; double load_torque; double misalignment;
                 ...; } gd_tvms_options;
typedef struct {
    double transverse_pressure_angle, working_pressure_angle, base_helix_angle;
    double center_distance;
    double pitch_radius[2], base_radius[2], tip_radius[2], root_radius[2], bore_radius[2];
    double base_pitch_transverse, base_pitch_normal;
    double contact_ratio_transverse, contact_ratio_face, contact_ratio_total;
    ...;
} gd_gear_pair_derived;
typedef struct {
    gd_tvms_method method; gd_gear_pair_derived geom; double mesh_period_rad;
    size_t n; size_t points; double *angle_rad; double *stiffness; int *pairs_in_contact;
    int max_pairs; double *load_share; double mean, max, min, peak_to_peak;
    double transverse_factor; int harmonics; double *harmonic_amplitude, *harmonic_phase;
    double iso_single_stiffness, iso_mesh_stiffness_alpha, iso_mesh_stiffness_beta;
    double body_stiffness; int slices; ...;
} gd_tvms_result;
const char *gd_tvms_method_name(gd_tvms_method m);
gd_status gd_tvms_method_parse(const char *name, gd_tvms_method *m, gd_error *err);
gd_status gd_tvms_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                          gd_tvms_result **out, gd_error *err);
void gd_tvms_free(gd_tvms_result *r);
gd_status gd_gear_pair_load(const char *path, const char *mesh_name,
                            const gd_load_options *opt, gd_gear_pair_geometry *geom,
                            gd_tvms_options *tvms, char *mesh_name_out, size_t size,
                            gd_error *err);
#define GD_LTCA_PARTIAL_FACE ...
#define GD_LTCA_EDGE_CONTACT ...
#define GD_LTCA_NO_CONTACT ...
typedef struct {
    gd_tvms_method method; gd_gear_pair_derived geom;
    double torque, force, misalignment, mesh_period_rad;
    size_t n, points; int slices, max_pairs; double slice_width, body_stiffness;
    double *angle_rad, *ste, *ste_unloaded, *stiffness; int *pairs_in_contact;
    double *pair_load, *line_load, *face_load_factor; int *flags; double *line_load_mean;
    double face_load_factor_cycle, ste_mean, ste_peak_to_peak;
    double stiffness_mean, stiffness_min, stiffness_max; int flagged; ...;
} gd_ltca_result;
gd_status gd_ltca_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                          gd_ltca_result **out, gd_error *err);
void gd_ltca_free(gd_ltca_result *r);
typedef struct {
    int nloads; size_t points; double *torque, *ste_peak_to_peak, *ste_mean, *stiffness_mean;
    double *face_load_factor_cycle; int *flagged; double *ste, *ste_unloaded; ...;
} gd_ltca_map;
gd_status gd_ltca_map_compute(const gd_gear_pair_geometry *g, const gd_tvms_options *opt,
                              const double *torques, int nloads, gd_ltca_map **out,
                              gd_error *err);
void gd_ltca_map_free(gd_ltca_map *m);
/* ---- test data, modal parameters, correlation (docs/testing.md) ---- */
typedef enum { GD_TD_RECEPTANCE, GD_TD_MOBILITY, GD_TD_ACCELERANCE, GD_TD_RATIO,
               ... } gd_td_quantity;
extern const char *const gd_td_quantity_names[4];
typedef struct { char name[...]; int function_type; int response_node, response_dir;
                 int reference_node, reference_dir; gd_td_quantity quantity;
                 char units[...]; double to_si; int n; double *freq_hz; double *re, *im;
                 int line; char file[...]; } gd_td_function;
typedef struct { int nfunctions; gd_td_function *functions; int nmodes; double *mode_hz;
                 double *mode_zeta; ...; } gd_testdata;
gd_status gd_testdata_read(int nfiles, const char *const *paths, int skip_other_datasets,
                           gd_testdata **out, gd_error *err);
void gd_testdata_free(gd_testdata *td);
const char *gd_td_dir_name(int dir);
typedef struct { double band_lo_hz, band_hi_hz; int max_order; double stab_freq, stab_damp,
                 max_damping, stable_share, peak_threshold; int poly_reference; }
               gd_ema_options;
typedef struct { int order; double frequency_hz, damping_ratio; char status; } gd_ema_pole;
typedef struct { double frequency_hz, damping_ratio; double lambda_re, lambda_im;
                 int stable_count; } gd_ema_mode;
typedef struct { int nfrf, nmodes; gd_ema_mode *modes; double *residue_re, *residue_im;
                 int npoles; gd_ema_pole *poles; int max_order; int nreferences;
                 double band_lo_hz, band_hi_hz; int nlines; } gd_ema_result;
void gd_ema_options_init(gd_ema_options *opt);
gd_status gd_ema_lscf(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt,
                      gd_ema_result **out, gd_error *err);
gd_status gd_ema_peaks(int nfrf, const gd_td_function *const *frfs, const gd_ema_options *opt,
                       gd_ema_result **out, gd_error *err);
void gd_ema_free(gd_ema_result *r);
typedef struct { int npoints; ...; } gd_test_setup;
gd_status gd_test_setup_load(const char *path, gd_test_setup **out, gd_error *err);
void gd_test_setup_free(gd_test_setup *s);
typedef struct { int nmodes; double *hz; double *zeta; int ndofs; int *dof; double *sign;
                 double *shape_re, *shape_im; } gd_measured_modes;
gd_status gd_measured_from_ema(const gd_system *sys, const gd_test_setup *setup, int nfrf,
                               const gd_td_function *const *frfs, const gd_ema_result *r,
                               gd_measured_modes *out, gd_error *err);
gd_status gd_measured_from_testdata(const gd_testdata *td, gd_measured_modes *out,
                                    gd_error *err);
void gd_measured_modes_free(gd_measured_modes *m);
typedef struct { int measured, model; double f_test, f_model, diff_pct; double mac;
                 double zeta_test; } gd_corr_pair;
typedef struct { int npairs; gd_corr_pair *pairs; double rms_pct; } gd_corr_table;
gd_status gd_correlate_modes(const gd_system *sys, const gd_measured_modes *mm,
                             gd_corr_table **out, gd_error *err);
void gd_corr_table_free(gd_corr_table *t);
gd_status gd_correlate_frf(const gd_system *sys, const gd_test_setup *setup,
                           const gd_td_function *f, gd_frf_quantity q, double *re, double *im,
                           gd_error *err);
typedef struct gd_model_source gd_model_source;
gd_status gd_model_source_load(const char *path, gd_model_source **out, gd_error *err);
void gd_model_source_free(gd_model_source *src);
typedef struct { const char *key; double lo, hi; } gd_update_param;
typedef struct { int nparams; const gd_update_param *params; gd_load_options load;
                 int max_iter; double tol; double step; int fd_check; } gd_update_options;
typedef struct { int nparams, ntargets, iterations; double *initial, *value, *sigma;
                 double *sens, *sens_fd; gd_corr_table *before, *after;
                 int at_bound; } gd_update_result;
void gd_update_options_init(gd_update_options *opt);
gd_status gd_model_update(const gd_model_source *src, const gd_measured_modes *mm,
                          const gd_update_options *opt, gd_update_result **out, gd_error *err);
void gd_update_free(gd_update_result *r);

"""


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--include", default=os.path.join(ROOT, "include"))
    ap.add_argument("--libdir", default=os.path.join(ROOT, "build"))
    a = ap.parse_args()
    include = os.path.abspath(a.include)
    libdir = os.path.abspath(a.libdir)
    if not os.path.exists(os.path.join(include, "geardyn", "geardyn.h")):
        sys.exit("build_ffi: no geardyn/geardyn.h under %s (give --include)" % include)
    if not any(f.startswith("libgeardyn.so") for f in os.listdir(libdir)):
        sys.exit("build_ffi: no libgeardyn.so in %s: build the library first (make build)"
                 % libdir)
    ffi = cffi.FFI()
    ffi.cdef(CDEF)
    # The configured version.h lives in the build tree; the other headers in include/.
    ffi.set_source(
        "geardyn._native",
        '#include "geardyn/geardyn.h"\n#include "geardyn/transient_model.h"\n',
        include_dirs=[include, os.path.join(libdir, "include")],
        library_dirs=[libdir],
        libraries=["geardyn"],
        extra_compile_args=["-O2", "-Wno-unused-parameter"],
        extra_link_args=["-Wl,-rpath," + libdir],
    )
    with tempfile.TemporaryDirectory() as tmp:
        so = ffi.compile(tmpdir=tmp, verbose=False)
        dest = os.path.join(HERE, "geardyn", os.path.basename(so))
        os.replace(so, dest)
    # The package's bytecode, as an installed package has it: without it every
    # `import geardyn` compiles its sources again (PYTHONDONTWRITEBYTECODE, a read-only
    # checkout), 5x the import's own time (issue 35: import <= 30 ms).
    compileall.compile_dir(os.path.join(HERE, "geardyn"), quiet=1)
    print("build_ffi: %s (links %s/libgeardyn.so)" % (os.path.relpath(dest, ROOT), libdir))


if __name__ == "__main__":
    main()
