/* Rattle metrics of a backlash mesh from its contact-change log (geardyn/rattle.h,
 * docs/rattle.md). The window [t0, t1] is cut into B batches of equal length; each
 * metric is a time average, so its value over the window is the mean of its batch
 * values, and the batch means give its confidence interval: with the batches long
 * against the correlation time of the motion their values are nearly independent and
 * normal, and mean +- t_{B-1, (1+c)/2} s_B / sqrt(B) covers the long-run value with
 * probability c (the batch-means method, e.g. Law & Kelton, Simulation Modeling and
 * Analysis, ch. 9). Student's quantile inverts the regularised incomplete beta function
 * (its continued fraction, Abramowitz & Stegun 26.5.8 and 26.7.1). */
#include <math.h>
#include <string.h>

#include "geardyn/rattle.h"

#define MAX_BATCHES 1000

void gd_rattle_options_init(gd_rattle_options *o)
{
    memset(o, 0, sizeof *o);
    o->batches = 10;
    o->confidence = 0.95;
    o->target = 0.1;
}

/* I_x(a, b) by its continued fraction (modified Lentz), for x < (a + 1) / (a + b + 2). */
static double beta_cf(double a, double b, double x)
{
    const double tiny = 1e-300;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    if (fabs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double f = d;
    for (int m = 1; m <= 300; m++) {
        double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a + m2 - 1.0) * (a + m2));
        d = 1.0 + aa * d;
        c = 1.0 + aa / c;
        d = 1.0 / (fabs(d) < tiny ? tiny : d);
        c = fabs(c) < tiny ? tiny : c;
        f *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + m2 + 1.0));
        d = 1.0 + aa * d;
        c = 1.0 + aa / c;
        d = 1.0 / (fabs(d) < tiny ? tiny : d);
        c = fabs(c) < tiny ? tiny : c;
        double del = d * c;
        f *= del;
        if (fabs(del - 1.0) < 1e-15) break;
    }
    return f;
}

/* The regularised incomplete beta function I_x(a, b). */
static double inc_beta(double a, double b, double x)
{
    if (x <= 0.0) return 0.0;
    if (x >= 1.0) return 1.0;
    double lfront = a * log(x) + b * log1p(-x) - (lgamma(a) + lgamma(b) - lgamma(a + b));
    if (x < (a + 1.0) / (a + b + 2.0)) return exp(lfront) * beta_cf(a, b, x) / a;
    return 1.0 - exp(lfront) * beta_cf(b, a, 1.0 - x) / b;
}

/* P(T <= t), T Student's t with nu degrees of freedom (A & S 26.7.1). */
static double t_cdf(double t, double nu)
{
    double tail = 0.5 * inc_beta(0.5 * nu, 0.5, nu / (nu + t * t));
    return t > 0 ? 1.0 - tail : tail;
}

double gd_student_t_quantile(double p, double dof)
{
    if (!(p > 0.0 && p < 1.0) || !(dof > 0.0) || !isfinite(dof)) return NAN;
    if (p == 0.5) return 0.0;
    double hi = 1.0;
    while (t_cdf(hi, dof) < fmax(p, 1.0 - p) && hi < 1e300)
        hi *= 2.0;
    double lo = -hi;
    for (int it = 0; it < 400 && hi - lo > 1e-13 * (1.0 + fabs(lo + hi)); it++) {
        double mid = 0.5 * (lo + hi);
        if (t_cdf(mid, dof) < p)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

typedef struct batch_acc {
    double t0, len;
    int B;
    double sep[MAX_BATCHES], drive[MAX_BATCHES], coast[MAX_BATCHES], energy[MAX_BATCHES];
} batch_acc;

static int batch_of(const batch_acc *a, double t)
{
    int j = (int)((t - a->t0) / a->len);
    return j < 0 ? 0 : (j >= a->B ? a->B - 1 : j);
}

/* Adds the separated stretch [ta, tb] (within the window) to the batches it spans. */
static void add_separated(batch_acc *a, double ta, double tb)
{
    while (tb > ta) {
        int j = batch_of(a, ta);
        double edge = a->t0 + (j + 1) * a->len;
        if (j < a->B - 1 && edge <= ta) /* ta on an edge that rounding put in batch j */
            edge = a->t0 + (++j + 1) * a->len;
        double end = j == a->B - 1 ? tb : fmin(tb, edge);
        a->sep[j] += end - ta;
        ta = end;
    }
}

static gd_rattle_estimate estimate(const double *x, int B, double scale, double tq)
{
    double mean = 0.0, ss = 0.0;
    for (int j = 0; j < B; j++)
        mean += x[j] * scale;
    mean /= B;
    for (int j = 0; j < B; j++)
        ss += (x[j] * scale - mean) * (x[j] * scale - mean);
    gd_rattle_estimate e = {mean, tq * sqrt(ss / (B - 1)) / sqrt((double)B)};
    return e;
}

static gd_status bad(gd_error *err, const char *field, const char *hint, const char *what)
{
    return gd_error_set(err, GD_EINPUT, "", 0, 0, field, hint, "rattle metrics: %s", what);
}

gd_status gd_rattle_metrics_eval(const gd_rattle_event *ev, int n, const gd_rattle_options *o,
                                 gd_rattle_metrics *out, gd_error *err)
{
    if (!(o->t1 > o->t0) || !isfinite(o->t0) || !isfinite(o->t1))
        return bad(err, "window", "record a longer stretch", "the window needs t1 > t0");
    if (o->batches < 2 || o->batches > MAX_BATCHES)
        return bad(err, "batches", "use 2 .. 1000 batches (10 is usual)",
                   "the batch count is out of range");
    if (!(o->confidence > 0.0 && o->confidence < 1.0))
        return bad(err, "confidence", "e.g. 0.95", "the confidence level must be in (0, 1)");
    if (!(o->mass >= 0.0) || !(o->vmax >= 0.0) || !(o->target >= 0.0))
        return bad(err, "mass", "give the mass, vmax and target as numbers >= 0",
                   "a negative mass, histogram range or target");
    if (o->state0 < -1 || o->state0 > 1)
        return bad(err, "state0", "-1 coast, 0 separated, 1 drive", "unknown contact state");
    for (int i = 0; i < n; i++) {
        if (!isfinite(ev[i].t) || !isfinite(ev[i].velocity) || (i && ev[i].t < ev[i - 1].t))
            return bad(err, "events", "pass one mesh's log in time order",
                       "events out of time order or not finite");
        if (ev[i].from < -1 || ev[i].from > 1 || ev[i].to < -1 || ev[i].to > 1)
            return bad(err, "events", "-1 coast, 0 separated, 1 drive", "unknown contact state");
    }
    memset(out, 0, sizeof *out);
    static const batch_acc zero;
    batch_acc a = zero;
    a.t0 = o->t0;
    a.B = o->batches;
    a.len = (o->t1 - o->t0) / a.B;
    out->duration = o->t1 - o->t0;
    out->batches = a.B;
    out->confidence = o->confidence;
    out->t_quantile = gd_student_t_quantile(0.5 * (1.0 + o->confidence), a.B - 1.0);

    /* the impact speeds' range for the histogram */
    double vmax = o->vmax;
    for (int i = 0; i < n; i++)
        if (ev[i].t >= o->t0 && ev[i].t <= o->t1 && ev[i].from == 0 && ev[i].to != 0)
            out->v_max = fmax(out->v_max, fabs(ev[i].velocity));
    if (vmax == 0.0) vmax = out->v_max > 0 ? out->v_max * (1.0 + 1e-12) : 1.0;
    out->bin_width = vmax / GD_RATTLE_BINS;

    int state = n > 0 ? ev[0].from : o->state0;
    double since = o->t0, sum_v = 0.0, sum_v2 = 0.0;
    for (int i = 0; i < n; i++) {
        const gd_rattle_event *e = &ev[i];
        if (e->t < o->t0) {
            state = e->to;
            continue;
        }
        if (e->t > o->t1) break;
        if (state == 0) add_separated(&a, since, e->t);
        if (e->from == 0 && e->to != 0) { /* an impact */
            double v = fabs(e->velocity);
            int j = batch_of(&a, e->t);
            int bin = (int)(v / out->bin_width);
            if (bin >= GD_RATTLE_BINS) bin = GD_RATTLE_BINS - 1;
            if (e->to > 0) {
                a.drive[j] += 1.0;
                out->drive_impacts++;
                out->hist_drive[bin]++;
            } else {
                a.coast[j] += 1.0;
                out->coast_impacts++;
                out->hist_coast[bin]++;
            }
            a.energy[j] += o->mass > 0 ? 0.5 * o->mass * v * v : v * v;
            sum_v += v;
            sum_v2 += v * v;
        }
        state = e->to;
        since = e->t;
    }
    if (state == 0) add_separated(&a, since, o->t1);
    int ni = out->drive_impacts + out->coast_impacts;
    if (ni) {
        out->v_mean = sum_v / ni;
        out->v_rms = sqrt(sum_v2 / ni);
    }

    double s = 1.0 / a.len, tq = out->t_quantile;
    out->separated = estimate(a.sep, a.B, s, tq);
    out->drive_rate = estimate(a.drive, a.B, s, tq);
    out->coast_rate = estimate(a.coast, a.B, s, tq);
    out->intensity = estimate(a.energy, a.B, s, tq);
    double total[MAX_BATCHES];
    for (int j = 0; j < a.B; j++)
        total[j] = a.drive[j] + a.coast[j];
    gd_rattle_estimate rate = estimate(total, a.B, s, tq);
    const gd_rattle_estimate *check[3] = {&out->separated, &rate, &out->intensity};
    for (int k = 0; k < 3; k++)
        if (check[k]->mean > 0)
            out->precision = fmax(out->precision, check[k]->half_width / check[k]->mean);
    double target = o->target > 0 ? o->target : 0.1;
    out->converged = out->precision <= target;
    out->suggested_duration =
        out->converged ? out->duration
                       : out->duration * (out->precision / target) * (out->precision / target);
    return GD_OK;
}
