/* Output series of the frf and unbalance commands. */
#ifndef GD_SWEEP_OUTPUT_H
#define GD_SWEEP_OUTPUT_H
#include <cjson/cJSON.h>
#include <stdio.h>

typedef struct gd_series {
    char name[200];
    const char *quantity; /* may be NULL */
    double harmonic;      /* > 0: unbalance harmonic order */
    const char *xname;    /* "frequency_rad_s" or "speed_rad_s" */
    int n;
    const double *x, *re, *im;
} gd_series;

cJSON *gd_series_json(const gd_series *s);
/* Rows: name, x, x/2pi, magnitude, phase_deg, real, imag. */
void gd_series_csv(FILE *f, const gd_series *s);
void gd_series_table(FILE *f, const gd_series *s, int ns, const char *xlabel, double xscale);

#endif
