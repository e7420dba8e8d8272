/* The sparse modes to the precision asked (gd_modal_options.tol, `geardyn modal --tol`):
 * Krylov-Schur (sparse_modes.c), then the refinement of the continuation (sparse_track.c)
 * while an elastic mode's relative residual (residual.c) is above the tolerance and
 * above what rounding leaves; and gd_modal_solve_sparse, the library's entry. */
#include <math.h>

#include "modal/modal_impl.h"

/* the largest residual of the elastic modes of r: all of them (want < 0), or only those
 * above want and above 100 times their rounding floor (0: none left to improve) */
static double worst_residual(const gd_modal_result *r, double want)
{
    double w = 0;
    for (int j = 0; j < r->nmodes; j++) {
        const gd_mode *md = &r->modes[j];
        if (!md->rigid_body &&
            (want < 0 || (md->residual > want && md->residual > 100 * md->residual_floor)))
            w = fmax(w, md->residual);
    }
    return w;
}

/* The linearised laws' share of the strain energy of the final modes (out freed on
 * failure). */
static gd_status laws_energy(const gd_dynmat *a, const gd_modal_options *opt, gd_modal_result **out,
                             gd_error *err)
{
    if (!gd_modal_energies_laws(a->sys, *out, opt->law_state)) return GD_OK;
    gd_modal_free(*out);
    *out = NULL;
    return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                        "out of memory in the sparse eigensolver");
}

gd_status gd_sparse_modes_to_tol(const gd_dynmat *a, const gd_splu_symbolic *sym,
                                 const gd_modal_options *opt, double shift, gd_sparse_ws *ws,
                                 gd_modal_result **out, gd_error *err)
{
    gd_modal_options o = *opt;
    double want = opt->tol > 0 ? opt->tol : GD_MODAL_TOL_DEFAULT;
    /* Krylov-Schur at least to the default: the refinement below starts from its modes,
     * and from those of a looser tolerance (1e-8 on gearbox100k) it does not converge */
    o.tol = fmin(want, GD_MODAL_TOL_DEFAULT);
    gd_status st = gd_sparse_modes(a, sym, &o, shift, ws, out, err);
    if (st) return st;
    if (worst_residual(*out, want) == 0) return laws_energy(a, opt, out, err);
    /* Krylov-Schur's vectors stop improving near 1e-8 of residual on the MMT rig
     * whatever its tolerance (their eigenvalues agree with LAPACK's to 1e-11): the pairs
     * are refined on the quadratic problem itself by residual inverse iteration with
     * Rayleigh-Ritz at factorisations of P(sigma) near them (sparse_track.c, the Campbell
     * continuation, here from this speed's own modes), a pass kept only when it lowers
     * the worst residual; at most 3 passes (repeated frequencies take two) */
    gd_sparse_ws local = {0};
    gd_sparse_ws *tw = ws;
    if (!tw) {
        if (gd_sparse_ws_init(&local, a, o.nmodes > 0 ? o.nmodes : a->pat.n))
            return laws_energy(a, opt, out, err); /* the Krylov-Schur modes as they are */
        tw = &local;
    }
    for (int pass = 0; pass < 3 && !st && worst_residual(*out, want) > 0; pass++) {
        gd_modal_result *ref = NULL;
        st = gd_sparse_refine(a, sym, &o, *out, tw, &ref, NULL);
        if (!st && ref &&
            gd_modal_residuals_on(a, tw->k, ref->damped ? tw->d : NULL, ref, NULL, NULL))
            st = GD_ENOMEM;
        int better = !st && ref && worst_residual(ref, -1) < worst_residual(*out, -1);
        if (better) {
            gd_modal_free(*out);
            *out = ref;
        } else {
            gd_modal_free(ref);
            if (!st) break;
        }
    }
    gd_sparse_ws_free(&local);
    /* the laws' strain energy, once the shapes are final */
    if (st != GD_ENOMEM && gd_modal_energies_laws(a->sys, *out, opt->law_state)) st = GD_ENOMEM;
    if (st == GD_ENOMEM) {
        gd_modal_free(*out);
        *out = NULL;
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "",
                            "out of memory in the sparse eigensolver");
    }
    return GD_OK; /* a refinement that failed leaves the Krylov-Schur modes */
}

gd_status gd_modal_solve_sparse(const gd_system *sys, const gd_modal_options *opt, double shift,
                                gd_modal_result **out, gd_error *err)
{
    *out = NULL;
    gd_dynmat a;
    gd_splu_symbolic sym;
    gd_status st = gd_dynmat_build(sys, &a, err);
    if (st) return st;
    st = gd_splu_analyze(&a.pat, &sym, err);
    if (!st) {
        st = gd_sparse_modes_to_tol(&a, &sym, opt, shift, NULL, out, err);
        gd_splu_symbolic_free(&sym);
    }
    gd_dynmat_free(&a);
    return st;
}
