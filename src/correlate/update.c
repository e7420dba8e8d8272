/* Model updating to measured natural frequencies ([Friswell1995] Ch. 7, sensitivity
 * methods): parameters p_k of the model file (--set paths) scaled by their starting
 * values, theta_k = p_k / p0_k, within bounds; residuals r_i = (f_model - f_test) /
 * f_test of the paired modes (pairing.c, redone at every evaluation); bounded
 * Levenberg-Marquardt: (J^T J + mu diag(J^T J)) d = -J^T r, the step projected on the
 * box, mu lowered on success and raised on failure.
 * The Jacobian from the eigenvalue derivatives ([FoxKapoor1968]), undamped and
 * mass-normalised: d lambda_j / dp = phi_j^T (dK/dp - lambda_j dM/dp) phi_j,
 * df_j / dp = (d lambda_j / dp) / (8 pi^2 f_j), with dK/dp and dM/dp a one-sided
 * difference of the assembled matrices (exact for a parameter the matrices are linear
 * in: a bearing or mesh stiffness); not a difference of eigenvalues, which fd_check
 * computes beside it as the check. */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "correlate/correlate_impl.h"

typedef struct ctx {
    const gd_model_source *src;
    const gd_measured_modes *mm;
    const gd_update_options *opt;
    int np, nt;
    double *p0;
} ctx;

void gd_update_options_init(gd_update_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->max_iter = 40;
    opt->tol = 1e-8;
    opt->step = 1e-6;
}

void gd_update_free(gd_update_result *r)
{
    if (!r) return;
    free(r->initial), free(r->value), free(r->sigma), free(r->sens), free(r->sens_fd);
    gd_corr_table_free(r->before);
    gd_corr_table_free(r->after);
    free(r);
}

/* The model and its system at parameter values p (SI). */
static gd_status build_at(const ctx *c, const double *p, gd_model **m, gd_system **s, gd_error *err)
{
    *m = NULL;
    *s = NULL;
    int nk = 0;
    for (int k = 0; k < c->np; k++)
        for (const char *q = c->opt->params[k].key; q; q = strchr(q + 1, ','))
            nk++;
    int ns = c->opt->load.nset + nk;
    char **texts = calloc((size_t)ns + 1, sizeof *texts);
    if (!texts) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    int i = 0;
    for (; i < c->opt->load.nset; i++)
        texts[i] = (char *)c->opt->load.set[i];
    gd_status st = GD_OK;
    for (int k = 0; k < c->np && !st; k++) {
        const char *q = c->opt->params[k].key;
        while (q) {
            const char *e = strchr(q, ',');
            size_t len = e ? (size_t)(e - q) : strlen(q);
            char *a = malloc(len + 40);
            if (!a) {
                st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
                break;
            }
            snprintf(a, len + 40, "%.*s=%.17g", (int)len, q, p[k]);
            texts[i++] = a;
            q = e ? e + 1 : NULL;
        }
    }
    if (!st) {
        gd_load_options lo = {ns, (const char *const *)texts};
        st = gd_model_source_model(c->src, &lo, m, err);
        if (!st) st = gd_system_build(*m, s, err);
    }
    for (int j = c->opt->load.nset; j < ns; j++)
        free(texts[j]);
    free(texts);
    if (st) {
        gd_system_free(*s);
        gd_model_free(*m);
        *m = NULL;
        *s = NULL;
    }
    return st;
}

/* Modes and the pairing at p; r (nt) the relative residuals when not NULL. */
static gd_status eval(const ctx *c, const double *p, gd_corr_modes *md, gd_corr_table **t,
                      double *r, gd_error *err)
{
    gd_model *m;
    gd_system *s;
    gd_status st = build_at(c, p, &m, &s, err);
    if (st) return st;
    st = gd_corr_model_modes(s, md, err);
    if (!st) {
        st = gd_corr_pair_modes(md, c->mm, t, err);
        if (st) gd_corr_modes_free(md);
    }
    gd_system_free(s);
    gd_model_free(m);
    if (st || !r) return st;
    for (int i = 0; i < c->nt; i++)
        r[i] = ((*t)->pairs[i].f_model - (*t)->pairs[i].f_test) / (*t)->pairs[i].f_test;
    return GD_OK;
}

/* J (nt x np, row-major) of the residuals in theta at p, by the eigenvalue
 * derivatives; sens (may be NULL) gets df/dp in Hz per SI unit. */
static gd_status jacobian(const ctx *c, const double *p, const gd_corr_modes *md,
                          const gd_corr_table *t, double *J, double *sens, gd_error *err)
{
    gd_model *m0, *m1;
    gd_system *s0, *s1;
    gd_status st = build_at(c, p, &m0, &s0, err);
    if (st) return st;
    int n = s0->ndof;
    double *M0 = malloc((size_t)n * n * sizeof(double)),
           *K0 = malloc((size_t)n * n * sizeof(double));
    double *M1 = malloc((size_t)n * n * sizeof(double)),
           *K1 = malloc((size_t)n * n * sizeof(double));
    double *q = malloc((size_t)c->np * sizeof(double));
    if (!M0 || !K0 || !M1 || !K1 || !q)
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    if (!st) gd_system_dense(s0, 0, M0, NULL, K0);
    for (int k = 0; !st && k < c->np; k++) {
        memcpy(q, p, (size_t)c->np * sizeof *q);
        double h = c->opt->step * fabs(p[k]);
        q[k] = p[k] + h;
        st = build_at(c, q, &m1, &s1, err);
        if (st) break;
        if (s1->ndof != n) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, c->opt->params[k].key,
                              "update values, not the model's structure",
                              "changing '%s' changes the number of DOFs", c->opt->params[k].key);
        } else {
            gd_system_dense(s1, 0, M1, NULL, K1);
            for (size_t e = 0; e < (size_t)n * n; e++) {
                K1[e] = (K1[e] - K0[e]) / h;
                M1[e] = (M1[e] - M0[e]) / h;
            }
            for (int i = 0; i < c->nt; i++) {
                int j = t->pairs[i].model;
                const double *phi = md->phi + (size_t)j * n;
                double dk = 0, dm = 0;
                for (int b = 0; b < n; b++) {
                    double kb = 0, mb = 0;
                    for (int a = 0; a < n; a++) {
                        kb += K1[a + (size_t)b * n] * phi[a];
                        mb += M1[a + (size_t)b * n] * phi[a];
                    }
                    dk += kb * phi[b];
                    dm += mb * phi[b];
                }
                double dl = dk - md->lambda[j] * dm, f = gd_corr_hz(md, j);
                double dfdp = dl / (8 * M_PI * M_PI * f);
                if (sens) sens[i * c->np + k] = dfdp;
                J[i * c->np + k] = dfdp * c->p0[k] / t->pairs[i].f_test;
            }
        }
        gd_system_free(s1);
        gd_model_free(m1);
    }
    free(M0), free(K0), free(M1), free(K1), free(q);
    gd_system_free(s0);
    gd_model_free(m0);
    return st;
}

/* Solves the np x np system A x = b (A symmetric positive definite, or LU). */
static int solve(int np, double *A, double *b)
{
    lapack_int piv[64];
    if (np > 64) return -1;
    return (int)LAPACKE_dgesv(LAPACK_ROW_MAJOR, np, 1, A, np, piv, b, 1);
}

static double sumsq(int n, const double *r)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += r[i] * r[i];
    return s;
}

gd_status gd_model_update(const gd_model_source *src, const gd_measured_modes *mm,
                          const gd_update_options *opt, gd_update_result **out, gd_error *err)
{
    *out = NULL;
    int np = opt->nparams, nt = mm->nmodes;
    if (np < 1 || np > 32)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "--update", "update 1 to 32 parameters",
                            "%d parameters to update", np);
    ctx c = {src, mm, opt, np, nt, calloc((size_t)np, sizeof(double))};
    gd_update_result *res = calloc(1, sizeof *res);
    double *th = calloc((size_t)np, sizeof(double)), *p = calloc((size_t)np, sizeof(double));
    double *tn = calloc((size_t)np, sizeof(double)), *r = calloc((size_t)nt, sizeof(double));
    double *rn = calloc((size_t)nt, sizeof(double)), *J = calloc((size_t)nt * np, sizeof(double));
    double *A = calloc((size_t)np * np, sizeof(double)), *g = calloc((size_t)np, sizeof(double));
    gd_corr_modes md = {0};
    gd_corr_table *t = NULL;
    gd_status st = GD_OK;
    if (!c.p0 || !res || !th || !p || !tn || !r || !rn || !J || !A || !g) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    res->nparams = np;
    res->ntargets = nt;
    res->initial = calloc((size_t)np, sizeof(double));
    res->value = calloc((size_t)np, sizeof(double));
    res->sigma = calloc((size_t)np, sizeof(double));
    res->sens = calloc((size_t)nt * np, sizeof(double));
    if (!res->initial || !res->value || !res->sigma || !res->sens) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    /* starting values: the file's (after the fixed overrides), inside the bounds */
    for (int k = 0; k < np && !st; k++) {
        const gd_update_param *pp = &opt->params[k];
        char first[256];
        const char *comma = strchr(pp->key, ',');
        snprintf(first, sizeof first, "%.*s", comma ? (int)(comma - pp->key) : (int)strlen(pp->key),
                 pp->key);
        if (!(pp->lo > 0 && pp->hi > pp->lo && isfinite(pp->hi))) {
            st = gd_error_set(err, GD_EINPUT, "--update", 0, 0, pp->key,
                              "write KEY=LO:HI with 0 < LO < HI, e.g. bearings.*.k=5e7:2e8",
                              "bounds %g:%g of '%s' are not 0 < LO < HI", pp->lo, pp->hi, pp->key);
            break;
        }
        st = gd_model_source_value(src, &opt->load, first, &c.p0[k], err);
        if (st) break;
        if (!(c.p0[k] > 0)) {
            st = gd_error_set(err, GD_EINPUT, "--update", 0, 0, pp->key,
                              "update positive values (stiffnesses, moduli, masses)",
                              "'%s' starts at %g, not above zero", first, c.p0[k]);
            break;
        }
        res->initial[k] = c.p0[k];
        p[k] = fmin(fmax(c.p0[k], pp->lo), pp->hi);
        th[k] = p[k] / c.p0[k];
    }
    if (st) goto done;
    st = eval(&c, p, &md, &t, r, err);
    if (st) goto done;
    st = jacobian(&c, p, &md, t, J, res->sens, err);
    if (st) goto done;
    res->before = t;
    t = NULL;
    /* a parameter that moves no target cannot be updated: say which */
    for (int k = 0; k < np; k++) {
        double big = 0;
        for (int i = 0; i < nt; i++)
            big = fmax(big, fabs(J[i * np + k]));
        if (big < 1e-6)
            st = gd_error_set(err, GD_EINPUT, "--update", 0, 0, opt->params[k].key,
                              "update parameters the measured modes depend on (bearing, mesh "
                              "stiffness, a modulus)",
                              "'%s' changes no target frequency (largest d ln f / d ln p = %.2g)",
                              opt->params[k].key, big);
        if (st) goto done;
    }
    if (opt->fd_check) {
        res->sens_fd = calloc((size_t)nt * np, sizeof(double));
        if (!res->sens_fd) {
            st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
            goto done;
        }
        for (int k = 0; k < np && !st; k++) {
            double h = 1e-4 * p[k], q[32], fp[64], fm[64];
            gd_corr_modes m2;
            gd_corr_table *t2;
            for (int sgn = -1; sgn <= 1 && !st; sgn += 2) {
                memcpy(q, p, (size_t)np * sizeof *q);
                q[k] += sgn * h;
                st = eval(&c, q, &m2, &t2, NULL, err);
                if (st) break;
                for (int i = 0; i < nt && i < 64; i++)
                    (sgn < 0 ? fm : fp)[i] = gd_corr_hz(&m2, res->before->pairs[i].model);
                gd_corr_modes_free(&m2);
                gd_corr_table_free(t2);
            }
            for (int i = 0; !st && i < nt && i < 64; i++)
                res->sens_fd[i * np + k] = (fp[i] - fm[i]) / (2 * h);
        }
        if (st) goto done;
    }
    /* bounded Levenberg-Marquardt */
    double f0 = sumsq(nt, r), mu = -1;
    int it;
    for (it = 0; it < opt->max_iter; it++) {
        for (int a = 0; a < np; a++) {
            g[a] = 0;
            for (int i = 0; i < nt; i++)
                g[a] += J[i * np + a] * r[i];
        }
        double dmax = 0;
        for (int a = 0; a < np; a++)
            for (int b = 0; b < np; b++) {
                double s = 0;
                for (int i = 0; i < nt; i++)
                    s += J[i * np + a] * J[i * np + b];
                A[a * np + b] = s;
                if (a == b) dmax = fmax(dmax, s);
            }
        if (mu < 0) mu = 1e-3;
        int accepted = 0;
        double stepn = 0;
        for (int tries = 0; tries < 12 && !accepted; tries++) {
            double Al[32 * 32], d[32];
            for (int a = 0; a < np; a++) {
                /* a parameter on a bound that the gradient pushes outward stays there
                 * (the active set of the box): its row and column drop out */
                const gd_update_param *pp = &opt->params[a];
                int lo_act = th[a] <= pp->lo / c.p0[a] * (1 + 1e-12) && g[a] > 0;
                int hi_act = th[a] >= pp->hi / c.p0[a] * (1 - 1e-12) && g[a] < 0;
                for (int b = 0; b < np; b++)
                    Al[a * np + b] = A[a * np + b];
                Al[a * np + a] += mu * fmax(A[a * np + a], 1e-12 * dmax);
                d[a] = -g[a];
                if (lo_act || hi_act) {
                    for (int b = 0; b < np; b++)
                        Al[a * np + b] = Al[b * np + a] = 0;
                    Al[a * np + a] = 1;
                    d[a] = 0;
                }
            }
            if (solve(np, Al, d)) {
                mu *= 4;
                continue;
            }
            stepn = 0;
            for (int a = 0; a < np; a++) {
                const gd_update_param *pp = &opt->params[a];
                tn[a] = fmin(fmax(th[a] + d[a], pp->lo / c.p0[a]), pp->hi / c.p0[a]);
                stepn = fmax(stepn, fabs(tn[a] - th[a]) / fmax(1, fabs(th[a])));
                p[a] = tn[a] * c.p0[a];
            }
            gd_corr_modes m2;
            gd_corr_table *t2;
            st = eval(&c, p, &m2, &t2, rn, err);
            if (st) goto done;
            double f1 = sumsq(nt, rn);
            if (f1 <= f0) {
                accepted = 1;
                /* the cost no longer falls: converged */
                if (f0 - f1 <= 1e-12 * f0) stepn = 0;
                memcpy(th, tn, (size_t)np * sizeof *th);
                memcpy(r, rn, (size_t)nt * sizeof *r);
                f0 = f1;
                gd_corr_modes_free(&md);
                md = m2;
                gd_corr_table_free(t);
                t = t2;
                mu = fmax(mu / 3, 1e-12);
            } else {
                gd_corr_modes_free(&m2);
                gd_corr_table_free(t2);
                mu *= 4;
            }
        }
        for (int a = 0; a < np; a++)
            p[a] = th[a] * c.p0[a];
        if (!accepted || stepn < opt->tol) break;
        st = jacobian(&c, p, &md, t ? t : res->before, J, NULL, err);
        if (st) goto done;
    }
    res->iterations = it + 1;
    if (!t) { /* no step accepted: the start is the answer */
        gd_corr_modes m2;
        st = eval(&c, p, &m2, &t, r, err);
        if (st) goto done;
        gd_corr_modes_free(&m2);
    }
    st = jacobian(&c, p, &md, t, J, NULL, err);
    if (st) goto done;
    /* confidence: s^2 (J^T J)^-1 in theta, s^2 = |r|^2 / (m - n) */
    {
        double s2 = nt > np ? f0 / (nt - np) : NAN;
        double Ai[32 * 32];
        for (int a = 0; a < np; a++)
            for (int b = 0; b < np; b++) {
                double s = 0;
                for (int i = 0; i < nt; i++)
                    s += J[i * np + a] * J[i * np + b];
                Ai[a * np + b] = s;
            }
        int ok = LAPACKE_dpotrf(LAPACK_ROW_MAJOR, 'L', np, Ai, np) == 0 &&
                 LAPACKE_dpotri(LAPACK_ROW_MAJOR, 'L', np, Ai, np) == 0;
        for (int a = 0; a < np; a++) {
            res->value[a] = p[a];
            res->sigma[a] = ok ? sqrt(s2 * Ai[a * np + a]) * c.p0[a] : NAN;
            const gd_update_param *pp = &opt->params[a];
            if (p[a] <= pp->lo * (1 + 1e-9) || p[a] >= pp->hi * (1 - 1e-9)) res->at_bound = 1;
        }
    }
    res->after = t;
    t = NULL;
done:
    gd_corr_modes_free(&md);
    gd_corr_table_free(t);
    free(c.p0), free(th), free(p), free(tn), free(r), free(rn), free(J), free(A), free(g);
    if (st)
        gd_update_free(res);
    else
        *out = res;
    return st;
}
