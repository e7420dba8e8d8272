/* Contact statistics of the backlash meshes: time in drive, coast and separated contact
 * from `from` on, contact losses and impacts, counted at each change of contact state
 * (the mode of a mesh law, law[0 .. nmesh - 1]; another law with switches only changes
 * its mode), and the log of those changes with the flanks' approach speed (the rattle
 * metrics of src/signal/rattle.c). Shared by CVODE (run.c) and generalized-alpha
 * (gen_alpha.c). */
#include <stdlib.h>
#include <string.h>

#include "transient/transient_impl.h"

/* Adds the time [t0, t1] (clipped to t >= from) to the time in contact state `state`. */
void gd_tr_contact_account(gd_tr_contact_stats *cs_, gd_contact state, double t0, double t1,
                           double from)
{
    if (t0 < from) t0 = from;
    if (t1 <= t0) return;
    if (state == GD_CONTACT_SEPARATED)
        cs_->separated_time += t1 - t0;
    else if (state == GD_CONTACT_COAST)
        cs_->coast_time += t1 - t0;
    else
        cs_->drive_time += t1 - t0;
}

/* The rate of switch 0 (d_e - b for a mesh: d_e') of law L along the motion in tr->q,
 * tr->v at t: a central difference over +-h in t and q (q + h q'), exact for the linear
 * d = a . q and O(h^2) for the transmission error read at the driver's angle. */
static double switch_rate(gd_transient *tr, const gd_law *L, double t)
{
    gd_law_point x;
    gd_tr_law_here(tr, L, t, &x);
    double q[GD_LAW_MAX_DOFS], g[2][GD_LAW_MAX_SWITCHES];
    const double h = 1e-6;
    for (int s = 0; s < 2; s++) {
        double sg = s ? -1.0 : 1.0;
        for (int j = 0; j < L->ndofs; j++)
            q[j] = x.q[j] + sg * h * x.v[j];
        gd_law_point xs = {t + sg * h, q, x.v};
        L->type->switches(L, &xs, g[s]);
    }
    return (g[0][0] - g[1][0]) / (2.0 * h);
}

static void log_event(gd_transient *tr, int i, gd_contact from_state, gd_contact to_state, double t,
                      gd_transient_result *res)
{
    int n = res->ncontact_events;
    /* capacity: 16, then doubled each time the count reaches a power of two */
    if (n == 0 || (n >= 16 && (n & (n - 1)) == 0)) {
        size_t cap = n == 0 ? 16 : 2 * (size_t)n;
        gd_tr_contact_event *e = realloc(res->contact_events, cap * sizeof *e);
        if (!e) {
            res->contact_events_lost++;
            return;
        }
        res->contact_events = e;
    }
    gd_tr_contact_event *e = &res->contact_events[n];
    e->t = t;
    e->mesh = i;
    e->from = (int)from_state;
    e->to = (int)to_state;
    e->velocity = switch_rate(tr, &tr->law[i], t);
    res->ncontact_events = n + 1;
}

void gd_tr_change_state(gd_transient *tr, int i, gd_contact ns, double t, double from,
                        gd_transient_result *res, gd_tr_contact_track *track)
{
    gd_tr_contact_stats *st = res->contacts;
    gd_law *L = &tr->law[i];
    gd_contact cur = (gd_contact)L->mode;
    if (ns == cur) return;
    L->mode = ns;
    if (i >= tr->nmesh) return;
    gd_tr_contact_account(&st[i], cur, track[i].since, t, from);
    if (t >= from) {
        if (cur == GD_CONTACT_DRIVE && ns != GD_CONTACT_DRIVE) st[i].contact_losses++;
        if (ns == GD_CONTACT_COAST) st[i].coast_impacts++;
        if (ns == GD_CONTACT_DRIVE) st[i].drive_impacts++;
        log_event(tr, i, cur, ns, t, res);
    }
    track[i].since = t;
}
