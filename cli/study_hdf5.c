/* results.h5: the study's table as one HDF5 compound dataset `/results`, one record per
 * case (fields: case, the parameters, the outputs, status, message; texts as
 * variable-length strings), with the study file, the analysis, the model and the
 * geardyn version as attributes of the file. HDF5 rather than Parquet: Debian packages
 * the HDF5 C library (libhdf5-dev, the serial build), while Parquet's C++ library
 * (Apache Arrow) is not in Debian; h5py, pandas (via h5py), MATLAB, Julia and R read
 * it. */
#include <hdf5.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/version.h"
#include "study_cli.h"

static int attr_text(hid_t file, hid_t str, const char *name, const char *text)
{
    hid_t sp = H5Screate(H5S_SCALAR);
    hid_t a = H5Acreate2(file, name, str, sp, H5P_DEFAULT, H5P_DEFAULT);
    int bad = a < 0 || H5Awrite(a, str, &text) < 0;
    if (a >= 0) H5Aclose(a);
    H5Sclose(sp);
    return bad ? -1 : 0;
}

int gd_study_write_hdf5(const gd_study *s, const char *path, char *const *lines, char *why,
                        size_t why_size)
{
    size_t n = gd_study_ncases(s), nrows = 0;
    for (size_t c = 0; c < n; c++)
        if (lines[c]) nrows++;
    int np = gd_study_nparams(s), no = gd_study_noutputs(s);
    size_t nfields = 1 + (size_t)np + (size_t)no + 2, rec = 8 * nfields;
    unsigned char *data = calloc(nrows ? nrows : 1, rec);
    char **messages = calloc(nrows ? nrows : 1, sizeof *messages);
    gd_study_row row = {0};
    if (!data || !messages || gd_study_row_init(s, &row, NULL)) {
        free(data);
        free(messages);
        snprintf(why, why_size, "out of memory");
        return -1;
    }
    int rc = 0;
    size_t r = 0;
    for (size_t c = 0; c < n && !rc; c++) {
        if (!lines[c]) continue;
        gd_error err;
        if (gd_study_parse_row(s, lines[c], &row, &err) || !(messages[r] = strdup(row.message))) {
            snprintf(why, why_size, "case %zu: %s", c, err.message);
            rc = -1;
            break;
        }
        unsigned char *p = data + r * rec;
        uint64_t idx = c;
        memcpy(p, &idx, 8);
        for (int k = 0; k < np; k++) {
            char buf[64];
            if (gd_study_param_numeric(s, k)) {
                double v = gd_study_case_value(s, c, k);
                memcpy(p + 8 * (1 + (size_t)k), &v, 8);
            } else {
                const char *t = gd_study_case_text(s, c, k, buf, sizeof buf);
                memcpy(p + 8 * (1 + (size_t)k), &t, sizeof t);
            }
        }
        memcpy(p + 8 * (1 + (size_t)np), row.outputs, 8 * (size_t)no);
        const char *st = gd_study_status_text(row.status);
        memcpy(p + 8 * (nfields - 2), &st, sizeof st);
        memcpy(p + 8 * (nfields - 1), &messages[r], sizeof messages[r]);
        r++;
    }
    gd_study_row_free(&row);
    if (!rc) {
        hid_t str = H5Tcopy(H5T_C_S1);
        H5Tset_size(str, H5T_VARIABLE);
        H5Tset_cset(str, H5T_CSET_UTF8);
        hid_t type = H5Tcreate(H5T_COMPOUND, rec);
        H5Tinsert(type, "case", 0, H5T_NATIVE_UINT64);
        for (int k = 0; k < np; k++)
            H5Tinsert(type, gd_study_param_name(s, k), 8 * (1 + (size_t)k),
                      gd_study_param_numeric(s, k) ? H5T_NATIVE_DOUBLE : str);
        for (int k = 0; k < no; k++)
            H5Tinsert(type, gd_study_output_name(s, k), 8 * (1 + (size_t)np + (size_t)k),
                      H5T_NATIVE_DOUBLE);
        H5Tinsert(type, "status", 8 * (nfields - 2), str);
        H5Tinsert(type, "message", 8 * (nfields - 1), str);
        hsize_t dims[1] = {nrows};
        hid_t file = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
        hid_t space = H5Screate_simple(1, dims, NULL);
        hid_t set = file >= 0 ? H5Dcreate2(file, "results", type, space, H5P_DEFAULT, H5P_DEFAULT,
                                           H5P_DEFAULT)
                              : -1;
        char version[64];
        snprintf(version, sizeof version, "%s", gd_version());
        if (set < 0 || (nrows && H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) ||
            attr_text(file, str, "geardyn_version", version) ||
            attr_text(file, str, "analysis", gd_study_analysis(s)) ||
            attr_text(file, str, "model", gd_study_model_file(s)) ||
            attr_text(file, str, "study_file", gd_study_text(s))) {
            snprintf(why, why_size, "HDF5 could not write %s", path);
            rc = -1;
        }
        if (set >= 0) H5Dclose(set);
        H5Sclose(space);
        if (file >= 0 && H5Fclose(file) < 0) rc = -1;
        H5Tclose(type);
        H5Tclose(str);
    }
    for (size_t i = 0; i < nrows; i++)
        free(messages[i]);
    free(messages);
    free(data);
    return rc;
}
