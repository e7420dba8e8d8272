/* Frequency response functions. Direct: at each frequency the complex dynamic
 * stiffness Z(w) = K - w^2 M + i w D is factored once (KLU, symbolic analysis shared)
 * and solved only for the requested inputs; frequencies run in parallel, each writing
 * its own slots. Modal: H(w) = sum_j u_j v_j^T / (i w - lambda_j) over the modes and
 * their conjugates with v^T (2 lambda M + D) u = 1 ([MMT2018] Eqs. 14-15), plus, for
 * rigid-body modes r (K r = D r = 0), the exact term -r r^T / (w^2 r^T M r). */
#include <complex.h>
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/frf.h"
#include "system/system_impl.h"

const char *const gd_frf_quantity_names[3] = {"receptance", "mobility", "accelerance"};

void gd_frf_options_init(gd_frf_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->quantity = GD_FRF_RECEPTANCE;
    opt->method = GD_FRF_DIRECT;
}

void gd_frf_free(gd_frf_result *r)
{
    if (!r) return;
    free(r->freqs);
    free(r->re);
    free(r->im);
    free(r->singular);
    free(r);
}

/* (i w)^p for displacement outputs of the chosen quantity; 1 for forces. */
static double complex quantity_factor(const gd_frf_options *opt, const gd_functional *f, double w)
{
    if (f->is_force) return 1.0;
    switch (opt->quantity) {
    case GD_FRF_MOBILITY:
        return I * w;
    case GD_FRF_ACCELERANCE:
        return -w * w;
    default:
        return 1.0;
    }
}

static double complex apply(const gd_functional *f, double w, const double *q /* complex pairs */)
{
    double complex s = 0;
    for (int j = 0; j < f->n; j++) {
        int i = f->dof[j];
        s += (f->k[j] + I * w * f->c[j]) * (q[2 * i] + I * q[2 * i + 1]);
    }
    return s;
}

static gd_status frf_direct(const gd_system *sys, const gd_frf_options *opt,
                            const gd_functional *fn, gd_frf_result *r, gd_error *err)
{
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    if ((st = gd_splu_analyze(&a.pat, &sym, err))) {
        gd_dynmat_free(&a);
        return st;
    }
    int n = a.pat.n, ni = opt->ninputs, nf = opt->nfreq, no = opt->noutputs;
    double *k = malloc((size_t)a.pat.nnz * sizeof *k), *d = malloc((size_t)a.pat.nnz * sizeof *d);
    int nomem = !k || !d;
    if (!nomem) gd_dynmat_at(&a, opt->speed, k, d);
    /* Entries past 1e150 (no physical stiffness is near: steel contacts are 1e9-1e10 N/m)
     * overflow in the factorisation, which then looked singular and printed "-" with exit 0
     * for a mesh stiffness of 1e308 (issue 38). */
    double big = 0;
    for (int e = 0; !nomem && e < a.pat.nnz; e++)
        big = isfinite(k[e]) && isfinite(d[e]) ? fmax(big, fmax(fabs(k[e]), fabs(d[e]))) : INFINITY;
    if (!nomem && !(big <= 1e150)) {
        free(k);
        free(d);
        gd_splu_symbolic_free(&sym);
        gd_dynmat_free(&a);
        return gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "",
                            "check the stiffness and damping values (and their units) for ones "
                            "so large the solve overflows",
                            "the dynamic stiffness at speed %g rad/s holds entries of %g, beyond "
                            "1e150: the factorisation would overflow",
                            opt->speed, big);
    }
    int nt = opt->nthreads > 0 ? opt->nthreads : omp_get_max_threads();
#pragma omp parallel num_threads(nt) if (!nomem)
    {
        double *z = malloc((size_t)2 * a.pat.nnz * sizeof *z);
        double *q = malloc((size_t)2 * n * ni * sizeof *q);
        int ok = z && q;
        if (!ok) {
#pragma omp atomic write
            nomem = 1;
        }
#pragma omp for schedule(dynamic, 4)
        for (int f = 0; f < nf; f++) {
            if (!ok) continue;
            double w = opt->freqs[f];
            gd_splu lu;
            int rc = gd_dynmat_factor_at(&a, &sym, k, d, w, z, &lu);
            if (rc < 0) {
#pragma omp atomic write
                nomem = 1;
            }
            if (rc) {
                r->singular[f] = 1;
                for (int o = 0; o < no; o++)
                    for (int i = 0; i < ni; i++) {
                        r->re[((size_t)o * ni + i) * nf + f] = NAN;
                        r->im[((size_t)o * ni + i) * nf + f] = NAN;
                    }
                gd_splu_free(&lu);
                continue;
            }
            memset(q, 0, (size_t)2 * n * ni * sizeof *q);
            for (int i = 0; i < ni; i++)
                q[2 * ((size_t)i * n + opt->inputs[i])] = 1.0;
            gd_splu_solve(&lu, &sym, n, ni, q);
            gd_splu_free(&lu);
            for (int o = 0; o < no; o++)
                for (int i = 0; i < ni; i++) {
                    double complex h =
                        apply(&fn[o], w, q + (size_t)2 * i * n) * quantity_factor(opt, &fn[o], w);
                    r->re[((size_t)o * ni + i) * nf + f] = creal(h);
                    r->im[((size_t)o * ni + i) * nf + f] = cimag(h);
                }
        }
        free(z);
        free(q);
    }
    free(k);
    free(d);
    gd_splu_symbolic_free(&sym);
    gd_dynmat_free(&a);
    if (nomem) return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the FRF");
    return GD_OK;
}

/* Rigid-body shapes, M-orthonormalised; checks K r = 0 and D r = 0. */
static gd_status rigid_shapes(const gd_system *sys, const gd_modal_result *mr, double speed,
                              double **R, int *nr, gd_error *err)
{
    int n = sys->ndof, cnt = 0;
    for (int j = 0; j < mr->nmodes; j++)
        cnt += mr->modes[j].rigid_body;
    *nr = cnt;
    *R = NULL;
    if (!cnt) return GD_OK;
    double *Rm = malloc((size_t)n * cnt * sizeof *Rm), *t = malloc((size_t)n * sizeof *t);
    double *Md = malloc((size_t)n * n * sizeof *Md), *Dd = malloc((size_t)n * n * sizeof *Dd);
    double *Kd = malloc((size_t)n * n * sizeof *Kd);
    gd_status st = GD_OK;
    if (!Rm || !t || !Md || !Dd || !Kd) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    gd_system_dense(sys, speed, Md, Dd, Kd);
    double kn = 0, dn = 0;
    for (size_t i = 0; i < (size_t)n * n; i++) {
        kn = fmax(kn, fabs(Kd[i]));
        dn = fmax(dn, fabs(Dd[i]));
    }
    int c = 0;
    for (int j = 0; j < mr->nmodes; j++) {
        if (!mr->modes[j].rigid_body) continue;
        double *r = Rm + (size_t)c * n;
        memcpy(r, mr->shape_re + (size_t)j * n, (size_t)n * sizeof *r);
        for (int pass = 0; pass < 2; pass++)
            for (int b = 0; b < c; b++) { /* r -= (rb^T M r) rb */
                const double *rb = Rm + (size_t)b * n;
                double s = 0;
                for (int x = 0; x < n; x++) {
                    double mx = 0;
                    for (int y = 0; y < n; y++)
                        mx += Md[x + (size_t)y * n] * r[y];
                    s += rb[x] * mx;
                }
                for (int x = 0; x < n; x++)
                    r[x] -= s * rb[x];
            }
        double mm = 0, rk = 0, rd = 0, rn = 0;
        for (int x = 0; x < n; x++) {
            double mx = 0, kx = 0, dx = 0;
            for (int y = 0; y < n; y++) {
                mx += Md[x + (size_t)y * n] * r[y];
                kx += Kd[x + (size_t)y * n] * r[y];
                dx += Dd[x + (size_t)y * n] * r[y];
            }
            mm += r[x] * mx;
            rk = fmax(rk, fabs(kx));
            rd = fmax(rd, fabs(dx));
            rn = fmax(rn, fabs(r[x]));
        }
        if (!(mm > 0) || rk > 1e-8 * kn * rn * n || rd > 1e-8 * (dn > 0 ? dn : 1) * rn * n) {
            st = gd_error_set(err, GD_EINPUT, sys->model->file, 0, 0, "method",
                              "use the direct method",
                              "modal summation needs rigid-body modes "
                              "free of stiffness and damping (K r = D r = 0)");
            goto done;
        }
        for (int x = 0; x < n; x++)
            r[x] /= sqrt(mm);
        c++;
    }
    *R = Rm;
    Rm = NULL;
done:
    free(Rm);
    free(t);
    free(Md);
    free(Dd);
    free(Kd);
    return st;
}

static gd_status frf_modal(const gd_system *sys, const gd_frf_options *opt, const gd_functional *fn,
                           gd_frf_result *r, gd_error *err)
{
    gd_modal_options mo;
    gd_modal_options_init(&mo);
    mo.speed = opt->speed;
    mo.nmodes = opt->nmodes;
    mo.want_left = 1;
    gd_modal_result *mr;
    gd_status st = gd_modal_solve(sys, &mo, &mr, err);
    if (st) return st;
    double *R = NULL;
    int nr = 0;
    if ((st = rigid_shapes(sys, mr, opt->speed, &R, &nr, err))) {
        gd_modal_free(mr);
        return st;
    }
    int n = sys->ndof, ni = opt->ninputs, nf = opt->nfreq, no = opt->noutputs, nm = mr->nmodes;
    /* per mode: c_k . u, c_c . u for each output; v[input] for each input */
    size_t sz = (size_t)nm * (no > 0 ? no : 1) + (size_t)nm * ni + (size_t)nr * (no + ni) + 1;
    double complex *cu_k = calloc(sz, sizeof *cu_k), *cu_c = calloc(sz, sizeof *cu_c);
    double complex *vb = calloc(sz, sizeof *vb);
    double *rc_k = calloc(sz, sizeof *rc_k), *rc_c = calloc(sz, sizeof *rc_c),
           *rb = calloc(sz, sizeof *rb);
    if (!cu_k || !cu_c || !vb || !rc_k || !rc_c || !rb) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto done;
    }
    int used = 0;
    for (int j = 0; j < nm; j++) {
        if (mr->modes[j].rigid_body) continue;
        used++;
        const double *ur = mr->shape_re + (size_t)j * n, *ui = mr->shape_im + (size_t)j * n;
        const double *vr = mr->left_re + (size_t)j * n, *vi = mr->left_im + (size_t)j * n;
        for (int o = 0; o < no; o++) {
            double complex sk = 0, sc = 0;
            for (int e = 0; e < fn[o].n; e++) {
                double complex u = ur[fn[o].dof[e]] + I * ui[fn[o].dof[e]];
                sk += fn[o].k[e] * u;
                sc += fn[o].c[e] * u;
            }
            cu_k[(size_t)j * no + o] = sk;
            cu_c[(size_t)j * no + o] = sc;
        }
        for (int i = 0; i < ni; i++)
            vb[(size_t)j * ni + i] = vr[opt->inputs[i]] + I * vi[opt->inputs[i]];
    }
    for (int b = 0; b < nr; b++) {
        const double *rr = R + (size_t)b * n;
        for (int o = 0; o < no; o++) {
            double sk = 0, sc = 0;
            for (int e = 0; e < fn[o].n; e++) {
                sk += fn[o].k[e] * rr[fn[o].dof[e]];
                sc += fn[o].c[e] * rr[fn[o].dof[e]];
            }
            rc_k[(size_t)b * no + o] = sk;
            rc_c[(size_t)b * no + o] = sc;
        }
        for (int i = 0; i < ni; i++)
            rb[(size_t)b * ni + i] = rr[opt->inputs[i]];
    }
    r->nmodes_used = used;
    r->nrigid = nr;
    for (int f = 0; f < nf; f++) {
        double w = opt->freqs[f];
        double complex s = I * w;
        for (int o = 0; o < no; o++)
            for (int i = 0; i < ni; i++) {
                double complex h = 0;
                for (int j = 0; j < nm; j++) {
                    const gd_mode *md = &mr->modes[j];
                    if (md->rigid_body) continue;
                    double complex lam = md->lambda_re + I * md->lambda_im;
                    double complex cu = cu_k[(size_t)j * no + o] + s * cu_c[(size_t)j * no + o];
                    double complex v = vb[(size_t)j * ni + i];
                    h += cu * v / (s - lam);
                    if (md->lambda_im > 0) { /* the conjugate mode */
                        double complex cuc =
                            conj(cu_k[(size_t)j * no + o]) + s * conj(cu_c[(size_t)j * no + o]);
                        h += cuc * conj(v) / (s - conj(lam));
                    }
                }
                for (int b = 0; b < nr; b++) {
                    double complex cr = rc_k[(size_t)b * no + o] + s * rc_c[(size_t)b * no + o];
                    h += cr * rb[(size_t)b * ni + i] / (s * s);
                }
                if (nr > 0 && w == 0) {
                    h = NAN;
                    r->singular[f] = 1;
                }
                h *= quantity_factor(opt, &fn[o], w);
                r->re[((size_t)o * ni + i) * nf + f] = creal(h);
                r->im[((size_t)o * ni + i) * nf + f] = cimag(h);
            }
    }
done:
    free(cu_k);
    free(cu_c);
    free(vb);
    free(rc_k);
    free(rc_c);
    free(rb);
    free(R);
    gd_modal_free(mr);
    return st;
}

gd_status gd_frf(const gd_system *sys, const gd_frf_options *opt, gd_frf_result **out,
                 gd_error *err)
{
    *out = NULL;
    if (opt->nfreq < 1 || !opt->freqs)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "freq", "give at least one frequency",
                            "no frequencies to compute");
    for (int f = 0; f < opt->nfreq; f++)
        if (!isfinite(opt->freqs[f]) || opt->freqs[f] < 0)
            return gd_error_set(
                err, GD_EINPUT, "", 0, 0, "freq", "give finite frequencies of zero or more",
                "frequency %d (%g rad/s) is negative or not finite", f + 1, opt->freqs[f]);
    if (opt->ninputs < 1 || opt->noutputs < 1)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, opt->ninputs < 1 ? "input" : "output",
                            "name an input DOF and at least one output", "no %s given",
                            opt->ninputs < 1 ? "input" : "output");
    for (int i = 0; i < opt->ninputs; i++)
        if (opt->inputs[i] < 0 || opt->inputs[i] >= sys->ndof)
            return gd_error_set(err, GD_EINPUT, "", 0, 0, "input", "name an active DOF",
                                "input DOF %d is not an active DOF", opt->inputs[i]);
    gd_frf_result *r = calloc(1, sizeof *r);
    gd_functional *fn = calloc((size_t)opt->noutputs, sizeof *fn);
    size_t nv = (size_t)opt->noutputs * opt->ninputs * opt->nfreq;
    gd_status st = GD_OK;
    if (!r || !fn || !(r->freqs = malloc((size_t)opt->nfreq * sizeof(double))) ||
        !(r->re = malloc(nv * sizeof(double))) || !(r->im = malloc(nv * sizeof(double))) ||
        !(r->singular = calloc((size_t)opt->nfreq, sizeof(int)))) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory in the FRF");
        goto done;
    }
    r->nfreq = opt->nfreq;
    r->ninputs = opt->ninputs;
    r->noutputs = opt->noutputs;
    memcpy(r->freqs, opt->freqs, (size_t)opt->nfreq * sizeof(double));
    for (int o = 0; o < opt->noutputs; o++) {
        const gd_probe *p = &opt->outputs[o];
        int bad =
            p->index < 0 || (!p->element && p->index >= sys->ndof) ||
            (p->element && (!p->element->force_row || p->index >= p->element->count(sys->model)));
        if (bad) {
            st = gd_error_set(err, GD_EINPUT, "", 0, 0, "output",
                              "name an existing DOF, mesh or bearing", "output %d does not exist",
                              o + 1);
            goto done;
        }
        gd_probe_functional(sys, p, opt->speed, &fn[o]);
    }
    st = opt->method == GD_FRF_MODAL ? frf_modal(sys, opt, fn, r, err)
                                     : frf_direct(sys, opt, fn, r, err);
    if (st) goto done;
    for (int f = 0; f < r->nfreq; f++)
        r->nsingular += r->singular[f];
    *out = r;
    r = NULL;
done:
    gd_frf_free(r);
    free(fn);
    return st;
}

void gd_frf_directional(const gd_frf_result *r, int ox, int oy, double *fr, double *fi, double *br,
                        double *bi)
{
    /* inputs 0 = x, 1 = y; H_ab = response a to input b */
    int nf = r->nfreq, ni = r->ninputs;
    for (int f = 0; f < nf; f++) {
#define H(o, i)                                                                                    \
    (r->re[((size_t)(o)*ni + (i)) * nf + f] + I * r->im[((size_t)(o)*ni + (i)) * nf + f])
        double complex hxx = H(ox, 0), hxy = H(ox, 1), hyx = H(oy, 0), hyy = H(oy, 1);
#undef H
        double complex hf = 0.5 * (hxx + hyy + I * (hyx - hxy));
        double complex hb = 0.5 * (hxx + hyy - I * (hyx - hxy));
        fr[f] = creal(hf);
        fi[f] = cimag(hf);
        br[f] = creal(hb);
        bi[f] = cimag(hb);
    }
}
