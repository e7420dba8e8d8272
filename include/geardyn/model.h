/* The model: a typed, validated description of a geared rotor system, read from a
 * YAML file (docs/model-format.md) or built in code (geardyn/builder.h, which the
 * file reader uses too). Validation lives in the builder; every later layer trusts a
 * finished gd_model. All quantities are SI.
 *
 * Ownership and threads: a model is made by gd_model_load / gd_model_load_string
 * (model_file.h has the variants with overrides) or gd_model_new + gd_model_finish
 * (builder.h), and freed by gd_model_free; it owns every array and table it points to.
 * A finished model is read-only for the rest of the library: systems, analyses and
 * several threads may read one model at once. gd_model_set_coupling and
 * gd_model_restrict_dofs change it: call them before building a system from it.
 */
#ifndef GEARDYN_MODEL_H
#define GEARDYN_MODEL_H
#include "geardyn/export.h"
#include "geardyn/error.h"
#include "geardyn/material.h"
#include "geardyn/laws.h"

#define GD_NAME_MAX 64
/* node names: a user's name, or a generated "<shaft>@<index>" */
#define GD_NODE_NAME_MAX (GD_NAME_MAX + 16)

/* Node DOFs, in this order: two lateral translations, axial translation, two tilts,
 * torsion about the shaft axis z. */
typedef enum gd_dof { GD_X, GD_Y, GD_Z, GD_RX, GD_RY, GD_RZ, GD_NODE_DOFS } gd_dof;
#define GD_DOF_BIT(d) (1u << (d))
#define GD_DOFS_ALL 0x3fu
GD_API extern const char *const gd_dof_names[GD_NODE_DOFS]; /* "x", "y", "z", "rx", "ry", "rz" */

typedef enum gd_coupling {
    GD_COUPLING_TORSIONAL,         /* rz only */
    GD_COUPLING_LATERAL_TORSIONAL, /* x, y, rz */
    GD_COUPLING_FULL,              /* all six */
} gd_coupling;
GD_API extern const char *const gd_coupling_names[3];
/* The node DOFs a coupling level keeps: torsional {rz}; lateral-torsional drops the
 * axial DOF z; full keeps all. (Shaft bending needs the tilts, so they stay.) */
GD_API unsigned gd_coupling_dof_mask(gd_coupling level);

typedef struct gd_loc {
    int line, column; /* where in the model file, for errors found later */
} gd_loc;

typedef struct gd_section {
    double length, outer_diameter, inner_diameter;
    int material;
    int elements;              /* number of elements this section is split into */
    double max_element_length; /* > 0: no element longer than this (0: use elements) */
    gd_loc loc;
} gd_section;

typedef struct gd_shaft {
    char name[GD_NAME_MAX];
    int nsections;
    gd_section *sections;
    int first_node, nnodes; /* the shaft's nodes are contiguous, ordered by position */
    double speed_ratio;     /* signed: speed = speed_ratio * reference speed, about +z */
    int speed_ratio_given;
    gd_loc loc;
    gd_loc speed_ratio_loc; /* of the speed_ratio key, when given */
} gd_shaft;

typedef struct gd_node {
    char name[GD_NODE_NAME_MAX]; /* user's name, or "<shaft>@<index>" if generated */
    int shaft;
    double position; /* axial position along the shaft, m */
    int named;       /* named by the user */
    int list_index;  /* index in the shaft's `nodes:` list, -1 if generated */
    gd_loc loc;
} gd_node;

/* A 2-node Timoshenko shaft element, generated from the sections. */
typedef struct gd_element {
    int shaft, section, node1, node2;
    double length, outer_diameter, inner_diameter;
    int material;
} gd_element;

typedef struct gd_disk {
    char name[GD_NAME_MAX];
    int node;
    double mass, polar_inertia, diametral_inertia;
    gd_loc loc;
} gd_disk;

/* Linear bearing/support coefficients (stiffness N/m, N m/rad; damping N s/m, ...). */
typedef struct gd_bearing_coeffs {
    double kxx, kxy, kyx, kyy, kzz, ktilt, ktorsion;
    double cxx, cxy, cyx, cyy, czz, ctilt, ctorsion;
} gd_bearing_coeffs;

typedef struct gd_bearing {
    char name[GD_NAME_MAX];
    int node, node2; /* node2 = -1: to ground */
    int has_sfd;     /* a squeeze film damper acts here in time integration */
    gd_sfd_params sfd;
    gd_bearing_coeffs coeffs; /* constant coefficients (or the table's first row) */
    int ntable;               /* > 0: coefficients interpolated in speed of the node's shaft */
    double *table_speed;      /* ntable speeds, increasing, rad/s */
    gd_bearing_coeffs *table; /* ntable rows */
    gd_loc loc;
} gd_bearing;

/* Lumped spring and damper on one DOF, between two nodes or from a node to ground. */
typedef struct gd_spring {
    char name[GD_NAME_MAX];
    int node1, node2; /* node2 = -1: to ground */
    gd_dof dof;
    double stiffness, damping;
    gd_loc loc;
} gd_spring;

struct gd_tvms_result;

/* What a mesh does in time integration beyond its constant k and c (docs/transient.md).
 * Tables are owned by the model. */
typedef struct gd_mesh_dynamics {
    gd_table *tvms;               /* k(driver angle), N/m, one mesh period; NULL: the
                                     `stiffness: {from: geometry}` result, or constant */
    double tvms_phase;            /* added to the driver angle, rad */
    double damping_per_stiffness; /* c = damping + this * k(angle), s */
    double damping_separated;     /* while the teeth are apart (backlash), N s/m */
    gd_table *ste;                /* static transmission error e(driver angle), m; NULL */
    int backlash;                 /* 1: gap on each flank */
    double gap;                   /* b, m */
    double coast_stiffness_ratio; /* k_coast / k_drive (default 1; 0: one-sided contact) */
} gd_mesh_dynamics;

/* External gear mesh between a driving and a driven gear on different shafts. The
 * mesh deformation is d = a . q along the contact normal; stiffness k acts on d. */
typedef struct gd_mesh {
    char name[GD_NAME_MAX];
    int driver, driven;        /* node indices */
    int teeth[2];              /* 0 when not given */
    double base_radius[2];     /* m */
    double pressure_angle;     /* transverse operating pressure angle, rad */
    double helix_angle;        /* at the pitch circle, rad (0: spur) */
    double base_helix_angle;   /* derived: tan(bb) = tan(b) cos(alpha_t) */
    int hand;                  /* driver's hand: +1 right, -1 left */
    double line_of_centres;    /* angle from +x of the line driver -> driven centre, rad */
    int driver_sense;          /* derived: +1 driver turns about +z at positive speed */
    double stiffness, damping; /* along the contact normal: N/m, N s/m */
    gd_coupling coupling;
    /* stiffness: {from: geometry}: k(driver angle) over a mesh cycle, owned; stiffness
     * above is its mean (linear analyses). NULL for a constant stiffness. */
    struct gd_tvms_result *tvms;
    double face_width; /* b, m: from `geometry:` or the `face_width` key; 0 unknown */
    gd_mesh_dynamics dyn;
    gd_loc loc;
} gd_mesh;

/* Rotating unbalance at a node: amount = mass x eccentricity (kg m), turning with the
 * node's shaft; phase is the angle of the heavy spot at t = 0 from +x, in the sense of
 * the shaft's rotation. */
typedef struct gd_unbalance {
    char name[GD_NAME_MAX];
    int node;
    double amount, phase;
    gd_loc loc;
} gd_unbalance;

/* An applied torque or force on one DOF (time integration). */
typedef struct gd_excitation {
    char name[GD_NAME_MAX];
    int node;
    gd_dof dof;
    gd_load_law law; /* law.table, if any, is owned */
    gd_loc loc;
} gd_excitation;

/* A DOF whose motion is prescribed (time integration). */
typedef struct gd_prescription {
    int node;
    gd_dof dof;
    gd_prescribed_law law; /* law.table, if any, is owned */
    gd_loc loc;
} gd_prescription;

/* The valve trains of one camshaft ([Benini2004] Eq. 10): one lift law, a mass and phase per
 * valve. */
typedef struct gd_cam {
    char name[GD_NAME_MAX];
    int node;
    gd_lift_law lift; /* lift.table, if any, is owned */
    int include_acceleration;
    int nvalves;
    double *valve_mass, *valve_phase;
    gd_loc loc;
} gd_cam;

/* A law of the registry (include/geardyn/law_type.h) acting on a node's DOFs: the
 * type's directions at node, then at node2 (-1: ground), or one direction `dof` for a
 * type with no directions of its own. */
typedef struct gd_model_law {
    char name[GD_NAME_MAX];
    const gd_law_type *type;
    int node, node2;
    gd_dof dof;
    double value[GD_LAW_MAX_PARAMS]; /* SI, in the type's parameter order */
    gd_loc loc;
} gd_model_law;

/* A planetary (epicyclic) gear set: sun, ring (internal gear), carrier and N planets,
 * the lumped lateral-torsional model of [LinParker1999] (docs/planetary.md). Sun, ring
 * and carrier sit on model nodes (lumped or FE shaft nodes): x, y and rz of those nodes
 * are the members' translations and rotation. Each planet gets a node of its own on a
 * generated one-node shaft ("<set>.planet<n>", node "<set>.p<n>"), its x, y in the model
 * axes. Meshes act along their lines of action, planet bearings join each planet to its
 * pin on the carrier (at carrier_radius, angle planet_angle[n] from +x). */
typedef enum gd_planetary_member {
    GD_PLANETARY_SUN,
    GD_PLANETARY_RING,
    GD_PLANETARY_CARRIER,
    GD_PLANETARY_NMEMBERS
} gd_planetary_member;
GD_API extern const char *const gd_planetary_member_names[GD_PLANETARY_NMEMBERS];

#define GD_PLANETARY_MAX_PLANETS 64

typedef struct gd_planetary_body {
    int node;             /* model node of the member */
    double mass, inertia; /* kg (each of x, y), kg m^2 about z; added to the node */
    double k_support;     /* N/m, to ground in x and in y */
    double k_torsion;     /* N m/rad, to ground about z (the held member's holding spring) */
} gd_planetary_body;

/* A planetary mesh's law in transient and periodic runs (docs/planetary.md, "Meshes as
 * laws"), the same gd_law_backlash_mesh a parallel mesh gets. Its angle variable is the
 * sun's rotation relative to the carrier at its nominal speed (one mesh period =
 * 2 pi / Z_s for both kinds of mesh), each planet's mesh delayed by its phase. */
typedef struct gd_planetary_mesh_law {
    int active;                   /* 1: the meshes of this kind are laws (else linear in K) */
    gd_table *tvms;               /* k(sun angle rel. carrier), N/m, owned; NULL: constant */
    double damping_per_stiffness; /* s */
    double damping_separated;     /* N s/m while the teeth are apart */
    int backlash;                 /* 1: a gap on each flank */
    double gap;                   /* m */
    double coast_stiffness_ratio; /* default 1; 0: one-sided contact */
} gd_planetary_mesh_law;

typedef struct gd_planetary {
    char name[GD_NAME_MAX];
    gd_planetary_body member[GD_PLANETARY_NMEMBERS];
    int held;                 /* gd_planetary_member held to ground torsionally, -1: none */
    int nplanets;             /* >= 1 */
    int first_planet;         /* planet n is node first_planet + n (consecutive) */
    double *planet_angle;     /* nplanets angles psi_n from +x, rad, increasing (owned) */
    int equally_spaced;       /* the angles were not given: psi_n = 2 pi n / N */
    int teeth[3];             /* sun, ring, planet; 0: not given */
    double base_radius[3];    /* sun, ring, planet, m */
    double carrier_radius;    /* radius of the planet centres, m */
    double pressure_angle[2]; /* operating, sun-planet and ring-planet meshes, rad */
    double helix_angle;       /* rad (0: spur); only the transverse model is built */
    double planet_tip_radius; /* m: given, or estimated (docs/planetary.md) */
    double planet_mass, planet_inertia; /* kg, kg m^2 */
    double bearing_stiffness;           /* planet bearing, N/m radial and tangential */
    double *pin_error;        /* nplanets tangential pin position errors, m (owned; NULL: none):
                                 the bearing's unloaded position (static load sharing) */
    double *pin_error_radial; /* nplanets radial pin position errors, m, outwards (owned; NULL:
                                 none) */
    double mesh_stiffness[2]; /* sun-planet, ring-planet, N/m along the line of action */
    double mesh_damping[2];   /* N s/m */
    /* the carrier-frame terms ([CooleyParker2012]) act on every body of the set (1) or on the
       planets only (0): docs/planetary.md */
    int carrier_frame_all;
    /* 1: the planet bearings' geometric stiffness of the planets' centrifugal load at carrier
       speed (default); 0: left out, as in [CooleyParker2012] Eq. 1 (docs/planetary.md) */
    int centrifugal_stiffness;
    /* meshes as laws, [0] sun-planet, [1] ring-planet (docs/planetary.md) */
    gd_planetary_mesh_law mesh_law[2];
    /* each planet's mesh phase, mesh periods in [0, 1) (planet n's mesh meets its tooth that
       much after the reference), given (owned, nplanets each) or NULL: from the teeth
       ([ParkerLin2004], gd_planetary_mesh_phase) */
    double *mesh_phase[2];
    /* the ring mesh's lag behind the sun mesh of the same planet, mesh periods: from the
       tooth geometry (between the TVMS tables' origins) or given; 0 otherwise */
    double sun_ring_phase;
    /* from the tooth geometry (0: none): transverse contact ratios and the mesh stiffness
       results, k(driver angle) of the sun (driver) - planet and planet (driver) - ring
       pairs (owned) */
    double contact_ratio[2];
    struct gd_tvms_result *tvms[2];
    /* the names of the set's 3 + 4N element instances (strain-energy components), in the
       element's order: SET.sun, .ring, .carrier, .planet<n>, .sun_mesh<n>, .ring_mesh<n>,
       .bearing<n> (owned) */
    char (*instance_name)[GD_NAME_MAX + 16];
    gd_loc loc;
} gd_planetary;

/* An idling gear (docs/model-format.md, "idlers"): a gear that turns on its carrying
 * shaft through a needle bearing. It has a node of its own on a generated one-node shaft
 * named after it (node, shaft and disk take the idler's name), joined to the carrying
 * node by a bearing "<idler>.needle" (radial, axial and tilt stiffness, no torsion): its
 * rotation is free except for the drag laws given on it and its synchroniser's lock. */
typedef struct gd_idler {
    char name[GD_NAME_MAX];
    int node;         /* the idler's own node */
    int carrier;      /* the carrying shaft's node */
    int synchroniser; /* index of the synchroniser that engages it, -1: none */
    int engaged;      /* 1: locked to its shaft by the selected gear */
    gd_loc loc;
} gd_idler;

/* The cone of a synchroniser: its friction torque while the speeds are matched,
 * T = mu F R_cone n_cones / sin(alpha) (docs/rattle.md, "Shifting"). */
typedef struct gd_synchro_cone {
    double mu, force, radius, angle; /* -, N, m, rad (the cone's half angle) */
    int cones;                       /* friction surfaces */
} gd_synchro_cone;

/* A synchroniser or dog clutch on a shaft node between one or two idlers. The engaged
 * idler is locked to the node by a stiff torsional spring "<synchroniser>.lock" (rz,
 * `stiffness`, `damping`): a spring, not a constraint, so that every analysis and a shift
 * in time integration see the same DOFs (docs/model-format.md). */
typedef struct gd_synchroniser {
    char name[GD_NAME_MAX];
    int node;
    int idler[2];              /* idler indices, idler[1] = -1 for a one-sided one */
    int engaged;               /* idler index locked, -1: neutral */
    int spring;                /* the lock's spring index, -1 when neutral */
    double stiffness, damping; /* the lock: N m/rad, N m s/rad */
    gd_synchro_cone cone;      /* cone.mu = 0: no cone given (a dog clutch) */
    gd_loc loc;
} gd_synchroniser;

/* Gear number -> the idler its selection engages (`gears:`). */
typedef struct gd_gear_choice {
    int number;
    int idler;
} gd_gear_choice;

typedef struct gd_model {
    char file[256];
    int nmaterials;
    gd_material *materials;
    int nshafts;
    gd_shaft *shafts;
    int nnodes;
    gd_node *nodes;
    int nelements;
    gd_element *elements;
    int ndisks;
    gd_disk *disks;
    int nbearings;
    gd_bearing *bearings;
    int nsprings;
    gd_spring *springs;
    int nmeshes;
    gd_mesh *meshes;
    int nunbalances;
    gd_unbalance *unbalances;
    /* time integration (docs/transient.md) */
    int nexcitations;
    gd_excitation *excitations;
    int excite_unbalances; /* the unbalances act in time integration (default 1) */
    int nprescribed;
    gd_prescription *prescribed;
    int ncams;
    gd_cam *cams;
    int nlaws;
    gd_model_law *laws;
    int nplanetary; /* planetary sets (docs/planetary.md) */
    gd_planetary *planetary;
    int nidlers; /* idling gears and their synchronisers (docs/model-format.md) */
    gd_idler *idlers;
    int nsynchronisers;
    gd_synchroniser *synchronisers;
    int ngears;
    gd_gear_choice *gears;
    int gear;            /* the selected gear number, 0: none (the synchronisers' own `engaged`) */
    unsigned dof_mask;   /* active node DOFs (GD_DOF_BIT) */
    int reference_shaft; /* shaft whose speed is the reference speed */
    double speed;        /* reference speed, rad/s (0 unless given) */
    /* Rayleigh damping C += alpha M + beta K ([JMSTHelical]; 0 unless given), K the constant
       stiffness (speed tables of bearings not included) */
    double rayleigh_alpha, rayleigh_beta; /* 1/s, s */
    /* gravitational acceleration, m/s^2, in the model's axes (`gravity:`; zero unless
       given): the static analysis (geardyn/static.h) loads the masses with it */
    double gravity[3];
    /* builder state while the model is built (include/geardyn/builder.h); NULL once
       gd_model_finish has succeeded */
    struct gd_model_build *build;
} gd_model;

GD_API gd_status gd_model_load(const char *path, gd_model **out, gd_error *err);
/* name stands in for the file name in messages. */
GD_API gd_status gd_model_load_string(const char *yaml, const char *name, gd_model **out,
                                      gd_error *err);
GD_API void gd_model_free(gd_model *model);

/* Overrides every mesh's coupling level (as `--coupling` does on the command line). The
 * shafts keep all their DOFs: a lower level only couples fewer DOFs through the meshes
 * ([JMSTHelical]'s lateral-torsional model); gd_model_restrict_dofs removes DOFs. */
GD_API void gd_model_set_coupling(gd_model *model, gd_coupling level);
/* Keeps only the active DOFs also in dof_mask (GD_DOF_BIT; `--dofs` on the command
 * line). GD_EINPUT, model unchanged, when none would be left. */
GD_API gd_status gd_model_restrict_dofs(gd_model *model, unsigned dof_mask, gd_error *err);

/* The damping the linear analyses use for a mesh: its constant damping plus the part
 * proportional to stiffness at the mean stiffness (c + c_per_k * k_mean). */
GD_API double gd_mesh_linear_damping(const gd_mesh *mesh);

GD_API int gd_model_find_node(const gd_model *model, const char *name);
GD_API int gd_model_find_shaft(const gd_model *model, const char *name);
GD_API int gd_model_find_mesh(const gd_model *model, const char *name);
/* The idler whose own node is `node`, or -1. */
GD_API int gd_model_idler_of_node(const gd_model *model, int node);
/* The order label of shaft s: "1x <shaft>", or for an idler "1x idler <mesh>[+<mesh>]"
 * named from the meshes it takes part in (docs/rattle.md). */
GD_API void gd_model_shaft_order_label(const gd_model *model, int s, char *buf, int cap);

/* Mesh numbering of the time-integration laws (gd_tr_mesh.mesh): 0 .. nmeshes - 1 the gear
 * meshes, then each planetary set's sun-planet meshes (planets 1..N) and ring-planet meshes.
 * gd_model_mesh_count: that total. gd_model_planetary_mesh: 1 and the set, kind (0 sun,
 * 1 ring) and planet of mesh i when it is a planetary mesh, else 0. gd_model_mesh_name: the
 * mesh's name ("<set>.sun_mesh<n>" for a planetary mesh), "" out of range. */
GD_API int gd_model_mesh_count(const gd_model *model);
GD_API int gd_model_planetary_mesh(const gd_model *model, int i, int *set, int *ring, int *planet);
GD_API const char *gd_model_mesh_name(const gd_model *model, int i);
/* Planet n's mesh phase (mesh periods in [0, 1)) on its sun (ring = 0) or ring mesh: the
 * given phases, else [ParkerLin2004] from the teeth and angles (gd_planet_mesh_phases, the
 * sun turning counterclockwise relative to the carrier when sun_direction >= 0), plus the
 * set's sun_ring_phase on ring meshes; 0 without teeth. */
GD_API double gd_planetary_mesh_phase(const gd_planetary *set, int ring, int n, int sun_direction);

/* Mass, polar and diametral inertia of a shaft with everything on its nodes. */
typedef struct gd_shaft_summary {
    double mass, polar_inertia;
    double length;
    int nelements, nnodes;
} gd_shaft_summary;
GD_API void gd_model_shaft_summary(const gd_model *model, int shaft, gd_shaft_summary *out);

#endif
