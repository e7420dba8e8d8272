/* geardyn: dynamics of geared rotor systems. This header includes every public header;
 * programs may include it alone, or only the headers they use.
 *
 * Layers, each using only the ones before it:
 *   model file  YAML text -> parsed and validated (gd_model_load, gd_model_load_string;
 *               units.h reads quantities such as "3000 rpm")
 *   model       gd_model: typed description of shafts, gears, bearings, loads
 *               (model.h, material.h, laws.h)
 *   system      gd_system: DOF numbering and sparse matrices, built once per model
 *               (system.h, sparse.h, probe.h)
 *   analyses    modal.h, static.h, campbell.h, frf.h, unbalance.h, transient.h, transient_model.h,
 *               mesh_stiffness.h (from gear geometry alone), spectrum.h (of records),
 *               waterfall.h (spectra over a stepped run-up, order cuts)
 *   output      result structures (gd_modal_result, gd_campbell_result, ...); printing,
 *               JSON and CSV are the command-line program's
 *   plots       plot.h: the figure of each result as SVG or self-contained HTML;
 *               report.h: a whole study in one file
 * Errors: every call that can fail returns a gd_status and fills a caller-owned
 * gd_error (error.h).
 *
 * Ownership: every *_free(p) frees what the matching constructor (*_load, *_build,
 * *_create, *_solve, ...) returned; the ones taking a pointer to an object accept NULL
 * (gd_csc_free empties a caller-owned struct instead). Results own their memory. Objects
 * built from others borrow them: a gd_system its gd_model, a gd_transient its
 * gd_system; free in reverse order of construction.
 *
 * Threads: no global mutable state. Distinct objects may be used from different
 * threads at once; a const object (e.g. one gd_system shared by several solves) may be
 * read concurrently. One non-const object must not be used by two threads at once.
 *
 * Version: GD_VERSION_* for the headers, gd_version() for the library linked. */
#ifndef GEARDYN_GEARDYN_H
#define GEARDYN_GEARDYN_H

#include "geardyn/export.h"
#include "geardyn/version.h"

#include "geardyn/error.h"
#include "geardyn/units.h"
#include "geardyn/material.h"
#include "geardyn/law_type.h"
#include "geardyn/laws.h"
#include "geardyn/bearing_geometry.h"
#include "geardyn/reynolds.h"
#include "geardyn/model.h"
#include "geardyn/builder.h"
#include "geardyn/planetary.h"
#include "geardyn/model_file.h"
#include "geardyn/elements.h"
#include "geardyn/system.h"
#include "geardyn/sparse.h"
#include "geardyn/blas.h"
#include "geardyn/mesh_stiffness.h"
#include "geardyn/modal.h"
#include "geardyn/static.h"
#include "geardyn/condense.h"
#include "geardyn/campbell.h"
#include "geardyn/waterfall.h"
#include "geardyn/probe.h"
#include "geardyn/frf.h"
#include "geardyn/unbalance.h"
#include "geardyn/transient.h"
#include "geardyn/transient_model.h"
#include "geardyn/periodic.h"
#include "geardyn/spectrum.h"
#include "geardyn/cycles.h"
#include "geardyn/rattle.h"
#include "geardyn/plot.h"
#include "geardyn/report.h"
#include "geardyn/study.h"
#include "geardyn/testdata.h"
#include "geardyn/ema.h"
#include "geardyn/correlate.h"

#endif
