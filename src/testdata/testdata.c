/* A set of measured functions read from several files: the file in memory and its
 * form told by its first line. */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "testdata/testdata_impl.h"

static gd_status read_one(const char *path, int skip_other, gd_testdata *td, gd_error *err)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return gd_error_set(err, GD_EIO, path, 0, 0, "", "check the path and its permissions",
                            "cannot open the test-data file");
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        if (cap - len < 65536) {
            size_t nc = cap ? 2 * cap : 1 << 20;
            char *nb = realloc(buf, nc + 1);
            if (!nb) {
                free(buf);
                fclose(fp);
                return gd_error_set(err, GD_ENOMEM, path, 0, 0, "", "", "out of memory");
            }
            buf = nb;
            cap = nc;
        }
        size_t got = fread(buf + len, 1, cap - len, fp);
        len += got;
        if (got == 0) break;
    }
    int bad = ferror(fp);
    fclose(fp);
    if (bad) {
        free(buf);
        return gd_error_set(err, GD_EIO, path, 0, 0, "", "check the file", "read error");
    }
    buf[len] = 0;
    gd_td_text t = {path, buf, len, 0, 0, 0};
    /* the form from the first non-blank line */
    size_t p = 0;
    while (p < len && isspace((unsigned char)buf[p]))
        p++;
    gd_status st;
    if (strncmp(buf + p, "-1", 2) == 0)
        st = gd_td_read_uff(&t, skip_other, td, err);
    else if (strncmp(buf + p, "# geardyn frf", 13) == 0)
        st = gd_td_read_frf_csv(&t, td, err);
    else if (strncmp(buf + p, "# geardyn modes", 15) == 0)
        st = gd_td_read_modes_csv(&t, td, err);
    else
        st = gd_error_set(err, GD_EINPUT, path, 1, 1, "",
                          "a UFF file starts with '    -1'; a CSV with '# geardyn frf' or "
                          "'# geardyn modes' (docs/testing.md)",
                          "not a test-data file geardyn reads");
    free(buf);
    return st;
}

gd_status gd_testdata_read(int nfiles, const char *const *paths, int skip_other_datasets,
                           gd_testdata **out, gd_error *err)
{
    *out = NULL;
    gd_testdata *td = calloc(1, sizeof *td);
    if (!td) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    for (int i = 0; i < nfiles; i++) {
        gd_status st = read_one(paths[i], skip_other_datasets, td, err);
        if (st) {
            gd_testdata_free(td);
            return st;
        }
    }
    *out = td;
    return GD_OK;
}

void gd_testdata_free(gd_testdata *td)
{
    if (!td) return;
    for (int i = 0; i < td->nfunctions; i++) {
        free(td->functions[i].freq_hz);
        free(td->functions[i].re);
        free(td->functions[i].im);
    }
    free(td->functions);
    free(td->mode_hz);
    free(td->mode_zeta);
    free(td->mode_label);
    free(td);
}
