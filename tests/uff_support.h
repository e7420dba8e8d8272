/* Synthetic measurements with a known truth, and a Universal File Format dataset 58 /
 * 58b writer that follows the published dataset description field by field ([UFF58]:
 * records 1-11 with their Fortran formats, record 12 as the data type's case, 58b's
 * identifier line Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12) and the same values as
 * IEEE bytes in the stated byte order). Written from the description, not from the
 * project's reader. Header-only (static inline). */
#ifndef GD_TEST_UFF_SUPPORT_H
#define GD_TEST_UFF_SUPPORT_H
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/geardyn.h"

typedef struct uff_frf {
    const char *id1; /* ID line 1 */
    int rsp_node, rsp_dir, ref_node, ref_dir;
    int num_type;                      /* record 9 specific data type: 8, 11, 12 */
    const char *num_units, *den_units; /* records 9, 10 units labels ("" for none) */
    int n;
    double f0, df; /* even abscissa, Hz */
    const double *re, *im;
} uff_frf;

/* Writes one dataset. binary: 0 ASCII, 1 58b little endian, 2 58b big endian.
 * dtype: record 7's ordinate data type, 5 (complex single) or 6 (complex double). */
static inline void uff_write58(FILE *fp, const uff_frf *h, int binary, int dtype)
{
    int dbl = dtype == 6, size = dbl ? 8 : 4;
    long nbytes = (long)h->n * 2 * size;
    fprintf(fp, "%6d\n", -1);
    if (binary)
        fprintf(fp, "%6d%c%6d%6d%12d%12ld%6d%6d%12d%12d\n", 58, 'b', binary == 1 ? 1 : 2, 2, 11,
                nbytes, 0, 0, 0, 0);
    else
        fprintf(fp, "%6d\n", 58);
    /* records 1-5: Format(80A1) */
    fprintf(fp, "%-80.80s\n", h->id1);
    fprintf(fp, "%-80.80s\n", "NONE");
    fprintf(fp, "%-80.80s\n", "02-Dec-26 01:00:00");
    fprintf(fp, "%-80.80s\n", "NONE");
    fprintf(fp, "%-80.80s\n", "NONE");
    /* record 6: Format(2(I5,I10),2(1X,10A1,I10,I4)) */
    fprintf(fp, "%5d%10d%5d%10d %-10.10s%10d%4d %-10.10s%10d%4d\n", 4, 1, 1, 0, "NONE", h->rsp_node,
            h->rsp_dir, "NONE", h->ref_node, h->ref_dir);
    /* record 7: Format(3I10,3E13.5) */
    fprintf(fp, "%10d%10d%10d%13.5E%13.5E%13.5E\n", dtype, h->n, 1, h->f0, h->df, 0.0);
    /* records 8-11: Format(I10,3I5,2(1X,20A1)) */
    fprintf(fp, "%10d%5d%5d%5d %-20.20s %-20.20s\n", 18, 0, 0, 0, "Frequency", "Hz");
    fprintf(fp, "%10d%5d%5d%5d %-20.20s %-20.20s\n", h->num_type, 1, 0, 0, "Response",
            h->num_units);
    fprintf(fp, "%10d%5d%5d%5d %-20.20s %-20.20s\n", 13, 0, 1, 0, "Force", h->den_units);
    fprintf(fp, "%10d%5d%5d%5d %-20.20s %-20.20s\n", 0, 0, 0, 0, "NONE", "NONE");
    if (!binary) {
        /* record 12, case 7 (complex double even): Format(4E20.12); case 3 (complex
         * single even): Format(6E13.5) */
        int per = dbl ? 4 : 6, k = 0;
        for (int i = 0; i < h->n; i++)
            for (int c = 0; c < 2; c++) {
                double v = c ? h->im[i] : h->re[i];
                fprintf(fp, dbl ? "%20.12E" : "%13.5E", v);
                if (++k % per == 0) fputc('\n', fp);
            }
        if (k % per) fputc('\n', fp);
    } else {
        for (int i = 0; i < h->n; i++)
            for (int c = 0; c < 2; c++) {
                double v = c ? h->im[i] : h->re[i];
                unsigned char b[8];
                if (dbl) {
                    uint64_t u;
                    memcpy(&u, &v, 8);
                    for (int j = 0; j < 8; j++)
                        b[binary == 1 ? j : 7 - j] = (unsigned char)(u >> (8 * j));
                } else {
                    float fv = (float)v;
                    uint32_t u;
                    memcpy(&u, &fv, 4);
                    for (int j = 0; j < 4; j++)
                        b[binary == 1 ? j : 3 - j] = (unsigned char)(u >> (8 * j));
                }
                fwrite(b, 1, (size_t)size, fp);
            }
        /* the closing -1 immediately follows the binary data */
    }
    fprintf(fp, "%6d\n", -1);
}

/* A seeded normal deviate (xorshift64* + Box-Muller). */
static inline double synth_normal(uint64_t *s)
{
    double u[2];
    for (int k = 0; k < 2; k++) {
        *s ^= *s >> 12;
        *s ^= *s << 25;
        *s ^= *s >> 27;
        u[k] = ((double)((*s * 2685821657736338717ULL) >> 11) + 0.5) / 9007199254740992.0;
    }
    return sqrt(-2 * log(u[0])) * cos(2 * M_PI * u[1]);
}

/* The truth: the rig of examples/rig2018.yaml in its vertical plane and torsion
 * (dofs y, rx, rz) with every bearing stiffer by `kfac`, its undamped modes mass-
 * normalised, modal damping from 1 % (lowest mode) to 3 % (highest below fmax), and
 * accelerances at nresp y DOFs (spread over both shafts) to a force at y of the
 * reference, with relative complex noise `noise` (seeded). */
typedef struct synth {
    int nresp, ref_dof, resp_dof[16], resp_node[16];
    int n;
    double f0, df, fmax;
    double *re, *im; /* nresp x n */
    int nmodes;      /* elastic modes below fmax */
    double hz[64], zeta[64];
    int visible[64]; /* its peak in some FRF is above 1 % of the largest mode's peak */
    double peak[64];
    double shape[64][16]; /* mass-normalised shape at the response DOFs */
} synth;

static inline int synth_make(synth *sy, double kfac, double noise, int nresp, int n, double df,
                             uint64_t seed)
{
    memset(sy, 0, sizeof *sy);
    char set1[64], set2[] = "dofs=[y, rx, rz]";
    snprintf(set1, sizeof set1, "bearings.*.k=%.17g", 1e8 * kfac);
    const char *sets[2] = {set1, set2};
    gd_load_options lo = {2, sets};
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_modal_result *r = NULL;
    gd_error err;
    if (gd_model_load_opts("examples/rig2018.yaml", &lo, &m, &err)) return 0;
    if (gd_system_build(m, &s, &err)) return 0;
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.kind = GD_MODAL_UNDAMPED;
    mo.method = GD_EIG_DENSE;
    if (gd_modal_solve(s, &mo, &r, &err)) return 0;
    int nd = s->ndof;
    double *M = calloc((size_t)nd * nd, sizeof *M);
    gd_system_dense(s, 0, M, NULL, NULL);
    /* response DOFs: y DOFs spread evenly over the list of y DOFs */
    int ny = 0, ydof[512];
    for (int i = 0; i < nd && ny < 512; i++)
        if (s->dof_type[i] == GD_Y) ydof[ny++] = i;
    sy->nresp = nresp;
    for (int j = 0; j < nresp; j++) {
        sy->resp_dof[j] = ydof[1 + (int)((double)j * (ny - 2) / (nresp - 1) + 0.5) % (ny - 1)];
        sy->resp_node[j] = s->dof_node[sy->resp_dof[j]];
    }
    sy->ref_dof = sy->resp_dof[1];
    sy->n = n;
    sy->df = df;
    sy->f0 = 0;
    sy->fmax = (n - 1) * df;
    /* mass-normalised elastic modes */
    int ne = 0, idx[256];
    double scale[256];
    for (int k = 0; k < r->nmodes && ne < 256; k++) {
        if (r->modes[k].rigid_body) continue;
        const double *p = r->shape_re + (size_t)k * nd;
        double mm = 0;
        for (int i = 0; i < nd; i++)
            for (int j = 0; j < nd; j++)
                mm += p[i] * M[i + j * nd] * p[j];
        idx[ne] = k;
        scale[ne++] = 1 / sqrt(mm);
    }
    int nb = 0;
    for (int e = 0; e < ne; e++)
        if (r->modes[idx[e]].frequency_hz < sy->fmax) nb++;
    sy->re = calloc((size_t)nresp * n, sizeof(double));
    sy->im = calloc((size_t)nresp * n, sizeof(double));
    uint64_t st = seed ? seed : 1;
    for (int e = 0; e < ne; e++) {
        const double *p = r->shape_re + (size_t)idx[e] * nd;
        double wr = r->modes[idx[e]].omega_n,
               z = e < nb && nb > 1 ? 0.01 + 0.02 * e / (nb - 1) : 0.02;
        if (e < nb && e < 64) {
            sy->hz[e] = r->modes[idx[e]].frequency_hz;
            sy->zeta[e] = z;
            for (int j = 0; j < nresp; j++)
                sy->shape[e][j] = p[sy->resp_dof[j]] * scale[e];
        }
        double pr = p[sy->ref_dof] * scale[e];
        for (int j = 0; j < nresp; j++) {
            double a = p[sy->resp_dof[j]] * scale[e] * pr;
            /* the mode's accelerance peak at w = wr: |a| / (2 z) */
            if (e < 64) sy->peak[e] = fmax(sy->peak[e], fabs(a) / (2 * z));
            for (int k = 0; k < n; k++) {
                double w = 2 * M_PI * k * df;
                /* accelerance -w^2 a / (wr^2 - w^2 + 2 i z wr w) */
                double dr = wr * wr - w * w, di = 2 * z * wr * w, d2 = dr * dr + di * di;
                sy->re[(size_t)j * n + k] += -w * w * a * dr / d2;
                sy->im[(size_t)j * n + k] += -w * w * a * (-di) / d2;
            }
        }
    }
    sy->nmodes = nb < 64 ? nb : 64;
    double pmax = 0;
    for (int e = 0; e < sy->nmodes; e++)
        pmax = fmax(pmax, sy->peak[e]);
    for (int e = 0; e < sy->nmodes; e++)
        sy->visible[e] = sy->peak[e] >= 0.01 * pmax;
    for (size_t k = 0; k < (size_t)nresp * n; k++) {
        double mag = hypot(sy->re[k], sy->im[k]);
        sy->re[k] += noise * mag * synth_normal(&st) / sqrt(2.0);
        sy->im[k] += noise * mag * synth_normal(&st) / sqrt(2.0);
    }
    free(M);
    gd_modal_free(r);
    gd_system_free(s);
    gd_model_free(m);
    return 1;
}

static inline void synth_free(synth *sy)
{
    free(sy->re);
    free(sy->im);
}

/* Writes the synthetic FRFs as one UFF file: each point labelled by its model node's
 * number (1-based, geardyn's default without a test setup); binary and dtype as
 * uff_write58. */
static inline int synth_write_uff(const synth *sy, const char *path, int binary, int dtype)
{
    FILE *fp = fopen(path, "wb");
    if (!fp) return 0;
    for (int j = 0; j < sy->nresp; j++) {
        char id[64];
        int rn = sy->resp_node[j] + 1, fn = sy->resp_node[1] + 1;
        snprintf(id, sizeof id, "H y%dy%d", rn, fn);
        uff_frf h = {id,
                     rn,
                     2,
                     fn,
                     2,
                     12,
                     "m/s^2",
                     "N",
                     sy->n,
                     sy->f0,
                     sy->df,
                     sy->re + (size_t)j * sy->n,
                     sy->im + (size_t)j * sy->n};
        uff_write58(fp, &h, binary, dtype);
    }
    fclose(fp);
    return 1;
}

#endif
