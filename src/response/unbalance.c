/* Steady response to the model's unbalances. An unbalance U on a shaft turning at
 * w_s = ratio x W puts a rotating force of magnitude U w_s^2 on its node; with the heavy
 * spot at angle sense (w t + phase), sense = sign(ratio), w = |w_s|, the complex
 * amplitudes (x = Re(X e^{i w t})) are F_x = U w^2 e^{i phase}, F_y = -i sense F_x.
 * Shafts with different |ratio| give different frequencies at one reference speed:
 * each distinct |ratio| is a harmonic, solved with Z(w) = K - w^2 M + i w D at the
 * reference speed's D and K. Speeds run in parallel, each writing its own slots. */
#include <complex.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/unbalance.h"
#include "system/system_impl.h"

#define PI 3.14159265358979323846

void gd_unbalance_options_init(gd_unbalance_options *opt)
{
    memset(opt, 0, sizeof *opt);
}

void gd_unbalance_free(gd_unbalance_result *r)
{
    if (!r) return;
    free(r->speeds);
    free(r->harmonics);
    free(r->re);
    free(r->im);
    free(r->orbits);
    free(r->singular);
    free(r);
}

void gd_orbit_from(double xr, double xi, double yr, double yi, double sense, gd_orbit *o)
{
    double complex X = xr + I * xi, Y = yr + I * yi;
    /* x + i y = Rf e^{iwt} + Rb e^{-iwt}: Rf = (X + iY)/2, Rb = conj(X - iY)/2 */
    double complex rf = 0.5 * (X + I * Y), rb = 0.5 * conj(X - I * Y);
    double af = cabs(rf), ab = cabs(rb);
    o->major = af + ab;
    o->minor = fabs(af - ab);
    o->angle = 0.5 * (carg(rf) + carg(rb));
    if (!(af + ab > 0) || fabs(af - ab) <= 1e-9 * (af + ab))
        o->whirl = GD_WHIRL_NONE;
    else
        o->whirl = ((af > ab) == (sense >= 0)) ? GD_WHIRL_FORWARD : GD_WHIRL_BACKWARD;
}

static double node_sense(const gd_model *m, int node)
{
    return m->shafts[m->nodes[node].shaft].speed_ratio < 0 ? -1.0 : 1.0;
}

gd_status gd_unbalance_response(const gd_system *sys, const gd_unbalance_options *opt,
                                gd_unbalance_result **out, gd_error *err)
{
    *out = NULL;
    const gd_model *m = sys->model;
    int ns = opt->nspeeds, no = opt->noutputs, nb = opt->norbits;
    if (ns < 1 || !opt->speeds)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "speeds", "give at least one speed",
                            "no speeds to compute");
    for (int s = 0; s < ns; s++)
        if (!isfinite(opt->speeds[s]) || opt->speeds[s] < 0)
            return gd_error_set(
                err, GD_EINPUT, "", 0, 0, "speeds", "give finite speeds of zero or more",
                "speed %d (%g rad/s) is negative or not finite", s + 1, opt->speeds[s]);
        /* the forces U w^2 and the dynamic stiffness K - w^2 M overflow to inf and NaN
         * long before 1e154 rad/s; no rotor survives 1e6 rad/s (9.5 million rpm: a 10 mm
         * rim at 10 km/s) */
        else if (opt->speeds[s] > 1e6)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "speeds",
                                "give speeds up to 1e6 rad/s (9.5 million rpm)",
                                "speed %d (%g rad/s) is beyond any rotor: no rim survives it, "
                                "and w^2 terms overflow",
                                s + 1, opt->speeds[s]);
    if (m->nunbalances == 0)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "unbalances",
                            "add an 'unbalances:' list to the model (docs/model-format.md)",
                            "the model has no unbalances");
    for (int u = 0; u < m->nunbalances; u++) {
        const gd_unbalance *ub = &m->unbalances[u];
        if (gd_system_dof(sys, ub->node, GD_X) < 0 || gd_system_dof(sys, ub->node, GD_Y) < 0)
            return gd_error_set(err, GD_EINPUT, m->file, ub->loc.line, ub->loc.column, ub->name,
                                "keep the lateral DOFs x and y (dofs: or --coupling)",
                                "unbalance '%s' is on node '%s', whose x and y are not active",
                                ub->name, m->nodes[ub->node].name);
    }
    for (int k = 0; k < nb; k++) {
        int nd = opt->orbit_nodes[k];
        if (nd < 0 || nd >= m->nnodes || gd_system_dof(sys, nd, GD_X) < 0 ||
            gd_system_dof(sys, nd, GD_Y) < 0)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "orbit",
                                "name a node whose x and y DOFs are active",
                                "orbit %d: node has no active x and y", k + 1);
    }
    for (int o = 0; o < no; o++) {
        const gd_probe *p = &opt->outputs[o];
        if (p->index < 0 || (!p->element && p->index >= sys->ndof) ||
            (p->element && (!p->element->force_row || p->index >= p->element->count(m))))
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "output",
                                "name an existing DOF, mesh or bearing", "output %d does not exist",
                                o + 1);
    }
    gd_status st = GD_OK;
    gd_unbalance_result *r = calloc(1, sizeof *r);
    int *harm_of = malloc((size_t)m->nunbalances * sizeof *harm_of);
    gd_dynmat a = {0};
    gd_splu_symbolic sym = {0};
    int built = 0;
    if (!r || !harm_of) goto nomem;
    r->harmonics = calloc((size_t)m->nunbalances, sizeof *r->harmonics);
    if (!r->harmonics) goto nomem;
    /* distinct |ratio|, ascending */
    for (int u = 0; u < m->nunbalances; u++) {
        double ord = fabs(m->shafts[m->nodes[m->unbalances[u].node].shaft].speed_ratio);
        int h = 0;
        while (h < r->nharmonics && fabs(r->harmonics[h].order - ord) > 1e-9 * ord)
            h++;
        if (h == r->nharmonics) r->harmonics[r->nharmonics++].order = ord;
    }
    for (int i = 1; i < r->nharmonics; i++)
        for (int j = i; j > 0 && r->harmonics[j - 1].order > r->harmonics[j].order; j--) {
            gd_unbalance_harmonic t = r->harmonics[j];
            r->harmonics[j] = r->harmonics[j - 1];
            r->harmonics[j - 1] = t;
        }
    for (int u = 0; u < m->nunbalances; u++) {
        double ord = fabs(m->shafts[m->nodes[m->unbalances[u].node].shaft].speed_ratio);
        int h = 0;
        while (fabs(r->harmonics[h].order - ord) > 1e-9 * ord)
            h++;
        harm_of[u] = h;
        r->harmonics[h].nunbalances++;
    }
    int nh = r->nharmonics;
    r->nspeeds = ns;
    r->noutputs = no;
    r->norbits = nb;
    size_t nv = (size_t)nh * (no > 0 ? no : 1) * ns, nob = (size_t)nh * (nb > 0 ? nb : 1) * ns;
    r->speeds = malloc((size_t)ns * sizeof *r->speeds);
    r->re = calloc(nv, sizeof *r->re);
    r->im = calloc(nv, sizeof *r->im);
    r->orbits = calloc(nob, sizeof *r->orbits);
    r->singular = calloc((size_t)ns, sizeof *r->singular);
    if (!r->speeds || !r->re || !r->im || !r->orbits || !r->singular) goto nomem;
    memcpy(r->speeds, opt->speeds, (size_t)ns * sizeof *r->speeds);
    if ((st = gd_dynmat_build(sys, &a, err))) goto done;
    built = 1;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) goto done;
    built = 2;
    int n = a.pat.n, nomem = 0;
    int nt = opt->nthreads > 0 ? opt->nthreads : omp_get_max_threads();
#pragma omp parallel num_threads(nt)
    {
        double *k = malloc((size_t)a.pat.nnz * sizeof *k),
               *d = malloc((size_t)a.pat.nnz * sizeof *d);
        double *z = malloc((size_t)2 * a.pat.nnz * sizeof *z),
               *q = malloc((size_t)2 * n * sizeof *q);
        gd_functional *fn = malloc((size_t)(no > 0 ? no : 1) * sizeof *fn);
        int ok = k && d && z && q && fn;
        if (!ok) {
#pragma omp atomic write
            nomem = 1;
        }
#pragma omp for schedule(dynamic, 4)
        for (int s = 0; s < ns; s++) {
            if (!ok) continue;
            double W = opt->speeds[s];
            gd_dynmat_at(&a, W, k, d);
            for (int o = 0; o < no; o++)
                gd_probe_functional(sys, &opt->outputs[o], W, &fn[o]);
            for (int h = 0; h < nh; h++) {
                double w = r->harmonics[h].order * W;
                memset(q, 0, (size_t)2 * n * sizeof *q);
                if (w > 0) {
                    for (int u = 0; u < m->nunbalances; u++) {
                        if (harm_of[u] != h) continue;
                        const gd_unbalance *ub = &m->unbalances[u];
                        double complex fx = ub->amount * w * w * cexp(I * ub->phase);
                        double complex fy = -I * node_sense(m, ub->node) * fx;
                        int ix = gd_system_dof(sys, ub->node, GD_X),
                            iy = gd_system_dof(sys, ub->node, GD_Y);
                        q[2 * ix] += creal(fx);
                        q[2 * ix + 1] += cimag(fx);
                        q[2 * iy] += creal(fy);
                        q[2 * iy + 1] += cimag(fy);
                    }
                    gd_splu lu;
                    int rc = gd_dynmat_factor_at(&a, &sym, k, d, w, z, &lu);
                    if (rc < 0) {
#pragma omp atomic write
                        nomem = 1;
                    }
                    if (rc) {
                        r->singular[s] = 1;
                        for (int i = 0; i < 2 * n; i++)
                            q[i] = NAN;
                    } else {
                        gd_splu_solve(&lu, &sym, n, 1, q);
                    }
                    gd_splu_free(&lu);
                }
                for (int o = 0; o < no; o++) {
                    double complex v = 0;
                    for (int j = 0; j < fn[o].n; j++) {
                        int i = fn[o].dof[j];
                        v += (fn[o].k[j] + I * w * fn[o].c[j]) * (q[2 * i] + I * q[2 * i + 1]);
                    }
                    r->re[((size_t)h * no + o) * ns + s] = creal(v);
                    r->im[((size_t)h * no + o) * ns + s] = cimag(v);
                }
                for (int b = 0; b < nb; b++) {
                    int nd = opt->orbit_nodes[b];
                    int ix = gd_system_dof(sys, nd, GD_X), iy = gd_system_dof(sys, nd, GD_Y);
                    gd_orbit_from(q[2 * ix], q[2 * ix + 1], q[2 * iy], q[2 * iy + 1],
                                  node_sense(m, nd), &r->orbits[((size_t)h * nb + b) * ns + s]);
                }
            }
        }
        free(k);
        free(d);
        free(z);
        free(q);
        free(fn);
    }
    if (nomem) goto nomem;
    *out = r;
    r = NULL;
    goto done;
nomem:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the unbalance response");
done:
    if (built == 2) gd_splu_symbolic_free(&sym);
    if (built) gd_dynmat_free(&a);
    free(harm_of);
    gd_unbalance_free(r);
    return st;
}
