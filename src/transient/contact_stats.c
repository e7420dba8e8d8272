/* Contact statistics of the backlash meshes: time in drive, coast and separated contact
 * from `from` on, contact losses and impacts, counted at each change of contact state
 * (the mode of a mesh law, law[0 .. nmesh - 1]; another law with switches only changes
 * its mode). Shared by CVODE (run.c) and generalized-alpha (gen_alpha.c). */
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

void gd_tr_change_state(gd_transient *tr, int i, gd_contact ns, double t, double from,
                        gd_tr_contact_stats *st, gd_tr_contact_track *track)
{
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
    }
    track[i].since = t;
}
