/* Parameter studies (geardyn/study.h), shared by the module's files:
 *   study_file.c: reading and checking the study file;
 *   cases.c: values of the parameters and the designs (factorial, zip, random, Latin
 *            hypercube);
 *   run.c: one case (overrides, analysis, outputs) and many over OpenMP;
 *   rows.c: the table's lines;
 *   analyses.c: the table of analyses; analysis_<name>.c: one analysis each. */
#ifndef GD_STUDY_IMPL_H
#define GD_STUDY_IMPL_H
#include <stdint.h>

#include "geardyn/mesh_stiffness.h"
#include "geardyn/model_file.h"
#include "geardyn/probe.h"
#include "geardyn/study.h"
#include "geardyn/system.h"
#include "model_file/yaml_doc_impl.h"

/* ---- analyses ---- */

/* A scalar output an analysis offers; indexed outputs are asked for as name[k] (k from
 * 1: mode k, critical speed k, harmonic k) or name[a:b]. */
typedef struct gd_study_output_def {
    const char *name;
    int indexed;
    const char *what; /* for the docs and the hint of an unknown name */
} gd_study_output_def;

/* One requested column: output def index and k (0 when not indexed). */
typedef struct gd_study_request {
    int def;
    int k;
} gd_study_request;

/* What a case hands its analysis: a built system, or a gear pair (gear_pair analyses). */
typedef struct gd_study_input {
    const gd_system *sys;
    const gd_gear_pair_geometry *geom;
    const gd_tvms_options *tvms;
} gd_study_input;

/* An analysis: its options (read from the `analysis:` map), its outputs, and how to run
 * a case. Adding an analysis is one file defining such a constant and one line in
 * analyses.c. */
typedef struct gd_study_runner {
    const char *name;
    int gear_pair;           /* reads the model file's gear pair, not a system */
    const char *const *keys; /* option keys of the `analysis:` map besides `type` */
    /* Reads the options from map (keys already checked) into *opts (malloc'd; freed with
     * free()). */
    gd_status (*options)(gd_yreader *r, const gd_ynode *map, void **opts);
    /* The mesh name of a gear-pair analysis's options (NULL: the first with geometry). */
    const char *(*mesh_name)(const void *opts);
    /* Optional: checks the options against the model as the file gives it (names of
     * meshes and nodes), before any case runs. */
    gd_status (*check)(const gd_system *sys, const void *opts, gd_error *err);
    /* Optional, for the analyses that linearise the model's laws (modal, campbell, frf,
     * unbalance): the one speed the analysis runs at, rad/s (the static equilibrium is
     * solved and checked there, as `geardyn modal` does), or -1 for a sweep (solved at
     * each speed). The case sets the operating point as the CLI does
     * (gd_static_operating_point, docs/bearings.md). NULL: nothing linearised. */
    double (*operating_speed)(const void *opts);
    const gd_study_output_def *outputs;
    int noutputs;
    /* Fills values[i] for each request (NaN where it does not exist). */
    gd_status (*run)(const gd_study_input *in, const void *opts, const gd_study_request *req,
                     int nreq, double *values, gd_error *err);
} gd_study_runner;

extern const gd_study_runner *const gd_study_analysis_table[];
const gd_study_runner *gd_study_find_analysis(const char *name);

extern const gd_study_runner gd_study_modal, gd_study_campbell, gd_study_frf, gd_study_unbalance,
    gd_study_transient, gd_study_mesh_stiffness, gd_study_periodic, gd_study_static,
    gd_study_contact;

/* The largest |re[k] + i im[k]| of n values into *peak and its k (-1, NaN when all are
 * NaN). */
long gd_study_peak(const double *re, const double *im, size_t n, double *peak);
/* k-th of n values (k from 1), NaN past the end. */
double gd_study_kth(const double *v, int n, int k);

/* A sweep option `key: {from: A, to: B, count: N}` (quantities with units, e.g. rpm,
 * Hz) of map; required. */
typedef struct gd_study_sweep {
    double from, to;
    long count;
} gd_study_sweep;
gd_status gd_study_read_sweep(gd_yreader *r, const gd_ynode *map, const char *key,
                              gd_study_sweep *out);
/* The sweep's count evenly spaced values (malloc'd), NULL if out of memory. */
double *gd_study_sweep_values(const gd_study_sweep *sw);
/* A probe text as the CLI writes it, resolved in sys: mesh:NAME, NODE.DOF or
 * node:NODE.DOF (a displacement), torque:NODE (input: NODE.rz). Sets *dof (active DOF,
 * -1 for a mesh) or probe. GD_EINPUT naming what is not there. */
gd_status gd_study_probe(const gd_system *sys, const char *text, gd_probe *probe, int *dof,
                         gd_error *err);

/* ---- the study ---- */

typedef enum gd_study_design {
    GD_DESIGN_FACTORIAL, /* every combination; the first parameter varies slowest */
    GD_DESIGN_ZIP,       /* case i takes value i of every parameter */
    GD_DESIGN_RANDOM,    /* independent uniform samples */
    GD_DESIGN_LHS        /* Latin hypercube: one sample in each of n strata per parameter */
} gd_study_design;

typedef struct gd_study_param {
    char *name, *path;
    char *unit;   /* appended to the value in the override ("" none) */
    double scale; /* the override's value is value * scale */
    int numeric;
    /* values: a list or a range with a count (factorial, zip) */
    size_t nvalues;
    double *values;
    char **texts; /* non-numeric list values, else NULL */
    /* range: from, to, log spacing (sampled designs) */
    double from, to;
    int log;
} gd_study_param;

struct gd_study {
    char *file, *text;
    gd_model_source *src;
    const gd_study_runner *analysis;
    void *opts;
    int op_kind; /* gd_operating_kind of `analysis: {operating_point: static|zero}` */
    gd_study_design design;
    int nparams;
    gd_study_param *params;
    size_t ncases;
    double *samples; /* random / LHS: ncases x nparams, case-major */
    int noutputs;
    gd_study_request *req;
    char **out_names;
};

/* cases.c: values of the ranges, case count, and the sampled designs (seeded). */
gd_status gd_study_make_cases(gd_study *s, uint64_t seed, gd_error *err);
/* Index into param p's values for case c (factorial, zip). */
size_t gd_study_value_index(const gd_study *s, size_t c, int p);

/* run.c: the override "PATH=VALUE" of parameter p in case c. */
void gd_study_assignment(const gd_study *s, size_t c, int p, char *buf, size_t size);

#endif
