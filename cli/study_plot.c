/* `geardyn study --plot FILE` (docs/studies.md): the finished table DIR/results.csv read
 * back and drawn as gd_plot_lines, each output over the first parameter (numeric), one
 * curve per combination of the other parameters' values. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "study_cli.h"

#define MAX_FAM 64

int gd_cli_study_plot(const gd_study *s, const char *dir, const char *path)
{
    gd_error err;
    gd_error_clear(&err);
    int np = gd_study_nparams(s), no = gd_study_noutputs(s);
    size_t nc = gd_study_ncases(s);
    if (np < 1 || !gd_study_param_numeric(s, 0) || no < 1) {
        fprintf(stderr, "geardyn: error: --plot: the first parameter must be numeric and the "
                        "study must have outputs\n");
        return GD_EXIT_INPUT;
    }
    char file[1200];
    snprintf(file, sizeof file, "%s/results.csv", dir);
    FILE *f = fopen(file, "r");
    if (!f) {
        fprintf(stderr, "geardyn: error: --plot: cannot read %s\n", file);
        return GD_EXIT_FAIL;
    }
    /* x: the first parameter's distinct values; families: the others' texts */
    double *x = malloc(nc * sizeof *x), *y = NULL;
    int *xi = malloc(nc * sizeof *xi), *fi = malloc(nc * sizeof *fi), nx = 0, nf = 0;
    char(*fam)[256] = calloc(MAX_FAM, sizeof *fam);
    const char *fams[MAX_FAM];
    int rc = GD_EXIT_FAIL;
    gd_study_row row;
    int have_row = 0;
    if (!x || !xi || !fi || !fam) goto done;
    for (size_t c = 0; c < nc; c++) {
        double v = gd_study_case_value(s, c, 0);
        int k = 0;
        while (k < nx && x[k] != v)
            k++;
        if (k == nx) x[nx++] = v;
        xi[c] = k;
        char label[256] = "", buf[128];
        for (int p = 1; p < np; p++) {
            size_t l = strlen(label);
            snprintf(label + l, sizeof label - l, "%s%s=%s", p > 1 ? ", " : "",
                     gd_study_param_name(s, p), gd_study_case_text(s, c, p, buf, sizeof buf));
        }
        int j = 0;
        while (j < nf && strcmp(fam[j], label))
            j++;
        if (j == nf) {
            if (nf == MAX_FAM) {
                fprintf(stderr, "geardyn: error: --plot: more than %d curves\n", MAX_FAM);
                rc = GD_EXIT_INPUT;
                goto done;
            }
            snprintf(fam[nf], sizeof fam[nf], "%s", label[0] ? label : "all cases");
            fams[nf] = fam[nf];
            nf++;
        }
        fi[c] = j;
    }
    /* x in increasing order for the curves */
    for (int a = 1; a < nx; a++)
        for (int b = a; b > 0 && x[b - 1] > x[b]; b--) {
            double t = x[b];
            x[b] = x[b - 1];
            x[b - 1] = t;
            for (size_t c = 0; c < nc; c++)
                xi[c] = xi[c] == b ? b - 1 : (xi[c] == b - 1 ? b : xi[c]);
        }
    y = malloc((size_t)no * nf * nx * sizeof *y);
    if (!y || gd_study_row_init(s, &row, &err)) goto done;
    have_row = 1;
    for (size_t k = 0; k < (size_t)no * nf * nx; k++)
        y[k] = NAN;
    char line[65536];
    if (!fgets(line, sizeof line, f)) goto done; /* the header */
    while (fgets(line, sizeof line, f)) {
        if (gd_study_parse_row(s, line, &row, &err) || row.index >= nc || row.status) continue;
        for (int o = 0; o < no; o++)
            y[((size_t)o * nf + fi[row.index]) * nx + xi[row.index]] = row.outputs[o];
    }
    const char **outs = malloc((size_t)no * sizeof *outs);
    if (!outs) goto done;
    for (int o = 0; o < no; o++)
        outs[o] = gd_study_output_name(s, o);
    gd_plot *p = NULL;
    gd_status st = gd_plot_lines("geardyn study", gd_study_param_name(s, 0), nx, x, nf, fams, no,
                                 outs, y, &p, &err);
    free(outs);
    rc = gd_cli_plot_finish(st, p, &err, path);
done:
    if (have_row) gd_study_row_free(&row);
    fclose(f);
    free(x);
    free(xi);
    free(fi);
    free(y);
    free(fam);
    return rc;
}
