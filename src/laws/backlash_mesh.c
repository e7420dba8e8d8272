/* The gear mesh as a registry law (gd_law_backlash_mesh): contact on the drive and the
 * coast flank with backlash, [Benini2004] Eqs. 2-4 (as cleaned up in DESIGN.md; the flank
 * forces are gd_backlash_force of backlash.c), the time-varying mesh stiffness k(theta)
 * ([Benini2004] Eq. 5, or a table from the tooth geometry) and the static transmission
 * error e(theta) read at the driver's angle, the mesh damping c = c0 + c_k k(theta)
 * ([Benini2004] Sec. 3.2). The deflection along the line of action is d = a . q with the
 * mesh vector a of the coupling level ([Kumar2011] for the lateral-torsional one).
 *
 * The linear part k_lin a a^T, c_lin a a^T is assembled in the system's K and C
 * (GD_LAW_ASSEMBLED): the law adds -a (F - k_lin d - c_lin d'). Its modes are the contact
 * states (gd_contact); the switches are d_e - b and d_e + b (d_e = d - e(theta)), located
 * as events by the integrators. The Jacobian has two rank-one terms: a a^T (the flank
 * stiffness and damping less the assembled ones) and a e_drv^T (the driver angle through
 * k(theta) and e(theta)). */
#include <math.h>
#include <stdio.h>

#include "geardyn/law_type.h"
#include "geardyn/laws.h"

static const gd_mesh_law_data *data_of(const gd_law *law)
{
    return (const gd_mesh_law_data *)law->data;
}

/* gd_mesh_law_eval, static so the compiler specialises it per call (most pass NULL). */
static inline __attribute__((always_inline)) double
eval(const gd_law *law, int state_in, double t, const double *q, const double *v, double *d_out,
     double *dd_out, double *k_out, double *de_out, double grad[4])
{
    const gd_mesh_law_data *m = data_of(law);
    gd_contact state = (gd_contact)state_in;
    double d = 0.0, dd = 0.0;
    for (int j = 0; j < m->na; j++) {
        d += m->a[j] * q[j];
        dd += m->a[j] * v[j];
    }
    if (d_out) *d_out = d;
    if (dd_out) *dd_out = dd;
    double k = m->stiffness, dk = 0.0, e1 = 0.0, e2 = 0.0, thd = 0.0;
    if (m->tvms || m->ste) {
        double qd = m->drv >= 0 ? q[m->drv] : 0.0;
        double vd = m->drv >= 0 ? v[m->drv] : 0.0;
        double th, wd;
        if (m->nominal) { /* run-up: the driver's nominal angle ratio phi(t) */
            double phi, w;
            m->nominal(m->nominal_ctx, t, &phi, &w);
            th = m->angle_offset + m->sense * (m->drv_ratio * phi + qd);
            wd = m->drv_ratio * w;
        } else {
            th = m->angle_offset + m->sense * (m->drv_rate * t + qd);
            wd = m->drv_rate;
        }
        thd = m->sense * (wd + vd);
        if (m->tvms) k = gd_table_eval(m->tvms, th, &dk, NULL);
        if (m->ste) {
            double e = gd_table_eval(m->ste, th, &e1, &e2);
            d -= e;
            dd -= e1 * thd;
        }
    }
    if (k_out) *k_out = k;
    if (de_out) *de_out = d;
    double c = m->damping + m->damping_per_k * k;
    gd_backlash_params p;
    p.b = m->backlash ? m->gap : 0.0;
    p.k_drive = k;
    p.k_coast = m->coast_scale * k;
    p.c_drive = c;
    p.c_coast = m->damping + m->damping_per_k * p.k_coast;
    p.c_free = m->damping_free;
    gd_contact st = m->backlash ? state : GD_CONTACT_DRIVE;
    /* contact homotopy (frequency-domain starts only): blend with the drive flank */
    double h = st != GD_CONTACT_DRIVE ? law->hold : 0.0;
    if (grad) {
        /* chain rule through the state's k(theta), c(theta) and the STE e(theta) */
        for (int b = 0; b < 4; b++)
            grad[b] = 0.0;
        for (int pass = 0; pass < (h > 0 ? 2 : 1); pass++) {
            gd_contact sp = pass ? GD_CONTACT_DRIVE : st;
            double wgt = pass ? h : 1.0 - h, g[4];
            gd_backlash_force_grad(&p, sp, d, dd, g);
            double dks = sp == GD_CONTACT_COAST ? m->coast_scale * dk : dk;
            double dcs = sp == GD_CONTACT_SEPARATED ? 0.0 : m->damping_per_k * dks;
            double dth = g[2] * dks + g[3] * dcs - g[0] * e1 - g[1] * e2 * thd;
            grad[0] += wgt * g[0];
            grad[1] += wgt * g[1];
            grad[2] += m->drv >= 0 ? wgt * m->sense * dth : 0.0;
            grad[3] += m->drv >= 0 ? -wgt * m->sense * g[1] * e1 : 0.0;
        }
    }
    if (!m->backlash) return k * d + c * dd;
    double F = gd_backlash_force(&p, state, d, dd);
    if (h > 0) F = (1.0 - h) * F + h * gd_backlash_force(&p, GD_CONTACT_DRIVE, d, dd);
    return F;
}

double gd_mesh_law_eval(const gd_law *law, int state, double t, const double *q, const double *v,
                        double *d, double *dd, double *k, double *de, double grad[4])
{
    return eval(law, state, t, q, v, d, dd, k, de, grad);
}

static unsigned mesh_flags(const gd_law *law)
{
    const gd_mesh_law_data *m = data_of(law);
    unsigned f = GD_LAW_ASSEMBLED;
    int nonlin = m->backlash || m->tvms || m->ste;
    if (!nonlin) f |= GD_LAW_LINEAR;
    if (!m->backlash) f |= GD_LAW_SMOOTH; /* no switches */
    /* the tables are read at the driver's angle: affine within a mode when it is
     * prescribed (or absent) */
    if (!((m->tvms || m->ste) && m->drv >= 0 && !m->angle_fixed)) f |= GD_LAW_PIECEWISE;
    if (nonlin || m->stiffness != m->k_lin ||
        m->damping + m->damping_per_k * m->stiffness != m->c_lin)
        f |= GD_LAW_TANGENT;
    return f;
}

/* term 0: u = w = a; term 1: u = a, w = e_drv */
static void mesh_term(const gd_law *law, int k, double *u, double *w)
{
    const gd_mesh_law_data *m = data_of(law);
    for (int j = 0; j < m->na; j++) {
        u[j] = m->a[j];
        if (k == 0) w[j] = m->a[j];
    }
    if (k == 1 && m->drv >= 0) w[m->drv] = 1.0;
}

static void mesh_force(const gd_law *law, const gd_law_point *x, double *f, double *jq, double *jv)
{
    const gd_mesh_law_data *m = data_of(law);
    double d, dd, gr[4];
    if (!jq && !jv) { /* the integrators' right-hand side */
        double F = eval(law, law->mode, x->t, x->q, x->v, &d, &dd, NULL, NULL, NULL);
        double g = F - m->k_lin * d - m->c_lin * dd;
        for (int j = 0; j < m->na; j++)
            f[j] -= m->a[j] * g;
        return;
    }
    double F = eval(law, law->mode, x->t, x->q, x->v, &d, &dd, NULL, NULL, gr);
    double g = F - m->k_lin * d - m->c_lin * dd;
    for (int j = 0; j < m->na; j++)
        f[j] -= m->a[j] * g;
    /* f -= a (F - k_lin d - c_lin d') */
    if (jq) {
        jq[0] = -(gr[0] - m->k_lin);
        jq[1] = -gr[2];
    }
    if (jv) {
        jv[0] = -(gr[1] - m->c_lin);
        jv[1] = -gr[3];
    }
}

static int mesh_frequencies(const gd_law *law, double *w, int cap, char *msg, size_t cap_msg)
{
    const gd_mesh_law_data *m = data_of(law);
    const gd_table *t[2] = {m->tvms, m->ste};
    int n = 0;
    for (int k = 0; k < 2; k++) {
        if (!t[k]) continue;
        if (!(t[k]->period > 0)) {
            snprintf(msg, cap_msg, "a mesh stiffness or error table is not periodic");
            return -1;
        }
        if (n < cap) w[n++] = 2.0 * M_PI / t[k]->period * fabs(m->drv_rate);
    }
    return n;
}

static const gd_law_record mesh_records[] = {
    {"force", "N"}, {"deflection", "m"}, {"state", "-"}, {"stiffness", "N/m"}};

static double mesh_record(const gd_law *law, int k, const gd_law_point *x)
{
    double d, kk;
    double F = eval(law, law->mode, x->t, x->q, x->v, &d, NULL, &kk, NULL, NULL);
    switch (k) {
    case GD_MESH_REC_FORCE:
        return F;
    case GD_MESH_REC_DEFLECTION:
        return d;
    case GD_MESH_REC_STATE:
        return (double)(data_of(law)->backlash ? law->mode : GD_CONTACT_DRIVE);
    default:
        return kk;
    }
}

/* switch 0: d_e - b (the drive flank), switch 1: d_e + b (the coast flank) */
static void mesh_switches(const gd_law *law, const gd_law_point *x, double *g)
{
    const gd_mesh_law_data *m = data_of(law);
    double de;
    eval(law, law->mode, x->t, x->q, x->v, NULL, NULL, NULL, &de, NULL);
    g[0] = de - m->gap;
    g[1] = de + m->gap;
}

static int mesh_mode_at(const gd_law *law, const gd_law_point *x)
{
    const gd_mesh_law_data *m = data_of(law);
    if (!m->backlash) return GD_CONTACT_DRIVE;
    double de;
    eval(law, law->mode, x->t, x->q, x->v, NULL, NULL, NULL, &de, NULL);
    return gd_backlash_state(de, m->gap);
}

static int mesh_mode_after(const gd_law *law, int mode, const int *dir)
{
    (void)law;
    if (dir[1] < 0) return GD_CONTACT_COAST;
    if (dir[0] > 0) return GD_CONTACT_DRIVE;
    if (dir[0] < 0 || dir[1] > 0) return GD_CONTACT_SEPARATED;
    return mode;
}

/* d_e = +b when entering or leaving the drive flank, else d_e = -b */
static int mesh_switch_of(const gd_law *law, int from, int to)
{
    (void)law;
    return (to == GD_CONTACT_DRIVE || from == GD_CONTACT_DRIVE) ? 0 : 1;
}

static double mesh_switch_tol(const gd_law *law)
{
    return 1e-6 * data_of(law)->gap + 1e-15;
}

/* A static equilibrium holds each flank's law beyond its interval: a pulling force on
 * the drive flank moves the mesh to the coast flank and back. */
static int mesh_static_mode(const gd_law *law, const gd_law_point *x)
{
    double F = eval(law, law->mode, x->t, x->q, x->v, NULL, NULL, NULL, NULL, NULL);
    if (law->mode == GD_CONTACT_DRIVE && F < 0) return GD_CONTACT_COAST;
    if (law->mode == GD_CONTACT_COAST && F > 0) return GD_CONTACT_DRIVE;
    return law->mode;
}

const gd_law_type gd_law_backlash_mesh = {
    .name = "backlash_mesh",
    .summary = "gear mesh: TVMS, transmission error, backlash on drive and coast flanks",
    .flags = GD_LAW_ASSEMBLED,
    .instance_flags = mesh_flags,
    .var_dofs = 1,
    .nterms = 2,
    .term = mesh_term,
    .force = mesh_force,
    .frequencies = mesh_frequencies,
    .records = mesh_records,
    .nrecords = 4,
    .record = mesh_record,
    .nswitches = 2,
    .switches = mesh_switches,
    .mode_at = mesh_mode_at,
    .mode_after = mesh_mode_after,
    .switch_of = mesh_switch_of,
    .switch_tol = mesh_switch_tol,
    .static_mode = mesh_static_mode,
    .hold_mode = GD_CONTACT_DRIVE,
};
