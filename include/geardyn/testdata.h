/* Measured test data: functions of frequency (FRFs, coherences) read from Universal
 * File Format dataset 58 (ASCII) and 58b (binary) ([UFF58]), or from geardyn's FRF CSV
 * form, and measured natural frequencies from a modes CSV (docs/testing.md). Each
 * function keeps its response and reference point (the test's node label and
 * direction), what its ordinate is (receptance, mobility, accelerance, or a
 * dimensionless ratio such as a coherence) and its values in SI units; FRFs convert
 * between receptance, mobility and accelerance (gd_td_convert).
 *
 * Ownership and threads: gd_testdata_read returns a set the caller frees with
 * gd_testdata_free; every array in it is owned by the set. Reading is reentrant (no
 * global state); a set may be read by many threads at once.
 */
#ifndef GEARDYN_TESTDATA_H
#define GEARDYN_TESTDATA_H
#include "geardyn/error.h"
#include "geardyn/export.h"

/* What an ordinate is, per unit force (FRFs) or dimensionless. */
typedef enum gd_td_quantity {
    GD_TD_RECEPTANCE,  /* m/N (rad/(N m) for rotations) */
    GD_TD_MOBILITY,    /* m/s/N */
    GD_TD_ACCELERANCE, /* m/s^2/N */
    GD_TD_RATIO        /* dimensionless: coherence, transmissibility */
} gd_td_quantity;
GD_API extern const char *const gd_td_quantity_names[4];

/* UFF function types of record 6, field 1 (the ones geardyn names). */
enum { GD_UFF_FRF = 4, GD_UFF_COHERENCE = 6 };

typedef struct gd_td_function {
    char name[81];     /* ID line 1 (CSV: the file's name line) */
    int function_type; /* UFF record 6 field 1: 4 FRF, 6 coherence, ... */
    int response_node; /* the test's point labels */
    int response_dir;  /* UFF direction code: +-1 x, +-2 y, +-3 z, +-4..6 rx..rz; 0 scalar */
    int reference_node;
    int reference_dir;
    gd_td_quantity quantity;
    char units[48];  /* the file's ordinate units as written, "m/s^2/N", "g/N" */
    double to_si;    /* factor the file's values were multiplied by */
    int n;           /* spectral lines */
    double *freq_hz; /* n, strictly increasing, >= 0 */
    double *re, *im; /* n, SI; im all 0 for real data */
    int line;        /* line of the dataset in its file (binary data: its header) */
    char file[256];  /* the file it came from */
} gd_td_function;

typedef struct gd_testdata {
    int nfunctions;
    gd_td_function *functions;
    /* measured natural frequencies (a modes CSV): nmodes of them */
    int nmodes;
    double *mode_hz;   /* nmodes */
    double *mode_zeta; /* nmodes, NAN when not given */
    char (*mode_label)[48];
} gd_testdata;

/* Reads the files (UFF 58/58b, FRF CSV or modes CSV, told apart by their first line)
 * into one set. Errors name the file, line and field: a file cut short, a dataset type
 * other than 58 (other datasets of a UFF file are skipped only when
 * skip_other_datasets is set), units that are not a displacement, velocity or
 * acceleration over a force, a frequency axis that does not increase. */
GD_API gd_status gd_testdata_read(int nfiles, const char *const *paths, int skip_other_datasets,
                                  gd_testdata **out, gd_error *err);
GD_API void gd_testdata_free(gd_testdata *td);

/* Converts an FRF in place to quantity `to` (receptance, mobility or accelerance):
 * H_x = H_v / (i w) = -H_a / w^2. A line at 0 Hz becomes NAN where the conversion
 * divides by w. GD_EINPUT for a ratio or a ratio target. */
GD_API gd_status gd_td_convert(gd_td_function *f, gd_td_quantity to, gd_error *err);

/* The SI factor and kind of an ordinate unit written "NUM/DEN" ("m/s^2/N", "g/N",
 * "mm/N", "in/s/lbf"); GD_EINPUT when it is not length, velocity or acceleration over
 * force. */
GD_API gd_status gd_td_units(const char *text, gd_td_quantity *q, double *to_si, gd_error *err);

/* "+y", "-rx", "s" for a UFF direction code. */
GD_API const char *gd_td_dir_name(int dir);

#endif
