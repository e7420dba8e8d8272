/* The points of a curve worth drawing at a given resolution (PNG and PDF output). A
 * frequency response of 100 000 points drew a 4 MB polyline and 100 000 markers, which
 * librsvg refuses to parse (issue 38 M8), for a curve 630 pixels wide. The classic
 * min/max decimation of plotted signals: consecutive points falling in the same
 * column of width `cell` pixels form a group, of which the first, the lowest, the highest
 * and the last are kept, in their order. The polyline through the kept points passes
 * within one cell of every point dropped (each lies inside its group's column, between
 * the group's lowest and highest, which the line visits), so at a cell of a quarter
 * pixel the drawing is the same to the eye; at most 4 points per column change are
 * left. Pixel coordinates in, indices out. */
#include <math.h>

#include "plot/plot_impl.h"

int pl_decimate(const double *x, const double *y, int n, double cell, int *keep)
{
    int m = 0;
    int i = 0;
    while (i < n) {
        double col = floor(x[i] / cell);
        int lo = i, hi = i, j = i + 1;
        for (; j < n && floor(x[j] / cell) == col; j++) {
            if (y[j] < y[lo]) lo = j;
            if (y[j] > y[hi]) hi = j;
        }
        int g[4] = {i, lo < hi ? lo : hi, lo < hi ? hi : lo, j - 1};
        for (int k = 0; k < 4; k++)
            if (m == 0 || keep[m - 1] < g[k]) keep[m++] = g[k];
        i = j;
    }
    return m;
}
