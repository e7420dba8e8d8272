/* Building a model in code (docs/builder.md). The YAML reader (gd_model_load) is one
 * caller of this API; a program can be another: create a model, add materials,
 * shafts, nodes, disks, bearings, springs, gear meshes and the time-integration items
 * through small spec structs, then gd_model_finish discretises the shafts, propagates
 * the gear-train speeds, sizes and stiffens the meshes from their geometry and
 * validates, with the same located errors as the file reader.
 *
 * Specs. Every add function takes a spec struct; fill it with its _init function
 * (which sets the defaults documented on each field; most are zero) and set what you
 * need. Names refer to items by name: a shaft's sections name their material, a disk
 * names its node, a mesh its driver and driven nodes. Names are resolved by
 * gd_model_finish, so items may be added in any order; a generated node is named
 * "<shaft>@<index>" as in model files.
 *
 * Errors. Every function returns GD_OK or fills err (which may be NULL) and returns
 * the status: GD_EINPUT for a value that is wrong, GD_ENOMEM when out of memory. The
 * error's field is the item's path and key, e.g. "bearings[2].kxx" (the item's index
 * among its kind, in the order added), its line and column those of the spec's `loc`
 * (0 for a model built in code). A spec's `path`, when not NULL, replaces the default
 * path prefix ("bearings[2]"); the YAML reader passes the key paths of the file. A
 * failed add leaves the model as it was; the model can still be freed, or added to.
 *
 * Ownership and threads. The caller keeps ownership of everything it passes: specs,
 * their strings and arrays are read during the call and not kept; the builder copies
 * whatever it keeps. The model returned by gd_model_new is the caller's, to free with
 * gd_model_free, finished or not. After gd_model_finish succeeds the model is
 * immutable for the builder: every add or set returns GD_EINPUT. A model under
 * construction must not be used from two threads at once; distinct models may be
 * built concurrently (the builder has no global state). */
#ifndef GEARDYN_BUILDER_H
#define GEARDYN_BUILDER_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/laws.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/model.h"

/* An empty model. name stands for the file in error messages (e.g. "rig.c"; NULL:
 * ""). *out is NULL on failure. */
GD_API gd_status gd_model_new(const char *name, gd_model **out, gd_error *err);

/* Discretises the shafts into elements and nodes, resolves every name, propagates the
 * shaft speeds along the gear train from the reference shaft, sizes and stiffens the
 * meshes from their geometry (TVMS) and validates the whole. On failure the model
 * stays unfinished and can only be freed: adds and another finish are refused. */
GD_API gd_status gd_model_finish(gd_model *m, gd_error *err);

/* 1 once gd_model_finish has succeeded (and for models read from files). */
GD_API int gd_model_is_finished(const gd_model *m);

/* ---- materials ---- */

/* An isotropic material: E and one of poisson or G. With G = 0 (the default),
 * G = E / (2 (1 + poisson)); with G > 0 and poisson = 0, poisson = E / (2 G) - 1; both
 * given are kept as they are. Default path "materials.<name>". */
typedef struct gd_material_spec {
    const char *name; /* required, unique, < GD_NAME_MAX characters */
    double density;   /* kg/m^3, > 0 */
    double E;         /* Pa, > 0 */
    double G;         /* Pa; 0: from E and poisson */
    double poisson;   /* in (-1, 0.5) */
    gd_loc loc;
    const char *path;
} gd_material_spec;
/* Defaults: all zero. */
GD_API void gd_material_spec_init(gd_material_spec *s);
/* *index: the material's index. Errors: a missing, too long or repeated name; density
 * or E not positive; G negative; a Poisson's ratio outside (-1, 0.5). */
GD_API gd_status gd_model_add_material(gd_model *m, const gd_material_spec *s, int *index,
                                       gd_error *err);

/* ---- shafts and nodes ---- */

/* A section: a hollow cylinder of constant diameters along the shaft. */
typedef struct gd_section_spec {
    double length, outer_diameter; /* m, > 0 */
    double inner_diameter;         /* m, 0 (default) for a solid shaft, < outer */
    const char *material;          /* NULL: the shaft's material */
    int elements; /* elements this section is split into; 0 (default): the shaft's rule */
    gd_loc loc;
} gd_section_spec;

/* A named station (node) on a shaft, at an axial position from the shaft's start. On
 * a shaft with sections a station at a section end takes that node; elsewhere it
 * splits the section. On a shaft without sections (lumped bodies) `at` only orders
 * the nodes. */
typedef struct gd_station_spec {
    const char *name; /* required, unique among all nodes */
    double at;        /* m, within [0, shaft length] */
    gd_loc loc;
} gd_station_spec;

typedef struct gd_shaft_spec {
    const char *name;     /* NULL: "shaft<index + 1>"; shares one namespace with
                             bearings, springs and meshes */
    const char *material; /* default material of the sections; NULL: none */
    int nsections;
    const gd_section_spec *sections; /* nsections, from the shaft's start */
    int nstations;
    const gd_station_spec *stations; /* nstations named nodes (more: gd_model_add_node) */
    int elements_per_section;        /* 0 (default): 1 */
    double max_element_length;       /* > 0: sections without `elements` get elements no longer
                                        than this (excludes elements_per_section) */
    int has_speed_ratio;             /* 1: speed_ratio below is given */
    double speed_ratio;              /* signed, about +z, times the reference speed; it must agree
                                        with the gear meshes (they fix it when not given) */
    gd_loc loc;
    gd_loc speed_ratio_loc; /* where speed_ratio was written (errors about it) */
    const char *path;       /* NULL: "shafts[<index>]" */
} gd_shaft_spec;
/* Model size limits: elements in one section (given, per section, or from
 * max_element_length), and nodes in the whole model (6 DOFs each) unless
 * gd_model_set_max_nodes (the file's `limits: {max_nodes: N}`) raises it. Checked
 * before anything is allocated for the elements. */
#define GD_MAX_SECTION_ELEMENTS 10000
#define GD_MAX_NODES_DEFAULT 100000

/* Defaults: all zero (NULL names: the shaft's material; elements: the shaft's rule). */
GD_API void gd_section_spec_init(gd_section_spec *s);
/* Defaults: all zero. */
GD_API void gd_station_spec_init(gd_station_spec *s);
/* Defaults: all zero, speed_ratio 1 (used only with has_speed_ratio). */
GD_API void gd_shaft_spec_init(gd_shaft_spec *s);
/* *index: the shaft's index. Errors now: a too long name; neither sections nor
 * stations; both elements_per_section and max_element_length; a section's length or
 * outer diameter not positive, its bore not below its outer diameter, no material on
 * the section or the shaft, elements beyond 10000; a station without a name or outside
 * the shaft. At finish: an unknown material, a name repeating another shaft's, two
 * named stations at one position, a node name used twice, a speed_ratio the meshes
 * contradict. */
GD_API gd_status gd_model_add_shaft(gd_model *m, const gd_shaft_spec *s, int *index, gd_error *err);

/* One more named station on a shaft added before. */
typedef struct gd_node_spec {
    const char *shaft; /* the shaft's name */
    const char *name;  /* required */
    double at;         /* m */
    gd_loc loc;
    const char *path; /* NULL: "shafts[<shaft>].nodes[<station index>]" */
} gd_node_spec;
/* Defaults: all zero. */
GD_API void gd_node_spec_init(gd_node_spec *s);
/* *index: the station's index among the shaft's stations (the node's index in the
 * model is known after finish: gd_model_find_node). */
GD_API gd_status gd_model_add_node(gd_model *m, const gd_node_spec *s, int *index, gd_error *err);

/* ---- bodies and supports ---- */

/* A rigid disk: mass and inertias, or a solid (or bored) cylinder of a material. */
typedef struct gd_disk_spec {
    const char *name;         /* NULL: "disk<index + 1>"; unique among disks */
    const char *node;         /* required */
    double mass;              /* kg, >= 0 */
    double polar_inertia;     /* kg m^2, >= 0 */
    double diametral_inertia; /* kg m^2; < 0 (the default): polar_inertia / 2, a thin disk */
    int from_geometry;        /* 1: mass and inertias from the cylinder below */
    double outer_diameter, inner_diameter, width; /* m (geometry) */
    const char *material;                         /* required with geometry */
    gd_loc loc;
    const char *path; /* NULL: "disks[<index>]" */
} gd_disk_spec;
/* Defaults: all zero, diametral_inertia -1 (a thin disk). */
GD_API void gd_disk_spec_init(gd_disk_spec *s);
/* *index: the disk's index. Errors now: negative mass or polar inertia, no mass and no
 * inertia; with geometry: diameters or width not positive, the bore not below the outer
 * diameter, no material. At finish: an unknown node or material, a repeated name. */
GD_API gd_status gd_model_add_disk(gd_model *m, const gd_disk_spec *s, int *index, gd_error *err);

/* A linear bearing between a node and ground (or a second node): constant
 * coefficients, or coefficients interpolated in the speed of the node's shaft; an
 * optional squeeze film damper acts in time integration. */
typedef struct gd_bearing_spec {
    const char *name;               /* NULL: "bearing<index + 1>" */
    const char *node;               /* required */
    const char *to;                 /* NULL: ground */
    gd_bearing_coeffs coeffs;       /* constant coefficients (all 0 by default); the direct
                                       terms (xx, yy, zz, tilt, torsion) must not be negative */
    int ntable;                     /* 0, or >= 2 rows of a speed table (coeffs then all 0) */
    const double *table_speed;      /* ntable increasing speeds, rad/s */
    const gd_bearing_coeffs *table; /* ntable rows */
    int has_sfd;                    /* 1: sfd below */
    gd_sfd_params sfd;
    gd_loc loc;
    const char *path; /* NULL: "bearings[<index>]" */
} gd_bearing_spec;
/* Defaults: all zero (no coefficients, to ground, no table, no SFD). */
GD_API void gd_bearing_spec_init(gd_bearing_spec *s);
/* *index: the bearing's index. Errors now: a negative direct coefficient; a table of
 * one row, with constant coefficients too, or with speeds not increasing; an SFD whose
 * dimensions are not positive, max_eccentricity not below 1 or clearance not below
 * the radius; nothing at all (no coefficient, table or SFD). At finish: an unknown
 * node, a node joined to itself, a name already used. */
GD_API gd_status gd_model_add_bearing(gd_model *m, const gd_bearing_spec *s, int *index,
                                      gd_error *err);

/* A spring and damper on one DOF, to ground or to a second node. */
typedef struct gd_spring_spec {
    const char *name;          /* NULL: "spring<index + 1>" */
    const char *node;          /* required */
    const char *to;            /* NULL: ground */
    gd_dof dof;                /* default GD_RZ */
    double stiffness, damping; /* >= 0, not both 0 */
    gd_loc loc;
    const char *path; /* NULL: "springs[<index>]" */
} gd_spring_spec;
/* Defaults: all zero, dof GD_RZ. */
GD_API void gd_spring_spec_init(gd_spring_spec *s);
/* *index: the spring's index. Errors now: an unknown DOF, negative values, neither
 * stiffness nor damping. At finish: an unknown node, a node joined to itself, a name
 * already used. */
GD_API gd_status gd_model_add_spring(gd_model *m, const gd_spring_spec *s, int *index,
                                     gd_error *err);

/* ---- idling gears, synchronisers and gear selection (docs/model-format.md) ---- */

/* An idler: a gear turning on the node `on` of its carrying shaft through a needle
 * bearing. Adds a one-node shaft, its node and a disk, all named `name`, and the bearing
 * "<name>.needle" from it to `on` (kxx = kyy = kzz = radial_stiffness, k_tilt, no
 * torsion). Mesh it like any gear (driver or driven: its name). */
typedef struct gd_idler_spec {
    const char *name;         /* required, unique among shafts and nodes */
    const char *on;           /* required: the carrying shaft's node */
    double mass;              /* kg, > 0 */
    double polar_inertia;     /* kg m^2, > 0 */
    double diametral_inertia; /* kg m^2; < 0 (default): polar_inertia / 2 */
    double radial_stiffness;  /* N/m, > 0: the needle bearing, radial and axial */
    double tilt_stiffness;    /* N m/rad, >= 0 */
    double radial_damping;    /* N s/m, >= 0 */
    gd_loc loc;
    const char *path; /* NULL: "idlers[<index>]" */
} gd_idler_spec;
/* Defaults: all zero, diametral_inertia -1. */
GD_API void gd_idler_spec_init(gd_idler_spec *s);
/* Errors now: a missing name or node, mass, inertia or radial stiffness not positive, a
 * negative tilt stiffness or damping. At finish: an unknown node `on`, a name used by a
 * shaft or node. */
GD_API gd_status gd_model_add_idler(gd_model *m, const gd_idler_spec *s, int *index, gd_error *err);

/* A synchroniser (or dog clutch) on a shaft node between one or two idlers of that
 * shaft. The engaged one (`engaged`, or the selected gear's) is locked by a torsional
 * spring "<name>.lock" of `stiffness` and `damping` to the node. */
typedef struct gd_synchroniser_spec {
    const char *name;      /* required */
    const char *node;      /* required: a node of the shaft carrying its idlers */
    const char *idlers[2]; /* idler names; idlers[1] NULL for a one-sided one */
    const char *engaged;   /* NULL: neutral unless a selected gear engages one */
    double stiffness;      /* N m/rad, > 0; default 1e7 */
    double damping;        /* N m s/rad, >= 0; default 0 */
    gd_synchro_cone cone;  /* the cone for shifts (all 0: none; then mu, force, radius,
                              angle > 0 and cones >= 1) */
    gd_loc loc;
    const char *path; /* NULL: "synchronisers[<index>]" */
} gd_synchroniser_spec;
/* Defaults: all zero, stiffness 1e7 N m/rad. */
GD_API void gd_synchroniser_spec_init(gd_synchroniser_spec *s);
/* Errors now: missing name, node or idlers, the same idler twice, bad values. At finish:
 * a name that is not an idler (a gear fixed on its shaft cannot be engaged), an idler on
 * two synchronisers, `engaged` not one of its idlers, two gears engaged on it (its own
 * `engaged` and the selected gear's), the node not on the idlers' carrying shaft. */
GD_API gd_status gd_model_add_synchroniser(gd_model *m, const gd_synchroniser_spec *s, int *index,
                                           gd_error *err);

/* Gear `number` (>= 1; e.g. 1..5, reverse as 6) engages `idler` (`gears:`). path NULL:
 * "gears.<number>". At finish: the idler must exist and be on a synchroniser. */
GD_API gd_status gd_model_add_gear(gd_model *m, int number, const char *idler, gd_loc loc,
                                   const char *path, gd_error *err);
/* Selects gear `number` (0: none), the file's `gear:` (or `--set gear=3`). At finish:
 * an error listing the gears when it is not among them. */
GD_API gd_status gd_model_select_gear(gd_model *m, int number, gd_loc loc, gd_error *err);
/* A gear shift in time integration (`shift:`, `transient --shift 3:4@0.5`): at `time` the
 * engaged gear `from` is released (law gear_release cancels its lock) and the synchroniser
 * of gear `to` pulls its idler to speed with its cone torque, then locks it (law
 * synchro_cone, T_c = mu F R_c n / sin(alpha) from the synchroniser's `cone:`). The laws
 * act in time integration only; the linear analyses see gear `from`. At finish: `from`
 * must be engaged, `to` exist, differ and have a synchroniser with a cone. */
GD_API gd_status gd_model_set_shift(gd_model *m, int from, int to, double time, gd_loc loc,
                                    gd_error *err);

/* ---- planetary gear sets (docs/planetary.md) ---- */
/* One central member: its node and what the set adds there. */
typedef struct gd_planetary_member_spec {
    const char *node; /* required: the member's node (lumped or on an FE shaft) */
    double mass;      /* kg, >= 0 */
    double inertia;   /* kg m^2 about z, >= 0 */
    double k_support; /* N/m to ground in x and in y, >= 0 */
    double k_torsion; /* N m/rad to ground about z, >= 0; required (> 0) for the held member */
} gd_planetary_member_spec;
/* A planetary set ([LinParker1999]). Sizes: base radii of sun, ring and planet and the
 * carrier radius (planet centres), all > 0. Planets: nplanets >= 1 at planet_angles
 * (NULL: equally spaced, psi_n = 2 pi n / N), all with one mass, inertia and bearing. */
/* Table data y(x) the builder copies (x increasing). n = 0: no table. */
typedef struct gd_table_spec {
    int n;
    const double *x, *y;
    gd_interp interp; /* default GD_INTERP_LINEAR */
} gd_table_spec;

/* A planetary mesh kind's law in transient and periodic runs (docs/planetary.md, "Meshes
 * as laws"): any of these makes every mesh of the kind a gd_law_backlash_mesh. */
typedef struct gd_planetary_mesh_law_spec {
    gd_table_spec tvms;           /* k(sun angle relative to the carrier), N/m, over one sun
                                     mesh period 2 pi / Z_s (needs teeth); n = 0: none */
    double damping_per_stiffness; /* s, >= 0 */
    double damping_separated;     /* N s/m while the teeth are apart, >= 0 */
    int backlash;                 /* 1: a gap on each flank */
    double backlash_gap;          /* m, >= 0 */
    double coast_stiffness_ratio; /* >= 0, default 1; 0: one-sided contact */
} gd_planetary_mesh_law_spec;

/* A set's tooth geometry (docs/planetary.md, "Meshes from geometry"): with the teeth, the
 * sun-planet (external) and ring-planet (internal) pairs of docs/mesh-stiffness.md give
 * the base radii, carrier radius (the centre distance), operating pressure angles, contact
 * ratios, the meshes' TVMS (their mean the linear stiffness unless mesh_stiffness is given)
 * and the ring mesh's phase behind the sun mesh. */
typedef struct gd_planetary_geometry {
    double module;           /* normal module, m > 0 */
    double pressure_angle;   /* normal pressure angle, rad; default 20 deg */
    double face_width;       /* m > 0 */
    double profile_shift[3]; /* sun, ring (ISO 21771 sign), planet; coefficients */
    gd_tvms_options tvms;    /* method, points (gd_tvms_options_init) */
} gd_planetary_geometry;
GD_API void gd_planetary_geometry_init(gd_planetary_geometry *g);

typedef struct gd_planetary_spec {
    const char *name; /* required; the planets' shafts and nodes are named after it */
    gd_planetary_member_spec member[GD_PLANETARY_NMEMBERS]; /* sun, ring, carrier */
    int held;                    /* gd_planetary_member, or -1 (default): none held */
    int nplanets;                /* 1 .. GD_PLANETARY_MAX_PLANETS */
    const double *planet_angles; /* nplanets angles, rad, increasing within [0, 2 pi); NULL */
    double planet_mass, planet_inertia; /* kg > 0, kg m^2 > 0 */
    double bearing_stiffness;           /* N/m > 0, radial and tangential */
    const double *pin_errors;           /* nplanets tangential pin position errors, m (in the
                                           carrier's sense of rotation); NULL: none */
    const double *pin_errors_radial;    /* nplanets radial pin position errors, m (outwards);
                                           NULL: none */
    int teeth[3];                       /* sun, ring, planet; 0: not given (all or none) */
    double base_radius[3];              /* sun, ring, planet, m > 0 */
    double carrier_radius;              /* m > 0 */
    double pressure_angle[2];           /* sun-planet, ring-planet, rad; default 20 deg */
    double helix_angle;                 /* rad, default 0 */
    double planet_tip_radius;           /* m; 0: estimated from the teeth (docs/planetary.md) */
    double mesh_stiffness[2];           /* sun-planet, ring-planet, N/m > 0 */
    double mesh_damping[2];             /* N s/m >= 0 */
    /* which bodies get the carrier-frame terms when the carrier turns: 1 all (the whole set
       in the carrier frame, [CooleyParker2012]), 0 the planets only (members on shafts
       modelled in the fixed frame), -1 (default) all when every member sits on a shaft
       without sections, else the planets */
    int carrier_frame;
    /* 1 (default): the planet bearings' geometric stiffness of the planets' centrifugal load
       at carrier speed; 0: left out, as in [CooleyParker2012] Eq. 1 (docs/planetary.md) */
    int centrifugal_stiffness;
    /* meshes as laws ([0] sun-planet, [1] ring-planet) and their phases: nplanets phases
       each in mesh periods, [0, 1) (NULL: from the teeth, [ParkerLin2004]); the ring
       mesh's lag behind the sun mesh (has_sun_ring_phase 0: from the geometry, or 0) */
    gd_planetary_mesh_law_spec mesh_law[2];
    const double *mesh_phases[2];
    double sun_ring_phase;
    int has_sun_ring_phase;
    /* tooth geometry (NULL: none; needs teeth; then base_radius and carrier_radius stay 0
       and mesh_stiffness may be 0: from the geometry) */
    const gd_planetary_geometry *geometry;
    gd_loc loc;
    const char *path; /* NULL: "planetary_sets[<index>]" */
} gd_planetary_spec;
/* Defaults: all zero, held -1, pressure angles 20 deg, centrifugal_stiffness 1. */
GD_API void gd_planetary_spec_init(gd_planetary_spec *s);
/* *index: the set's index. Adds one lumped shaft per planet. Errors now: a missing or
 * too long name, values out of range, angles not increasing in [0, 2 pi), teeth given
 * in part, planets whose tips overlap at their spacing, tooth counts that cannot be
 * assembled at the angles ((Z_s + Z_r) psi_n / 2 pi not a whole number), a ring whose
 * pitch circle is inside the planets' span, a held member without torsional support.
 * At finish: an unknown node, two members on one node, a held member's node also held
 * torsionally elsewhere (a bearing or spring to ground about z, or another set). */
GD_API gd_status gd_model_add_planetary(gd_model *m, const gd_planetary_spec *s, int *index,
                                        gd_error *err);

/* ---- gear meshes ---- */

/* An external gear mesh. The gear size is given by exactly one of base_radius,
 * pitch_radius, module (with teeth), or geometry. */
typedef struct gd_mesh_spec {
    const char *name;       /* required */
    const char *driver;     /* node of the driving gear, required */
    const char *driven;     /* node of the driven gear, on another shaft */
    int teeth[2];           /* 0: not given; >= 3 */
    double base_radius[2];  /* m; 0: not given */
    double pitch_radius[2]; /* m; 0: not given */
    double module;          /* m; 0: not given */
    double pressure_angle;  /* transverse, rad, < 60 deg; default 20 deg */
    double helix_angle;     /* rad, < 60 deg; default 0 (spur) */
    int hand;               /* of the driver: +1 right (default), -1 left */
    double line_of_centres; /* rad, from +x, driver -> driven centre */
    int driver_rotation;    /* 0: not checked; +1 ccw / -1 cw: must match the train */
    /* geometry (docs/mesh-stiffness.md): the teeth, angles and hand come from it */
    const gd_gear_pair_geometry *geometry; /* NULL: none */
    int stiffness_from_geometry;           /* 1: k(angle) by gd_tvms_compute (needs geometry) */
    /* for stiffness_from_geometry (defaults); with tvms_options.contact_analysis the loaded
       stiffness of gd_ltca_compute at load_torque, and the transmission error
       delta - F0 / k_L (docs/mesh-stiffness.md, "Loaded contact analysis") */
    gd_tvms_options tvms_options;
    double stiffness;     /* N/m along the contact normal, > 0; 0: from the tvms table or the
                             geometry (required otherwise) */
    double damping;       /* N s/m, >= 0 */
    double face_width;    /* m, >= 0; 0: unknown, or from the geometry (not both) */
    gd_coupling coupling; /* default GD_COUPLING_FULL */
    /* time integration (docs/transient.md) */
    double damping_per_stiffness;     /* s, >= 0 */
    double damping_separated;         /* N s/m while the teeth are apart, >= 0 */
    gd_table_spec tvms;               /* k(driver angle) over one mesh period; needs teeth */
    double tvms_phase;                /* rad */
    gd_table_spec transmission_error; /* e(driver angle), m, over one mesh period */
    int backlash;                     /* 1: a gap on each flank */
    double backlash_gap;              /* m, >= 0 */
    double coast_stiffness_ratio;     /* >= 0, default 1; 0: one-sided contact */
    gd_loc loc;
    const char *path; /* NULL: "meshes[<index>]" */
} gd_mesh_spec;
/* Defaults: all zero, pressure_angle 20 deg, hand +1, coupling full, tvms_options from
 * gd_tvms_options_init, linear table interpolation, coast_stiffness_ratio 1. */
GD_API void gd_mesh_spec_init(gd_mesh_spec *s);
/* *index: the mesh's index. Errors now: no name; teeth below 3; radii or module not
 * positive; angles negative or not below 60 deg; the gear size missing or given twice;
 * a module without teeth; radii and teeth of different ratios; teeth with geometry;
 * stiffness from geometry without geometry; a tvms or transmission_error table without
 * the driver's teeth, with fewer than two points, or (tvms) with a value not
 * positive, or given with stiffness from geometry, or (transmission_error) given with the
 * contact analysis; no stiffness at all. At finish:
 * unknown nodes, both gears on one shaft, the geometry invalid (gd_gear_pair_derive,
 * gd_tvms_compute), a table outside one mesh period, a name already used, a loop of
 * meshes whose ratios disagree, driver_rotation against the train. With
 * stiffness_from_geometry the TVMS mean is the linear stiffness. */
GD_API gd_status gd_model_add_mesh(gd_model *m, const gd_mesh_spec *s, int *index, gd_error *err);

/* ---- unbalances and time-integration items ---- */

typedef struct gd_unbalance_spec {
    const char *name; /* NULL: "unbalance<index + 1>" */
    const char *node; /* required */
    double amount;    /* kg m, > 0 */
    double phase;     /* rad */
    gd_loc loc;
    const char *path; /* NULL: "unbalances[<index>]" */
} gd_unbalance_spec;
/* Defaults: all zero. */
GD_API void gd_unbalance_spec_init(gd_unbalance_spec *s);
/* *index: the unbalance's index. Errors: amount not positive; at finish an unknown
 * node. */
GD_API gd_status gd_model_add_unbalance(gd_model *m, const gd_unbalance_spec *s, int *index,
                                        gd_error *err);

/* An applied load. law.kind says which law; law.table is ignored: a
 * GD_LOAD_TABLE_ANGLE law takes its values over one revolution from `table`. */
typedef struct gd_excitation_spec {
    const char *name; /* NULL: "load<index + 1>" */
    const char *node; /* required */
    gd_dof dof;       /* default GD_RZ */
    gd_load_law law;  /* default constant 0 */
    gd_table_spec table;
    gd_loc loc;
    const char *path; /* NULL: "excitations.loads[<index>]" */
} gd_excitation_spec;
/* Defaults: all zero, dof GD_RZ, a constant law, linear table interpolation. */
GD_API void gd_excitation_spec_init(gd_excitation_spec *s);
/* *index: the load's index. Errors: an unknown DOF or law, a harmonic frequency (or
 * order) not positive, a table law without two points; at finish an unknown node or a
 * table gd_table_new refuses (over one revolution, 2 pi). */
GD_API gd_status gd_model_add_excitation(gd_model *m, const gd_excitation_spec *s, int *index,
                                         gd_error *err);
/* Whether the unbalances act in time integration (default 1). */
GD_API gd_status gd_model_set_excite_unbalances(gd_model *m, int on, gd_error *err);

/* A prescribed DOF motion; a GD_PRESCRIBED_TABLE law takes its values (total value vs
 * time) from `table` (default interpolation there: spline). */
typedef struct gd_prescribed_spec {
    const char *node;      /* required */
    gd_dof dof;            /* default GD_RZ; each node DOF at most once */
    gd_prescribed_law law; /* default nominal */
    gd_table_spec table;
    gd_loc loc;
    const char *path; /* NULL: "prescribed[<index>]" */
} gd_prescribed_spec;
/* Defaults: all zero, dof GD_RZ, the nominal motion, spline table interpolation. */
GD_API void gd_prescribed_spec_init(gd_prescribed_spec *s);
/* *index: the prescription's index. Errors: an unknown DOF or kind, a harmonic
 * frequency not positive, a table law without two points; at finish an unknown node,
 * a DOF prescribed twice, a table gd_table_new refuses. */
GD_API gd_status gd_model_add_prescribed(gd_model *m, const gd_prescribed_spec *s, int *index,
                                         gd_error *err);

/* Valve trains on a camshaft node: a lift law (lift.kind GD_LIFT_TABLE takes s(angle)
 * over one revolution from `lift_table`, default spline; GD_LIFT_HARMONIC uses
 * lift.harmonic) and a mass and phase per valve. */
typedef struct gd_cam_spec {
    const char *name;     /* NULL: "cam<index + 1>" */
    const char *camshaft; /* node, required */
    gd_lift_law lift;     /* default: a table */
    gd_table_spec lift_table;
    int include_acceleration;               /* default 1 */
    int nvalves;                            /* >= 1 */
    const double *valve_mass, *valve_phase; /* kg (> 0), rad */
    gd_loc loc;
    const char *path; /* NULL: "cam_torques[<index>]" */
} gd_cam_spec;
/* Defaults: all zero, a table lift law (spline), include_acceleration 1. */
GD_API void gd_cam_spec_init(gd_cam_spec *s);
/* *index: the cam's index. Errors: no lift table (or more than GD_HARMONICS_MAX
 * harmonics), no valves, a valve mass not positive; at finish an unknown node or a
 * lift table gd_table_new refuses (over one revolution). valve_phase may be NULL
 * (all 0). */
GD_API gd_status gd_model_add_cam(gd_model *m, const gd_cam_spec *s, int *index, gd_error *err);

/* A law of the registry (include/geardyn/law_type.h): a squeeze film damper, a
 * polynomial spring, friction, or a user's own type, on `node` (and `node2`, the other
 * side, for two-node types; NULL: ground). A type without directions of its own acts
 * in `dof`. values[k] is parameter k of the type's table in SI (NAN: its default);
 * NULL: every default. The type is borrowed: it must outlive the model. */
typedef struct gd_law_spec {
    const char *name;        /* NULL: "<type><index + 1>" */
    const gd_law_type *type; /* required */
    const char *node;        /* required */
    const char *node2;       /* two-node types; NULL: ground */
    gd_dof dof;              /* types with ndirs = 0; default GD_X */
    const double *values;    /* type->nparams values, or NULL */
    gd_loc loc;
    const char *path; /* NULL: "laws[<index>]" */
} gd_law_spec;
/* Defaults: all zero (dof GD_X, every parameter at its default). */
GD_API void gd_law_spec_init(gd_law_spec *s);
/* *index: the law's index. Errors: no type or an invalid type table, node2 on a
 * one-node type, a parameter missing, not finite or out of its bounds (the field names
 * it); at finish an unknown node. Whether the DOFs are active is checked where a
 * problem is made from the model (gd_transient_model_build). */
GD_API gd_status gd_model_add_law(gd_model *m, const gd_law_spec *s, int *index, gd_error *err);

/* ---- globals ---- */

/* The active node DOFs (GD_DOF_BIT mask, not 0; default GD_DOFS_ALL). */
GD_API gd_status gd_model_set_dofs(gd_model *m, unsigned dof_mask, gd_error *err);
/* The shaft whose speed is the reference speed (default: the first shaft) and its
 * sense: rotation +1 turns it about +z (ccw, default), -1 about -z (cw). loc locates
 * errors about an unknown name. */
GD_API gd_status gd_model_set_reference_shaft(gd_model *m, const char *shaft, int rotation,
                                              gd_loc loc, gd_error *err);
/* The most nodes the shafts may be discretised into (default GD_MAX_NODES_DEFAULT);
 * gd_model_finish fails, before allocating them, on a model that would have more.
 * max_nodes >= 1; loc locates errors about it. */
GD_API gd_status gd_model_set_max_nodes(gd_model *m, long max_nodes, gd_loc loc, gd_error *err);
/* Rayleigh damping C += alpha M + beta K (alpha 1/s, beta s, both finite and >= 0;
 * default 0) with K the constant stiffness: elements, bearings without speed tables,
 * mean mesh stiffness. */
GD_API gd_status gd_model_set_rayleigh(gd_model *m, double alpha, double beta, gd_error *err);
/* alpha and beta that give the damping ratios z1, z2 at the angular frequencies w1 !=
 * w2 (rad/s, > 0): z = alpha / (2 w) + beta w / 2 at each ([JMSTHelical], Rayleigh). GD_EINPUT
 * when w1 = w2 or the ratios need a negative alpha or beta. */
GD_API gd_status gd_rayleigh_from_ratios(double z1, double z2, double w1, double w2, double *alpha,
                                         double *beta, gd_error *err);
/* Gravity: acceleration g (m/s^2, finite, >= 0) along direction (three finite values,
 * not all zero; normalised here), in the model's axes (shafts along z). Default none.
 * Errors are located at loc, field "gravity". */
GD_API gd_status gd_model_set_gravity(gd_model *m, const double direction[3], double g, gd_loc loc,
                                      gd_error *err);
/* The reference speed, rad/s, >= 0 (default 0). */
GD_API gd_status gd_model_set_speed(gd_model *m, double speed, gd_error *err);

#endif
