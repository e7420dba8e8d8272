/* The static initial state of a run (GD_TR_INIT_STATIC): equilibrium at t by modified
 * Newton with the linear stiffness (meshes at their model stiffness, always in contact)
 * as the iteration matrix. Backlash meshes are held on a flank (each flank's law
 * continued beyond its interval, so the problem is smooth): all start on the drive
 * flank; after convergence a mesh whose force pulls (F < 0) moves to the coast flank and
 * one pushing on the coast flank back to the drive flank, until no flank changes. A mesh
 * carrying no load is left in the gap by the caller's gd_transient_set_contacts.
 *
 * A train free in torsion (every gearbox driven by a torque and loaded by one: no DOF
 * holds its rotation) has no static state: K_ff is singular along the train's rotation
 * in its speed ratios, phi (rz of every shaft by its ratio; a turn in the ratios
 * deforms no mesh). An LU of K_ff then takes a pivot of rounding size and the iteration
 * diverges ("did not converge", issue 35). The start is then the train's state under
 * inertia relief (as in FE statics of free structures): the net load that would turn
 * the train is balanced by the inertia of a uniform angular acceleration a of the whole
 * train, K q = f(q) - M phi a, with the gauge phi^T M q = 0 (the bordered system below);
 * the run then starts from the elastic state under the loads and accelerates from it.
 *
 * A model whose laws carry static load (GD_LAW_SUPPORT: rolling or journal bearings) has
 * no linear stiffness in their directions (a rolling bearing's clearance, a journal's
 * film), so K_ff is singular there and the iteration above cannot start (issue 35 item
 * 6). Its start is the static analysis's equilibrium (src/static: the same solver, laws
 * and holds as `geardyn static`) under the run's loads at t: K q = f(t) + f_law(q) with
 * the prescribed DOFs and one torsion DOF per free train held, or its located error
 * naming the DOF that moves or the law that cannot carry the load. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"
#include "system/system_impl.h"
#include "transient/transient_impl.h"

/* 1 when one of the problem's laws carries static load (the model's bearings). */
static int support_laws(const gd_transient *tr)
{
    for (int i = 0; i < tr->nlaw; i++)
        if (tr->law[i].type->flags & GD_LAW_SUPPORT) return 1;
    return 0;
}

/* The static analysis's equilibrium under the run's loads at t (the residual at rest
 * less the system laws' forces there, which the static solver adds itself) into y. */
static gd_status static_of_laws(gd_transient *tr, double t, double *y, gd_error *err)
{
    const gd_system *sys = tr->sys;
    const int n = sys->ndof, nf = tr->nf;
    size_t n1 = (size_t)(n > 0 ? n : 1);
    double *f = calloc(n1, sizeof *f), *fl = calloc(n1, sizeof *fl), *q = calloc(n1, sizeof *q);
    int *held = malloc(n1 * sizeof *held);
    gd_status st = GD_OK;
    if (!f || !fl || !q || !held) {
        st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        goto out;
    }
    memset(y, 0, (size_t)2 * nf * sizeof *y);
    gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
    memset(tr->acc, 0, (size_t)tr->n * sizeof *tr->acc);
    gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
    gd_system_law_forces(sys, tr->speed, q, fl);
    for (int i = 0; i < n; i++)
        f[i] = tr->r[i] - fl[i];
    gd_static_options so;
    gd_static_options_init(&so);
    so.speed = tr->speed;
    if ((st = gd_st_equilibrium(sys, &so, tr->speed, f, 1, held, q, err))) goto out;
    for (int i = 0; i < nf; i++)
        y[i] = q[tr->free_dof[i]];
    /* the laws' contact states (a backlash mesh's flank) at that state */
    gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
    for (int i = 0; i < tr->nlaw; i++) {
        gd_law *L = &tr->law[i];
        if (!L->type->static_mode) continue;
        L->mode = L->type->hold_mode;
        if (!gd_law_nswitches(L)) continue;
        gd_law_point lx;
        gd_tr_law_here(tr, L, t, &lx);
        L->mode = L->type->static_mode(L, &lx);
    }
out:
    free(f);
    free(fl);
    free(q);
    free(held);
    return st;
}

/* phi (nf): the free DOFs' share of the train's rotation (rz by the shaft's speed
 * ratio); 1 when K_ff phi vanishes to rounding against the torsional stiffness on phi,
 * i.e. the train is free to turn. */
static int free_rotation(const gd_transient *tr, double *phi)
{
    const int nf = tr->nf;
    double pmax = 0, kscale = 0;
    for (int i = 0; i < nf; i++) {
        phi[i] = tr->ratio[tr->free_dof[i]];
        pmax = fmax(pmax, fabs(phi[i]));
    }
    if (!(pmax > 0)) return 0;
    const cs *K = tr->Kff;
    double *kp = calloc((size_t)nf, sizeof *kp);
    if (!kp) return 0;
    for (int j = 0; j < nf; j++)
        for (int p = K->p[j]; p < K->p[j + 1]; p++) {
            kp[K->i[p]] += K->x[p] * phi[j];
            if (K->i[p] == j && phi[j] != 0) kscale = fmax(kscale, fabs(K->x[p] * phi[j]));
        }
    double r = 0;
    for (int i = 0; i < nf; i++)
        r = fmax(r, fabs(kp[i]));
    free(kp);
    return kscale > 0 && r <= 1e-9 * kscale;
}

/* [K_ff, m; m^T, 0] with m = M_ff phi: the stiffness bordered by the train's inertia. */
static cs *bordered(const gd_transient *tr, const double *phi, double *m)
{
    const int nf = tr->nf;
    memset(m, 0, (size_t)nf * sizeof *m);
    cs_gaxpy(tr->Mff, phi, m);
    const cs *K = tr->Kff;
    cs *T = cs_spalloc(nf + 1, nf + 1, K->p[nf] + 2 * nf, 1, 1);
    if (!T) return NULL;
    int ok = 1;
    for (int j = 0; j < nf && ok; j++)
        for (int p = K->p[j]; p < K->p[j + 1] && ok; p++)
            ok = cs_entry(T, K->i[p], j, K->x[p]);
    for (int i = 0; i < nf && ok; i++)
        if (m[i] != 0) ok = cs_entry(T, i, nf, m[i]) && cs_entry(T, nf, i, m[i]);
    cs *A = ok ? cs_compress(T) : NULL;
    cs_spfree(T);
    return A;
}

gd_status gd_tr_static_state(gd_transient *tr, double t, double *y, gd_error *err)
{
    const int nf = tr->nf;
    /* the physical DOFs are the system's: the static analysis's solver applies */
    if (!tr->red && tr->n == tr->sys->ndof && support_laws(tr))
        return static_of_laws(tr, t, y, err);
    double *phi = malloc((size_t)(nf + 1) * sizeof *phi);
    double *m = malloc((size_t)(nf + 1) * sizeof *m);
    double *b = malloc((size_t)(nf + 1) * sizeof *b), *x = malloc((size_t)(nf + 1) * sizeof *x);
    if (!phi || !m || !b || !x) {
        free(phi);
        free(m);
        free(b);
        free(x);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    /* the reduced problem's coordinates are not the shafts' DOFs: no relief there */
    int relief = !tr->red && free_rotation(tr, phi);
    cs *A = relief ? bordered(tr, phi, m) : NULL;
    const int na = relief ? nf + 1 : nf;
    css *S = relief ? (A ? cs_sqr(1, A, 0) : NULL) : cs_sqr(1, tr->Kff, 0);
    csn *N = S ? cs_lu(relief ? A : tr->Kff, S, 1.0) : NULL;
    gd_status st = GD_OK;
    if (!N) {
        st = gd_error_set(err, GD_EINPUT, "", 0, 0, "init",
                          "start from rest, or prescribe a DOF (e.g. the input) or add a "
                          "support; `geardyn static` names the DOF that moves",
                          relief ? "static initial state: a free motion other than the train's "
                                   "rotation (a shaft without bearings, or a second free train)"
                                 : "static initial state: the stiffness of the free DOFs is "
                                   "singular (a free rigid-body motion)");
        goto out;
    }
    memset(y, 0, (size_t)2 * nf * sizeof *y);
    for (int i = 0; i < tr->nlaw; i++)
        if (tr->law[i].type->static_mode) tr->law[i].mode = tr->law[i].type->hold_mode;
    int converged = 0;
    for (int outer = 0; outer < 20 && !converged; outer++) {
        int it;
        for (it = 0; it < 500; it++) {
            gd_tr_fill(tr, t, y, tr->q, tr->v, tr->acc);
            memset(tr->acc, 0, (size_t)tr->n * sizeof *tr->acc);
            gd_tr_residual(tr, t, tr->q, tr->v, tr->acc, tr->r);
            for (int i = 0; i < nf; i++)
                b[i] = tr->r[tr->free_dof[i]];
            if (relief) b[nf] = 0; /* the gauge: phi^T M dq = 0 */
            cs_ipvec(N->pinv, b, x, na);
            cs_lsolve(N->L, x);
            cs_usolve(N->U, x);
            cs_ipvec(S->q, x, b, na);
            double dn = 0, qn = 0;
            for (int i = 0; i < nf; i++) {
                y[i] += b[i];
                dn = fmax(dn, fabs(b[i]));
                qn = fmax(qn, fabs(y[i]));
            }
            if (!isfinite(dn)) break;
            if (dn <= 1e-13 * qn || dn == 0.0) break;
        }
        if (it == 500 || !isfinite(y[0])) break;
        converged = 1;
        gd_tr_fill(tr, t, y, tr->q, tr->v, NULL);
        for (int i = 0; i < tr->nlaw; i++) {
            gd_law *L = &tr->law[i];
            if (!L->type->static_mode || !gd_law_nswitches(L)) continue;
            gd_law_point lx;
            gd_tr_law_here(tr, L, t, &lx);
            int ns = L->type->static_mode(L, &lx);
            if (ns != L->mode) {
                L->mode = ns;
                converged = 0;
            }
        }
    }
    if (!converged) {
        memset(y, 0, (size_t)2 * nf * sizeof *y);
        st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "init", "start from rest",
                          "static initial state did not converge (the laws' contact states "
                          "kept changing, or the loads exceed what the laws carry)");
    }
out:
    cs_sfree(S);
    cs_nfree(N);
    cs_spfree(A);
    free(phi);
    free(m);
    free(b);
    free(x);
    return st;
}
