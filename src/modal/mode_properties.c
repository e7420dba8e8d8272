/* Per-mode properties: whirl direction from the forward/backward circular components
 * of each node's x/y orbit, modal strain energy shares by motion type and by
 * component, the dominant ones, and the normalisation of a complex shape. */
#include <complex.h>
#include <lapacke.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "modal/modal_impl.h"

#define PI 3.14159265358979323846

const char *const gd_whirl_names[4] = {"none", "forward", "backward", "mixed"};

gd_motion gd_dof_motion(gd_dof d)
{
    return gd_system_dof_motion(d);
}

/* |z| without hypot's care for overflow (the shapes are normalised to a largest entry
 * of 1): the whirl's four moduli per node are a visible part of a Campbell sweep */
static double mag(double complex z)
{
    return sqrt(creal(z) * creal(z) + cimag(z) * cimag(z));
}

/* M_ii (0 for a massless or absent DOF) */
static double diag_mass(const gd_system *sys, int i)
{
    if (i < 0) return 0.0;
    for (int k = sys->M.colptr[i]; k < sys->M.colptr[i + 1]; k++)
        if (sys->M.rowind[k] == i) return sys->M.values[k];
    return 0.0;
}

/* The orbits a mode's whirl is read from: at every node, that of the centre (x, y) and
 * that of the tilt (rx, ry), whose vector turns the same way as the axis' slope
 * (dx/dz, dy/dz) = (ry, -rx). A tilt mode of a disk on a stiff centre (a rotor's
 * gyroscopic pair) moves its centre by rounding only: read from the centre alone it
 * was "none" (dense: exactly zero) or "mixed" (sparse: noise turning either way). The
 * orbits are weighed by their kinetic energy (diagonal mass and inertia), so metres
 * and radians compare and a rounding-sized orbit is left out. */
typedef struct orbit {
    double complex a, b; /* the x and y (or rx and ry) amplitudes */
    double weight;       /* kinetic-energy weight: mass times |a|^2 + |b|^2 */
    int node;
} orbit;

static int node_orbit(const gd_system *sys, int node, int tilt, int unit, const double *re,
                      const double *im, orbit *o)
{
    int ix = gd_system_dof(sys, node, tilt ? GD_RX : GD_X),
        iy = gd_system_dof(sys, node, tilt ? GD_RY : GD_Y);
    if (ix < 0 || iy < 0) return 0;
    o->a = re[ix] + I * im[ix];
    o->b = re[iy] + I * im[iy];
    double m = unit ? 1.0 : 0.5 * (diag_mass(sys, ix) + diag_mass(sys, iy));
    o->weight = m * (creal(o->a * conj(o->a)) + creal(o->b * conj(o->b)));
    o->node = node;
    return 1;
}

static gd_whirl mode_whirl(const gd_system *sys, const double *re, const double *im)
{
    const gd_model *m = sys->model;
    double maxw = 0;
    int unit = 0; /* no moving node has mass (massless x, y and tilts): by amplitude */
    for (; unit < 2 && !(maxw > 0); unit++)
        for (int node = 0; node < m->nnodes; node++)
            for (int tilt = 0; tilt < 2; tilt++) {
                orbit o;
                if (node_orbit(sys, node, tilt, unit, re, im, &o) && o.weight > maxw)
                    maxw = o.weight;
            }
    unit--;
    if (!(maxw > 0)) return GD_WHIRL_NONE;
    int fwd = 0, bwd = 0;
    for (int node = 0; node < m->nnodes; node++)
        for (int tilt = 0; tilt < 2; tilt++) {
            orbit o;
            /* 1e-6 of the largest energy: 1e-3 of its amplitude, as before by amplitude */
            if (!node_orbit(sys, node, tilt, unit, re, im, &o) || o.weight < 1e-6 * maxw) continue;
            double complex X = o.a, Y = o.b;
            /* x + i y = (X + iY)/2 e^{iwt} + conj(X - iY)/2 e^{-iwt}: forward and backward
             * circular components ([Kumar2011] Eqs. 2.5-2.8) */
            double rf = mag(X + I * Y), rb = mag(X - I * Y);
            if (m->shafts[m->nodes[node].shaft].speed_ratio < 0) {
                double t = rf;
                rf = rb;
                rb = t;
            }
            double ell = (rf - rb) / (rf + rb);
            if (ell > 1e-3) fwd = 1;
            if (ell < -1e-3) bwd = 1;
        }
    if (fwd && bwd) return GD_WHIRL_MIXED;
    if (fwd) return GD_WHIRL_FORWARD;
    if (bwd) return GD_WHIRL_BACKWARD;
    return GD_WHIRL_NONE;
}

/* No lateral motion to speak of: no whirl. A gearbox's torsional mode carries a few per
 * cent of lateral strain energy through its meshes, whose small orbits turn either way;
 * called "backward" it was drawn as a whirling mode in Campbell (issue 35: a
 * 97 %-torsional mode). An elastic mode with less than GD_WHIRL_MIN_LATERAL of its strain
 * energy in lateral and tilt motion (its shares set: a nonzero total) is not a whirling
 * mode. */
static int whirl_suppressed(const gd_mode *md)
{
    return !md->rigid_body &&
           md->energy_share[GD_MOTION_LATERAL] + md->energy_share[GD_MOTION_TILT] <
               GD_WHIRL_MIN_LATERAL;
}

void gd_mode_set_lambda(gd_mode *md, double lr, double li)
{
    double mag = hypot(lr, li);
    md->lambda_re = lr;
    md->lambda_im = li;
    md->omega_n = mag;
    md->omega_d = li;
    md->frequency_hz = mag / (2 * PI);
    md->damping_ratio = -lr / mag;
    md->overdamped = li == 0;
    md->unstable = lr > 1e-8 * mag;
    double z = md->damping_ratio;
    md->log_decrement = li > 0 && fabs(z) < 1 ? 2 * PI * z / sqrt(1 - z * z) : NAN;
}

void gd_mode_finish(const gd_system *sys, double speed, gd_mode *md, const double *re,
                    const double *im, double *comp_share)
{
    gd_mode_finish_laws(sys, speed, NULL, md, re, im, comp_share);
}

void gd_mode_finish_laws(const gd_system *sys, double speed, const double *law_K, gd_mode *md,
                         const double *re, const double *im, double *comp_share)
{
    int nc = sys->ncomponents;
    double by_motion[GD_NMOTIONS];
    double *by_comp = comp_share;
    double total =
        gd_system_strain_energy_laws(sys, speed, law_K, re, im, by_motion, by_comp, NULL);
    md->dominant_motion = GD_MOTION_LATERAL;
    md->dominant_component = -1;
    /* a divergent mode (negative stiffness) has negative strain energy: its shares are
     * fractions of that negative total like any other */
    if (md->rigid_body || total == 0 || !isfinite(total)) {
        for (int k = 0; k < GD_NMOTIONS; k++)
            md->energy_share[k] = 0;
        for (int c = 0; c < nc; c++)
            by_comp[c] = 0;
        /* a rigid mode is named by how it moves: the largest kinetic DOF type */
        double ke[GD_NMOTIONS] = {0};
        for (int i = 0; i < sys->ndof; i++) {
            double a = re[i] * re[i] + (im ? im[i] * im[i] : 0);
            gd_motion mo = gd_dof_motion(sys->dof_type[i]);
            for (int k = sys->M.colptr[i]; k < sys->M.colptr[i + 1]; k++)
                if (sys->M.rowind[k] == i) ke[mo] += sys->M.values[k] * a;
        }
        int best = 0;
        for (int k = 1; k < GD_NMOTIONS; k++)
            if (ke[k] > ke[best]) best = k;
        md->dominant_motion = (gd_motion)best;
    } else {
        int best = 0;
        for (int k = 0; k < GD_NMOTIONS; k++) {
            /* + 0.0: no -0 shares when the total is negative */
            md->energy_share[k] = by_motion[k] / total + 0.0;
            if (md->energy_share[k] > md->energy_share[best]) best = k;
        }
        md->dominant_motion = (gd_motion)best;
        int bc = 0;
        for (int c = 0; c < nc; c++) {
            by_comp[c] = by_comp[c] / total + 0.0;
            if (by_comp[c] > by_comp[bc]) bc = c;
        }
        /* no component holds strain energy (it is all in elements outside them): no
         * label rather than the first component's */
        md->dominant_component = nc > 0 && by_comp[bc] > 1e-9 ? bc : -1;
    }
    /* whirl is relative to the spin; at rest there is no direction to compare with */
    md->whirl = speed != 0.0 ? mode_whirl(sys, re, im) : GD_WHIRL_NONE;
    if (total != 0 && whirl_suppressed(md)) md->whirl = GD_WHIRL_NONE;
}

/* The whirl of a repeated eigenvalue's modes (an axisymmetric rotor's x/y pair where
 * nothing splits it: no gyroscopic term, or --undamped at speed). Any basis of the pair's
 * space is an eigenbasis, and solvers return different ones (LAPACK two straight-line
 * orbits, "none"; Krylov-Schur complex mixtures, "forward" or "backward" or "mixed"), so a
 * label read from the returned vectors depended on the solver. The space itself does
 * not: the combinations extremal in forward share, the generalized eigenvectors of
 * F c = mu S c with F the kinetic-energy-weighted forward circular components of every
 * centre and tilt orbit and S forward plus backward (the pair turned to circular orbits,
 * as the directional modes' clusters in directional.c), are the same whatever basis.
 * The cluster's modes are labelled by those combinations, most forward first (an
 * isotropic pair: mode j forward, mode j + 1 backward, by either solver); the shapes are
 * left as solved. Clusters: consecutive elastic modes within 1e-6 of each other's
 * eigenvalue, at most CLUSTER_MAX. */
enum { CLUSTER_MAX = 8 };

static double orbit_weight(const gd_system *sys, int ix, int iy, int unit)
{
    return unit ? 1.0 : 0.5 * (diag_mass(sys, ix) + diag_mass(sys, iy));
}

static void cluster_whirl(const gd_system *sys, gd_modal_result *r, int j0, int g, double *wre,
                          double *wim)
{
    const gd_model *m = sys->model;
    const int n = r->ndof;
    double complex F[CLUSTER_MAX * CLUSTER_MAX] = {0}, S[CLUSTER_MAX * CLUSTER_MAX] = {0};
    double mu[CLUSTER_MAX];
    int unit = 1; /* by mass where any centre or tilt has one, as mode_whirl */
    for (int node = 0; node < m->nnodes && unit; node++)
        for (int tilt = 0; tilt < 2 && unit; tilt++) {
            int ix = gd_system_dof(sys, node, tilt ? GD_RX : GD_X),
                iy = gd_system_dof(sys, node, tilt ? GD_RY : GD_Y);
            if (ix >= 0 && iy >= 0 && orbit_weight(sys, ix, iy, 0) > 0) unit = 0;
        }
    for (int node = 0; node < m->nnodes; node++)
        for (int tilt = 0; tilt < 2; tilt++) {
            int ix = gd_system_dof(sys, node, tilt ? GD_RX : GD_X),
                iy = gd_system_dof(sys, node, tilt ? GD_RY : GD_Y);
            if (ix < 0 || iy < 0) continue;
            double w = orbit_weight(sys, ix, iy, unit);
            double sg = m->shafts[m->nodes[node].shaft].speed_ratio < 0 ? -1.0 : 1.0;
            for (int a = 0; a < g; a++) {
                size_t oa = (size_t)(j0 + a) * n;
                double complex xa = r->shape_re[oa + ix] + I * r->shape_im[oa + ix],
                               ya = r->shape_re[oa + iy] + I * r->shape_im[oa + iy];
                double complex fa = xa + sg * I * ya, ba = xa - sg * I * ya;
                for (int b = 0; b < g; b++) {
                    size_t ob = (size_t)(j0 + b) * n;
                    double complex xb = r->shape_re[ob + ix] + I * r->shape_im[ob + ix],
                                   yb = r->shape_re[ob + iy] + I * r->shape_im[ob + iy];
                    double complex fb = xb + sg * I * yb, bb = xb - sg * I * yb;
                    F[a + b * g] += w * conj(fa) * fb;
                    S[a + b * g] += w * (conj(fa) * fb + conj(ba) * bb);
                }
            }
        }
    /* S singular (no orbit in the space): the labels stay as they are */
    if (LAPACKE_zhegv(LAPACK_COL_MAJOR, 1, 'V', 'U', g, F, g, S, g, mu) != 0) return;
    for (int k = 0; k < g; k++) {
        /* zhegv sorts mu ascending: the most forward combination is the last */
        const double complex *c = F + (size_t)(g - 1 - k) * g;
        for (int i = 0; i < n; i++) {
            double complex v = 0;
            for (int b = 0; b < g; b++) {
                size_t ob = (size_t)(j0 + b) * n;
                v += c[b] * (r->shape_re[ob + i] + I * r->shape_im[ob + i]);
            }
            wre[(size_t)k * n + i] = creal(v);
            wim[(size_t)k * n + i] = cimag(v);
        }
    }
    for (int k = 0; k < g; k++) {
        gd_mode *md = &r->modes[j0 + k];
        md->whirl = whirl_suppressed(md)
                        ? GD_WHIRL_NONE
                        : mode_whirl(sys, wre + (size_t)k * n, wim + (size_t)k * n);
    }
}

static gd_status pair_whirl(const gd_system *sys, gd_modal_result *r)
{
    if (r->speed == 0.0 || !r->shape_re || !r->shape_im || r->ndof != sys->ndof) return GD_OK;
    double *w = NULL;
    for (int j = 0; j < r->nmodes;) {
        const gd_mode *a = &r->modes[j];
        int g = 1;
        while (!a->rigid_body && j + g < r->nmodes && g < CLUSTER_MAX &&
               !r->modes[j + g].rigid_body &&
               cabs((r->modes[j + g].lambda_re - a->lambda_re) +
                    I * (r->modes[j + g].lambda_im - a->lambda_im)) <= 1e-6 * a->omega_n)
            g++;
        if (g > 1) {
            if (!w && !(w = malloc((size_t)2 * CLUSTER_MAX * r->ndof * sizeof *w)))
                return GD_ENOMEM;
            cluster_whirl(sys, r, j, g, w, w + (size_t)CLUSTER_MAX * r->ndof);
        }
        j += g;
    }
    free(w);
    return GD_OK;
}

gd_status gd_modal_energies_laws(const gd_system *sys, gd_modal_result *r, const double *law_state)
{
    if (r->ndof != sys->ndof) return GD_OK;
    if (sys->nlaws) {
        double *Kb = malloc((size_t)sys->law_block * 2 * sizeof *Kb);
        if (!Kb) return GD_ENOMEM;
        gd_system_law_blocks_at(sys, r->speed, law_state, Kb, Kb + sys->law_block);
        for (int j = 0; j < r->nmodes; j++) {
            if (r->modes[j].rigid_body) continue;
            size_t n = (size_t)r->ndof * j;
            gd_mode_finish_laws(sys, r->speed, Kb, &r->modes[j], r->shape_re + n, r->shape_im + n,
                                r->energy_by_component + (size_t)j * sys->ncomponents);
        }
        free(Kb);
    }
    /* the labels of repeated eigenvalues from their space, not the solver's basis */
    return pair_whirl(sys, r);
}

/* Scales a complex vector so its largest entry is 1 + 0i; returns the divisor. */
double complex gd_normalise_max(double *re, double *im, int n)
{
    int best = 0;
    double bm = -1;
    for (int i = 0; i < n; i++) {
        double a = re[i] * re[i] + im[i] * im[i];
        if (a > bm * (1 + 1e-12)) {
            bm = a;
            best = i;
        }
    }
    double complex s = re[best] + I * im[best];
    if (cabs(s) == 0) return 1.0;
    /* times 1/s = conj(s) / |s|^2: one division instead of one per entry */
    double ir = re[best] / bm, ii = -im[best] / bm;
    for (int i = 0; i < n; i++) {
        double zr = re[i] * ir - im[i] * ii, zi = re[i] * ii + im[i] * ir;
        re[i] = zr;
        im[i] = zi;
    }
    re[best] = 1.0;
    im[best] = 0.0;
    return s;
}
