/* Does a periodic orbit attract the transient at the period T? A Poincare probe (issue 33:
 * "every point converged or explained"). An idling gear in rattle often has no periodic
 * orbit at all: its transient never settles, and Newton on the period map from its state
 * then spends monodromy matrices (minutes each through the impacts) on an orbit that is
 * not there. So when a transient has not settled it is carried on over PROBE_PERIODS
 * more periods, and its once-per-period states y_k (the section) are compared with the
 * states p = 1 .. PROBE_PMAX periods earlier, component by component against the
 * section's own spread (as `geardyn transient --periods` compares its Poincare points with
 * each record's range):
 *
 *   d_p(k) = max_i |y_k,i - y_k-p,i| / s_i,   s_i = max_k y_k,i - min_k y_k,i
 *
 * (s_i at least 1e-3 of its block's size: a component that does not move is not
 * compared). A periodic attractor of period p T makes d_p fall towards 0 while the spread
 * keeps the early transient; a motion that no orbit attracts keeps every d_p of order 1.
 * The verdict asks for both: the smallest d_p over the last half above PROBE_FLOOR for
 * every p, and neither decay nor growth (d_1's mean over the last quarter within a factor
 * 2 of its mean over the first: a growing transient leaves an unstable orbit, which
 * Newton finds, as in the parametric resonance of a damped Mathieu pair). Anything else goes on to
 * Newton from the same start as before. The block norm of Newton's residual would not do: on
 * examples/manual_5speed.yaml the driveline's wind-up sets the scale and the idlers' rattle moves
 * the state by 0.004-0.12 of it a period, below any floor. Counted, never timed: the same states
 * and verdict on every run. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/shooting/shooting_impl.h"

/* periods of the probe (about one dense monodromy of a 12-state train, 0.7 (2 N + 1)
 * periods, where the rattle's impacts do not make the monodromy dearer still) */
#define PROBE_PERIODS 24
/* periods compared (period-1 .. period-8 orbits) */
#define PROBE_PMAX 8
/* a return within this fraction of the section's spread in every component */
#define PROBE_FLOOR 5e-2

/* d_p(k) over the section Y with the spreads s */
static double dist(const shoot *sh, const double *Y, const double *s, int k, int p)
{
    const int N = sh->N;
    double d = 0.0;
    for (int i = 0; i < N; i++)
        d = fmax(d, fabs(Y[(size_t)k * N + i] - Y[(size_t)(k - p) * N + i]) / s[i]);
    return d;
}

static double mean_d1(const shoot *sh, const double *Y, const double *s, int a, int b)
{
    double m = 0.0;
    for (int k = a; k < b; k++)
        m += dist(sh, Y, s, k, 1);
    return b > a ? m / (b - a) : NAN;
}

int gd_per_sh_probe(shoot *sh, double *y, const char *from)
{
    const int N = sh->N, n = PROBE_PERIODS;
    /* rattle needs contact: a smooth or time-varying linear train settles, if slowly (the
     * damped Mathieu pair below its parametric resonance turns a complex pair of |mu| near
     * 1, and 24 of its periods neither decay nor return) */
    if (gd_transient_nswitches(sh->p->tr) == 0) return 0;
    double *Y = malloc(((size_t)(n + 1) * N + 2 * (size_t)N) * sizeof *Y);
    if (!Y) {
        snprintf(sh->why, sizeof sh->why, "out of memory");
        return -1;
    }
    double *s = Y + (size_t)(n + 1) * N, *lo = s + N;
    memcpy(Y, y, (size_t)N * sizeof *Y);
    int k, rc = 0;
    for (k = 1; k <= n; k++) {
        if (sh->t_period > 0 && gd_per_sh_over_budget(sh, sh->t_period, "the periodicity probe"))
            break;
        gd_per_sh_tolerances(sh, Y + (size_t)(k - 1) * N);
        if (gd_per_sh_period(sh, Y + (size_t)(k - 1) * N, Y + (size_t)k * N)) {
            rc = -1;
            goto done;
        }
    }
    k--;                  /* the last state integrated */
    if (k < n) goto done; /* the budget cut it: no verdict from a short probe */
    gd_per_sh_scales(sh, Y + (size_t)n * N, lo); /* the block sizes: the spreads' floor */
    for (int i = 0; i < N; i++) {
        double a = INFINITY, b = -INFINITY;
        for (int j = 0; j <= n; j++) {
            a = fmin(a, Y[(size_t)j * N + i]);
            b = fmax(b, Y[(size_t)j * N + i]);
        }
        s[i] = fmax(b - a, 1e-3 * lo[i]);
    }
    double dmin = INFINITY, d1lo = INFINITY, d1hi = 0.0;
    for (int p = 1; p <= PROBE_PMAX; p++)
        for (int j = n / 2; j <= n; j++) {
            const double d = dist(sh, Y, s, j, p);
            dmin = fmin(dmin, d);
            if (p == 1) {
                d1lo = fmin(d1lo, d);
                d1hi = fmax(d1hi, d);
            }
        }
    const double first = mean_d1(sh, Y, s, 1, 1 + n / 4),
                 last = mean_d1(sh, Y, s, n + 1 - n / 4, n + 1);
    /* no verdict: Newton goes on from the start as before (the probe's states are not the
     * better start: on a period-2 attractor the last one lies on it, not near the
     * unstable period-1 orbit Newton is after) */
    if (dmin > PROBE_FLOOR && last >= 0.5 * first && last <= 2.0 * first) {
        memcpy(y, Y + (size_t)n * N, (size_t)N * sizeof *y);
        sh->warm_periods += n;
        /* the evidence first: auto's hand-over keeps the first 110 characters */
        snprintf(sh->why, sizeof sh->why,
                 "no periodic orbit attracts the transient at T = %.4g s: %d periods after %d "
                 "from %.40s, none returns within %.2g of the spread (1-%d T; per period "
                 "%.2g-%.2g, neither decaying nor growing): rattle?",
                 sh->p->T, n, sh->warm_periods - n, from, dmin, PROBE_PMAX, d1lo, d1hi);
        sh->not_periodic = 1;
        rc = 1;
    }
done:
    free(Y);
    return rc;
}
