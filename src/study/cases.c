/* The cases of a study: the values of each parameter and how they combine.
 *   factorial: every combination, case c = sum_p i_p * prod_{q > p} n_q (the first
 *              parameter varies slowest, as nested loops would);
 *   zip:       case c takes value c of every parameter;
 *   random:    independent uniform samples in [from, to] (log: uniform in the logs);
 *   latin-hypercube: per parameter, the n samples fall one in each of n equal strata,
 *              in a random order (McKay, Beckman & Conover 1979).
 * The samples come from SplitMix64 (Steele, Lea & Flood 2014) seeded by `seed:`, drawn
 * in a fixed order at load time, so every rank, shard and thread count sees the same
 * cases. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "study/study_impl.h"

/* SplitMix64: the state advances by the golden-ratio increment and is mixed (Steele et
 * al. 2014, Fig. 3). */
static uint64_t next64(uint64_t *state)
{
    uint64_t z = (*state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1) with 53 random bits. */
static double uniform01(uint64_t *state)
{
    return (double)(next64(state) >> 11) * 0x1.0p-53;
}

/* u in [0, 1] mapped onto the parameter's range (log: geometric). */
static double at(const gd_study_param *p, double u)
{
    if (p->log) return exp(log(p->from) + u * (log(p->to) - log(p->from)));
    return p->from + u * (p->to - p->from);
}

static gd_status range_values(gd_study_param *p, gd_error *err)
{
    if (p->values) return GD_OK; /* a list */
    p->values = malloc(p->nvalues * sizeof *p->values);
    if (!p->values) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    for (size_t i = 0; i < p->nvalues; i++)
        p->values[i] = p->nvalues == 1 ? p->from : at(p, (double)i / (double)(p->nvalues - 1));
    /* the ends exactly as written */
    p->values[0] = p->from;
    if (p->nvalues > 1) p->values[p->nvalues - 1] = p->to;
    return GD_OK;
}

static gd_status sample(gd_study *s, uint64_t seed, gd_error *err)
{
    size_t n = s->ncases;
    s->samples = malloc(n * (size_t)s->nparams * sizeof *s->samples);
    size_t *perm = s->design == GD_DESIGN_LHS ? malloc(n * sizeof *perm) : NULL;
    if (!s->samples || (s->design == GD_DESIGN_LHS && !perm)) {
        free(perm);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    uint64_t state = seed;
    for (int p = 0; p < s->nparams; p++) {
        if (perm) { /* Fisher-Yates shuffle of the strata */
            for (size_t i = 0; i < n; i++)
                perm[i] = i;
            for (size_t i = n; i > 1; i--) {
                size_t j = (size_t)(next64(&state) % i);
                size_t t = perm[i - 1];
                perm[i - 1] = perm[j];
                perm[j] = t;
            }
        }
        for (size_t c = 0; c < n; c++) {
            double u = uniform01(&state);
            if (perm) u = ((double)perm[c] + u) / (double)n;
            s->samples[c * (size_t)s->nparams + (size_t)p] = at(&s->params[p], u);
        }
    }
    free(perm);
    return GD_OK;
}

gd_status gd_study_make_cases(gd_study *s, uint64_t seed, gd_error *err)
{
    if (s->design == GD_DESIGN_RANDOM || s->design == GD_DESIGN_LHS) return sample(s, seed, err);
    size_t n = 1;
    for (int p = 0; p < s->nparams; p++) {
        if (range_values(&s->params[p], err)) return GD_ENOMEM;
        if (s->design == GD_DESIGN_ZIP) {
            n = s->params[p].nvalues;
        } else {
            if (n > ((size_t)1 << 40) / s->params[p].nvalues)
                return gd_error_set(err, GD_EINPUT, s->file, 0, 0, "parameters",
                                    "use fewer values, or a random or Latin-hypercube design",
                                    "more than 2^40 cases");
            n *= s->params[p].nvalues;
        }
    }
    s->ncases = n;
    return GD_OK;
}

size_t gd_study_value_index(const gd_study *s, size_t c, int p)
{
    if (s->design == GD_DESIGN_ZIP) return c;
    for (int q = s->nparams - 1; q > p; q--)
        c /= s->params[q].nvalues;
    return c % s->params[p].nvalues;
}

double gd_study_case_value(const gd_study *s, size_t c, int p)
{
    if (s->samples) return s->samples[c * (size_t)s->nparams + (size_t)p];
    return s->params[p].values[gd_study_value_index(s, c, p)];
}

/* A case's value of parameter p as text: the assignment "path=value unit" (the --set
 * form) and the bare value (a table cell). */
void gd_study_assignment(const gd_study *s, size_t c, int p, char *buf, size_t size)
{
    const gd_study_param *pa = &s->params[p];
    if (!pa->numeric) {
        snprintf(buf, size, "%s=%s", pa->path, pa->texts[gd_study_value_index(s, c, p)]);
        return;
    }
    snprintf(buf, size, "%s=%.17g%s%s", pa->path, gd_study_case_value(s, c, p) * pa->scale,
             pa->unit[0] ? " " : "", pa->unit);
}

const char *gd_study_case_text(const gd_study *s, size_t c, int p, char *buf, size_t size)
{
    const gd_study_param *pa = &s->params[p];
    if (!pa->numeric) return pa->texts[gd_study_value_index(s, c, p)];
    snprintf(buf, size, "%.17g", gd_study_case_value(s, c, p));
    return buf;
}
