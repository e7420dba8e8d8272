/* Held DOFs of the static analysis. The prescribed DOFs of the model are held at 0 (a
 * motor holding the input at its speed reacts whatever torque it must). What is still
 * free to move as a rigid body is the null space of the stiffness over the other DOFs:
 * found from the Jacobi-scaled stiffness D K D (D = diag(K)^(-1/2), so N/m and N m/rad
 * entries compare), eigenvalues (symmetric K) or singular values (a cross-coupled
 * bearing) below 1e-10 of the largest. A gear train
 * turning as a whole in its ratios moves only torsion DOFs: the torque balance holds it
 * at one torsion DOF per free train, where the train's net torque is reacted (the input
 * torque by the output, or the loads by the input); the planets of a planetary set orbit
 * with it (their translations count with the torsion) and never hold it. Any free motion with a
 * lateral, axial or tilt part (a shaft without bearings) is an input error naming the DOF that
 * moves most. */
#include <lapacke.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "static/static_impl.h"

static const char *const MOTION_WORDS[GD_NODE_DOFS] = {"lateral translation x",
                                                       "lateral translation y",
                                                       "axial translation z",
                                                       "tilt rx",
                                                       "tilt ry",
                                                       "torsion rz"};
static const char *const HOLD_HINTS[GD_NODE_DOFS] = {
    "add a bearing (k, kxx) or a spring on x at this shaft, or prescribe the DOF",
    "add a bearing (k, kyy) or a spring on y at this shaft, or prescribe the DOF",
    "add a bearing with axial stiffness kzz, or leave z out of `dofs:`",
    "add a second bearing along the shaft or a bearing with k_tilt",
    "add a second bearing along the shaft or a bearing with k_tilt",
    "prescribe the torsion of a node of the train"};

/* 1 when node is a planet of a planetary set: its translations orbit with the train's
 * rotation, and its torsion is no place to react the train's torque (docs/planetary.md). */
static int planet_node(const gd_model *m, int node)
{
    for (int k = 0; k < m->nplanetary; k++) {
        const gd_planetary *g = &m->planetary[k];
        if (node >= g->first_planet && node < g->first_planet + g->nplanets) return 1;
    }
    return 0;
}

/* A DOF a gear train turning as a whole moves: torsion, and a planet's translations. */
static int train_dof(const gd_system *sys, int i)
{
    return sys->dof_type[i] == GD_RZ ||
           (sys->dof_type[i] <= GD_Y && planet_node(sys->model, sys->dof_node[i]));
}

/* The free motion whose non-torsion part is largest: an input error naming it. */
static gd_status name_free_motion(const gd_system *sys, const int *fr, int nf, const double *Z,
                                  int r, gd_error *err)
{
    const gd_model *m = sys->model;
    /* G = Zn^T Zn over the non-torsion rows; its top eigenvector combines the null
       vectors into the motion with the most non-torsion movement */
    double *G = calloc((size_t)r * r, sizeof *G), w[64];
    int best = -1;
    if (G && r <= 64) {
        for (int a = 0; a < r; a++)
            for (int b = 0; b < r; b++)
                for (int i = 0; i < nf; i++)
                    if (!train_dof(sys, fr[i]))
                        G[a + (size_t)b * r] += Z[i + (size_t)a * nf] * Z[i + (size_t)b * nf];
        if (LAPACKE_dsyev(LAPACK_COL_MAJOR, 'V', 'U', r, G, r, w) == 0) {
            double mx = 0;
            for (int i = 0; i < nf; i++) {
                if (train_dof(sys, fr[i])) continue;
                double v = 0;
                for (int a = 0; a < r; a++)
                    v += Z[i + (size_t)a * nf] * G[a + (size_t)(r - 1) * r];
                if (fabs(v) > mx) mx = fabs(v), best = fr[i];
            }
        }
    }
    free(G);
    if (best < 0)
        return gd_error_set(err, GD_EINPUT, m->file, 0, 0, "",
                            "add supports (bearings or springs) to every shaft",
                            "the stiffness is singular: the model moves freely as a rigid body");
    int node = sys->dof_node[best];
    gd_dof d = sys->dof_type[best];
    const gd_shaft *sh = &m->shafts[m->nodes[node].shaft];
    char field[GD_NAME_MAX + 32];
    snprintf(field, sizeof field, "shafts[%d]", m->nodes[node].shaft);
    return gd_error_set(err, GD_EINPUT, m->file, sh->loc.line, sh->loc.column, field, HOLD_HINTS[d],
                        "the model is free to move: shaft '%s' in %s (most at node '%s'); "
                        "nothing holds it, so there is no static equilibrium",
                        sh->name, MOTION_WORDS[d], m->nodes[node].name);
}

/* Candidate torsion holds, in order of preference, as nodes (-1 ends). */
static int candidates(const gd_model *m, const gd_static_options *opt, int *out)
{
    int k = 0;
    if (opt->hold_node >= 0) out[k++] = opt->hold_node;
    int in = gd_st_input_node(m, opt);
    if (opt->input_torque == 0) {
        if (in >= 0) out[k++] = in;
        for (int s = 0; s < m->nshafts; s++)
            out[k++] = m->shafts[s].first_node;
    } else {
        int ins = in >= 0 ? m->nodes[in].shaft : -1;
        for (int s = m->nshafts - 1; s >= 0; s--)
            if (s != ins) out[k++] = m->shafts[s].first_node + m->shafts[s].nnodes - 1;
    }
    for (int i = 0; i < m->nnodes; i++)
        out[k++] = i;
    return k;
}

gd_status gd_st_holds(const gd_system *sys, const double *K, const gd_static_options *opt,
                      int *held, gd_error *err)
{
    const gd_model *m = sys->model;
    const int n = sys->ndof;
    memset(held, 0, (size_t)n * sizeof *held);
    for (int k = 0; k < m->nprescribed; k++) {
        int i = gd_system_dof(sys, m->prescribed[k].node, m->prescribed[k].dof);
        if (i >= 0) held[i] = GD_ST_PRESCRIBED;
    }
    int nf = 0;
    int *fr = malloc((size_t)(n > 0 ? n : 1) * sizeof *fr);
    double *A = NULL, *s = NULL, *vt = NULL, *sup = NULL, *Z = NULL, *basis = NULL;
    int *cand = NULL;
    gd_status st = GD_OK;
    if (!fr) goto oom;
    for (int i = 0; i < n; i++)
        if (!held[i]) fr[nf++] = i;
    if (nf == 0) goto out;
    A = malloc((size_t)nf * nf * sizeof *A);
    s = malloc((size_t)nf * sizeof *s);
    if (!A || !s) goto oom;
    for (int b = 0; b < nf; b++)
        for (int a = 0; a < nf; a++) {
            double kaa = K[fr[a] + (size_t)fr[a] * n], kbb = K[fr[b] + (size_t)fr[b] * n];
            double da = kaa > 0 ? 1 / sqrt(kaa) : 1, db = kbb > 0 ? 1 / sqrt(kbb) : 1;
            A[a + (size_t)b * nf] = da * K[fr[a] + (size_t)fr[b] * n] * db;
        }
    /* symmetric (no cross-coupled bearing): the eigenvectors of the smallest |lambda|,
       by dsyevd (several times faster than the SVD); otherwise the SVD */
    int sym = 1;
    for (int b = 0; b < nf && sym; b++)
        for (int a = b + 1; a < nf; a++)
            if (fabs(A[a + (size_t)b * nf] - A[b + (size_t)a * nf]) > 1e-13) {
                sym = 0;
                break;
            }
    int r = 0;
    double tol;
    if (sym) {
        /* ascending eigenvalues, the eigenvectors as columns of A */
        if (LAPACKE_dsyevd(LAPACK_COL_MAJOR, 'V', 'L', nf, A, nf, s) != 0) goto numeric;
        tol = 1e-10 * fmax(fabs(s[0]), fabs(s[nf - 1]));
    } else {
        /* descending singular values, the right vectors as rows of vt */
        vt = malloc((size_t)nf * nf * sizeof *vt);
        sup = malloc((size_t)nf * sizeof *sup);
        if (!vt || !sup) goto oom;
        if (LAPACKE_dgesvd(LAPACK_COL_MAJOR, 'N', 'A', nf, nf, A, nf, s, NULL, 1, vt, nf, sup))
            goto numeric;
        tol = 1e-10 * s[0];
    }
    for (int i = 0; i < nf; i++)
        if (fabs(s[i]) <= tol) r++;
    if (r == 0) goto out;
    /* the null vectors (scaled coordinates), as columns */
    if (!(Z = malloc((size_t)nf * r * sizeof *Z))) goto oom;
    double zmax = 0, nt = 0;
    int nnull = 0;
    for (int j = 0; j < nf; j++) {
        if (!(fabs(s[j]) <= tol)) continue;
        for (int i = 0; i < nf; i++) {
            double v = sym ? A[i + (size_t)j * nf] : vt[j + (size_t)i * nf];
            Z[i + (size_t)nnull * nf] = v;
            zmax = fmax(zmax, fabs(v));
            if (!train_dof(sys, fr[i])) nt = fmax(nt, fabs(v));
        }
        nnull++;
    }
    if (nt > 1e-6 * zmax) {
        st = name_free_motion(sys, fr, nf, Z, r, err);
        goto out;
    }
    /* one torsion DOF per free train: rows of Z taken greedily in order of preference
       while they add rank (Gram-Schmidt against the rows taken) */
    int *where = malloc((size_t)n * sizeof *where);
    cand = malloc((size_t)(m->nnodes + m->nshafts + 2) * sizeof *cand);
    basis = calloc((size_t)r * r, sizeof *basis);
    if (!where || !cand || !basis) {
        free(where);
        goto oom;
    }
    for (int i = 0; i < n; i++)
        where[i] = -1;
    for (int i = 0; i < nf; i++)
        where[fr[i]] = i; /* position among the free DOFs, -1 */
    int nc = candidates(m, opt, cand), taken = 0;
    for (int c = 0; c < nc && taken < r; c++) {
        if (planet_node(m, cand[c]) && cand[c] != opt->hold_node) continue;
        int dof = gd_system_dof(sys, cand[c], GD_RZ);
        if (dof < 0 || where[dof] < 0 || held[dof]) continue;
        double row[64], nrm0 = 0, nrm = 0;
        if (r > 64) break;
        for (int j = 0; j < r; j++) {
            row[j] = Z[where[dof] + (size_t)j * nf];
            nrm0 += row[j] * row[j];
        }
        if (!(sqrt(nrm0) > 1e-8 * zmax)) continue;
        for (int t = 0; t < taken; t++) {
            double dot = 0;
            for (int j = 0; j < r; j++)
                dot += row[j] * basis[j + (size_t)t * r];
            for (int j = 0; j < r; j++)
                row[j] -= dot * basis[j + (size_t)t * r];
        }
        for (int j = 0; j < r; j++)
            nrm += row[j] * row[j];
        if (!(sqrt(nrm) > 1e-6 * sqrt(nrm0))) continue;
        for (int j = 0; j < r; j++)
            basis[j + (size_t)taken * r] = row[j] / sqrt(nrm);
        held[dof] = GD_ST_TORQUE_HOLD;
        taken++;
    }
    free(where);
    if (taken < r)
        st = gd_error_set(err, GD_ENUMERIC, m->file, 0, 0, "", "prescribe the torsion of a node",
                          "could not choose torsion DOFs to hold the %d free gear train%s", r,
                          r == 1 ? "" : "s");
    goto out;
numeric:
    st = gd_error_set(err, GD_ENUMERIC, "", 0, 0, "", "", "eigen/SVD of the stiffness failed");
    goto out;
oom:
    st = gd_error_set(err, GD_ENOMEM, "", 0, 0, "", "", "out of memory");
out:
    free(fr);
    free(A);
    free(s);
    free(vt);
    free(sup);
    free(Z);
    free(basis);
    free(cand);
    return st;
}
