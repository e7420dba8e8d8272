/* The effective mass of a mesh along its line of action (gd_transient_mesh_mass): a unit
 * force pair along the mesh vector a accelerates d = a . q by a^T M_ff^-1 a, so the flanks
 * meet with the inertia m_e = 1 / (a^T M_ff^-1 a) (the rattle intensity's impact energy
 * m_e v^2 / 2, docs/rattle.md). */
#include <stdlib.h>

#include "geardyn/laws.h"
#include "transient/transient_impl.h"

gd_status gd_transient_mesh_mass(gd_transient *tr, int mesh, double *mass, gd_error *err)
{
    *mass = 0.0;
    if (mesh < 0 || mesh >= tr->nmesh)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "mesh", "", "no mesh %d (the problem has %d)",
                            mesh, tr->nmesh);
    if (tr->red)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "mesh", "run without the reduction",
                            "the effective mass of a mesh needs the physical DOFs");
    const gd_law *L = &tr->law[mesh];
    const gd_mesh_law_data *m = L->data;
    double *b = calloc((size_t)tr->nf, sizeof *b), *x = calloc((size_t)tr->nf, sizeof *x);
    if (!b || !x) {
        free(b);
        free(x);
        return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
    }
    int any = 0;
    for (int j = 0; j < m->na && j < L->ndofs; j++) {
        int d = L->dof[j];
        int f = d >= 0 ? tr->fidx[d] : -1;
        if (f < 0 || m->a[j] == 0.0) continue;
        b[f] += m->a[j];
        any = 1;
    }
    double s = 0.0;
    if (any) {
        double *a = calloc((size_t)tr->nf, sizeof *a);
        if (!a) {
            free(b);
            free(x);
            return gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
        }
        for (int i = 0; i < tr->nf; i++)
            a[i] = b[i];
        gd_tr_mass_solve(tr, b, x);
        for (int i = 0; i < tr->nf; i++)
            s += a[i] * x[i];
        free(a);
    }
    free(b);
    free(x);
    if (!(s > 0))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "mesh", "",
                            "mesh %d moves no free DOF: it has no effective mass", mesh);
    *mass = 1.0 / s;
    return GD_OK;
}
