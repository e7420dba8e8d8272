/* Per-mode properties: whirl direction from the forward/backward circular components
 * of each node's x/y orbit, modal strain energy shares by motion type and by
 * component, the dominant ones, and the normalisation of a complex shape. */
#include <complex.h>
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
    /* no lateral motion to speak of: no whirl. A gearbox's torsional mode carries a few
     * per cent of lateral strain energy through its meshes, whose small orbits turn
     * either way; called "backward" it was drawn as a whirling mode in Campbell (issue
     * 35: a 97 %-torsional mode). A mode with less than GD_WHIRL_MIN_LATERAL of its
     * strain energy in lateral and tilt motion is not a whirling mode. */
    if (!md->rigid_body && total != 0 &&
        md->energy_share[GD_MOTION_LATERAL] + md->energy_share[GD_MOTION_TILT] <
            GD_WHIRL_MIN_LATERAL)
        md->whirl = GD_WHIRL_NONE;
}

gd_status gd_modal_energies_laws(const gd_system *sys, gd_modal_result *r, const double *law_state)
{
    if (!sys->nlaws || r->ndof != sys->ndof) return GD_OK;
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
    return GD_OK;
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
