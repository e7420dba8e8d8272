/* The x-y pair layout shared by the squeeze film damper, the journal bearing and the
 * rolling-element bearing (laws_impl.h), and the linearisation of any law from its
 * rank-one terms (with its force, in one evaluation: gd_law_force_tangent). */
#include <stdio.h>

#include "laws/laws_impl.h"

const int gd_law_xy_dirs[2] = {0, 1};

void gd_law_xy_term(const gd_law *law, int k, double *u, double *w)
{
    (void)law;
    int r = k / 2, c = k % 2;
    u[r] = 1.0;
    u[2 + r] = -1.0;
    w[c] = 1.0;
    w[2 + c] = -1.0;
}

/* K -= sum jq_k u_k w_k^T, C -= sum jv_k u_k w_k^T over the law's terms */
static void add_terms(const gd_law *law, const double *jq, const double *jv, double *K, double *C)
{
    const gd_law_type *t = law->type;
    const int n = law->ndofs;
    for (int k = 0; k < t->nterms; k++) {
        double u[GD_LAW_MAX_DOFS] = {0}, w[GD_LAW_MAX_DOFS] = {0};
        t->term(law, k, u, w);
        for (int j = 0; j < n; j++) {
            if (w[j] == 0.0) continue;
            for (int i = 0; i < n; i++) {
                K[i + n * j] -= jq[k] * u[i] * w[j];
                C[i + n * j] -= jv[k] * u[i] * w[j];
            }
        }
    }
}

void gd_law_linearize_terms(const gd_law *law, const gd_law_point *x, double *K, double *C)
{
    double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS], f[GD_LAW_MAX_DOFS] = {0};
    law->type->force(law, x, f, jq, jv);
    add_terms(law, jq, jv, K, C);
}

void gd_law_force_tangent(const gd_law *law, const gd_law_point *x, double *f, double *K, double *C)
{
    const gd_law_type *t = law->type;
    if (t->linearize == gd_law_linearize_terms) {
        /* one evaluation for the force and its terms */
        double jq[GD_LAW_MAX_TERMS], jv[GD_LAW_MAX_TERMS];
        t->force(law, x, f, jq, jv);
        add_terms(law, jq, jv, K, C);
        return;
    }
    t->force(law, x, f, NULL, NULL);
    if (t->linearize) t->linearize(law, x, K, C);
}

int gd_law_check_film(double film, double max_eccentricity, const char **field, char *msg,
                      size_t cap)
{
    if (film != 0.0 && film != 1.0) {
        *field = "film";
        snprintf(msg, cap, "film is 0 (pi film) or 1 (2pi film), not %g", film);
        return 1;
    }
    if (!(max_eccentricity < 1.0)) {
        *field = "max_eccentricity";
        snprintf(msg, cap, "the eccentricity cap must be below 1 (got %g)", max_eccentricity);
        return 1;
    }
    return 0;
}
