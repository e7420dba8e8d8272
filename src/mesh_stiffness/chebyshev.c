/* A smooth function on [a, b] tabulated at Chebyshev-Lobatto points and evaluated by
 * barycentric interpolation (Berrut & Trefethen 2004), so the costly tooth energy
 * integrals are done once per gear pair, not once per slice and angle. The table is
 * refined by doubling until the old interpolant predicts the new nodes to rtol. */
#include <math.h>
#include <stdlib.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static double node(double a, double b, int j, int n)
{
    return a + (b - a) * 0.5 * (1 - cos(GD_MS_PI * j / (n - 1)));
}

int gd_ms_cheb_build(gd_ms_cheb *c, gd_ms_fn f, void *ctx, double a, double b, int n, int nmax,
                     double rtol)
{
    c->x = c->f = NULL;
    c->a = a;
    c->b = b;
    if (n < 3) n = 3;
    c->n = n;
    c->x = malloc((size_t)n * sizeof *c->x);
    c->f = malloc((size_t)n * sizeof *c->f);
    if (!c->x || !c->f) goto oom;
    for (int j = 0; j < n; j++) {
        c->x[j] = node(a, b, j, n);
        c->f[j] = f(c->x[j], ctx);
    }
    while (2 * c->n - 1 <= nmax) {
        int m = 2 * c->n - 1;
        double *x = malloc((size_t)m * sizeof *x), *v = malloc((size_t)m * sizeof *v);
        if (!x || !v) {
            free(x);
            free(v);
            goto oom;
        }
        double maxerr = 0, scale = 0;
        for (int j = 0; j < m; j++) {
            x[j] = node(a, b, j, m);
            if (j % 2 == 0) {
                v[j] = c->f[j / 2];
            } else {
                v[j] = f(x[j], ctx);
                double e = fabs(v[j] - gd_ms_cheb_eval(c, x[j]));
                if (e > maxerr) maxerr = e;
            }
            if (fabs(v[j]) > scale) scale = fabs(v[j]);
        }
        free(c->x);
        free(c->f);
        c->x = x;
        c->f = v;
        c->n = m;
        if (maxerr <= rtol * scale) break;
    }
    return 0;
oom:
    gd_ms_cheb_free(c);
    return -1;
}

double gd_ms_cheb_eval(const gd_ms_cheb *c, double x)
{
    double num = 0, den = 0;
    for (int j = 0; j < c->n; j++) {
        double d = x - c->x[j];
        if (d == 0) return c->f[j];
        double w = (j % 2 ? -1.0 : 1.0) / d;
        if (j == 0 || j == c->n - 1) w *= 0.5;
        num += w * c->f[j];
        den += w;
    }
    return num / den;
}

void gd_ms_cheb_free(gd_ms_cheb *c)
{
    free(c->x);
    free(c->f);
    c->x = c->f = NULL;
    c->n = 0;
}
