/* Quadrature for the tooth energy integrals: adaptive Gauss-Kronrod 7/15 (nodes and
 * weights of QUADPACK, Piessens et al. 1983) with interval bisection until the
 * Kronrod-Gauss difference is below the tolerance; and fixed Gauss-Legendre rules
 * (nodes by Newton's method on P_n) so tests can show the convergence. */
#include <float.h>
#include <math.h>

#include "mesh_stiffness/mesh_stiffness_impl.h"

static const double XGK[8] = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.0};
static const double WGK[8] = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
static const double WG[4] = {
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

static double gk15(gd_ms_fn f, void *ctx, double a, double b, double *errest)
{
    double c = 0.5 * (a + b), h = 0.5 * (b - a);
    double fc = f(c, ctx);
    double rk = fc * WGK[7], rg = fc * WG[3];
    for (int j = 0; j < 7; j++) {
        double dx = h * XGK[j];
        double fs = f(c - dx, ctx) + f(c + dx, ctx);
        rk += WGK[j] * fs;
        if (j % 2 == 1) rg += WG[j / 2] * fs;
    }
    *errest = fabs((rk - rg) * h);
    return rk * h;
}

static double adapt(gd_ms_fn f, void *ctx, double a, double b, double whole, double tol, int depth,
                    int *neval)
{
    double el, er;
    double m = 0.5 * (a + b);
    double l = gk15(f, ctx, a, m, &el), r = gk15(f, ctx, m, b, &er);
    *neval += 30;
    /* depth and call budget stop a tolerance that rounding makes unreachable */
    if (el + er <= tol || depth >= 30 || *neval > 60000 || fabs(l + r - whole) <= 0.1 * tol)
        return l + r;
    return adapt(f, ctx, a, m, l, 0.5 * tol, depth + 1, neval) +
           adapt(f, ctx, m, b, r, 0.5 * tol, depth + 1, neval);
}

double gd_ms_integrate(gd_ms_fn f, void *ctx, double a, double b, double rtol, int *neval)
{
    int n = 15;
    double e;
    double whole = gk15(f, ctx, a, b, &e);
    if (rtol < 100 * DBL_EPSILON) rtol = 100 * DBL_EPSILON; /* below this is rounding */
    double tol = rtol * fabs(whole);
    double res = whole;
    if (e > tol) res = adapt(f, ctx, a, b, whole, tol, 1, &n);
    if (neval) *neval += n;
    return res;
}

double gd_ms_gauss_legendre(gd_ms_fn f, void *ctx, double a, double b, int n)
{
    if (n < 1) n = 1;
    if (n > 64) n = 64;
    double c = 0.5 * (a + b), h = 0.5 * (b - a), sum = 0;
    for (int i = 1; i <= (n + 1) / 2; i++) {
        double x = cos(GD_MS_PI * (i - 0.25) / (n + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = x;
            for (int k = 2; k <= n; k++) {
                double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = n * (x * p1 - p0) / (x * x - 1);
            double dx = p1 / dp;
            x -= dx;
            if (fabs(dx) < 1e-16) break;
        }
        double w = 2 / ((1 - x * x) * dp * dp);
        if (2 * i - 1 == n)
            sum += w * f(c, ctx);
        else
            sum += w * (f(c - h * x, ctx) + f(c + h * x, ctx));
    }
    return sum * h;
}
