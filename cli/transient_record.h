/* `geardyn transient --record WHAT`: the record spec parser (docs/transient.md).
 *
 *   NODE.DOF[:disp|vel|angle|speed]     displacement (default), velocity, total angle or
 *                                       total speed of an active DOF
 *   ratio:NODE_A/NODE_B                 total angular speed of A's rz over B's rz
 *   mesh:NAME[:force|state|deflection|stiffness]   (NAME may be '*': every mesh)
 *   sfd:BEARING[:fx|fy|ecc]             damper force on the journal or e/c ('*': all)
 *
 * Items are comma-separated; the option may be repeated. */
#ifndef GD_TRANSIENT_RECORD_H
#define GD_TRANSIENT_RECORD_H
#include "geardyn/transient_model.h"

typedef struct gd_cli_record {
    gd_tr_record rec;
    char name[200]; /* canonical spec, e.g. "mesh:m01:force" (CSV column, JSON name) */
    const char *unit;
} gd_cli_record;

typedef struct gd_cli_records {
    int n, cap;
    gd_cli_record *r;
} gd_cli_records;

/* Parses text (comma-separated items) and appends to recs. Returns 0, or 2 after a
 * usage error on stderr naming the item. */
int gd_cli_parse_records(const char *cmd, const gd_system *sys, const gd_transient_model *tm,
                         const char *text, gd_cli_records *recs);
/* The records used when no --record is given: every nonlinear mesh's force and contact
 * state, every damper's fx, fy; else the total speed of every rz DOF; else every DOF. */
int gd_cli_default_records(const gd_system *sys, const gd_transient_model *tm,
                           gd_cli_records *recs);
void gd_cli_records_free(gd_cli_records *recs);

#endif
