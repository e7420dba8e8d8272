/* The value of one record at time t from the full displacements and velocities: a DOF,
 * an angle or speed with the nominal rotation added, a mesh's force, deflection, state or
 * stiffness, a law's record. Shared by every integrator (run.c, gen_alpha.c, linear.c). */
#include "transient/transient_impl.h"

/* Record value r at time t with full q, v. */
double gd_tr_record_value(gd_transient *tr, const gd_tr_record *rec, double t, const double *q,
                          const double *v)
{
    const gd_model *model = tr->sys->model;
    int i = rec->index;
    if (tr->prof && (rec->kind == GD_REC_ANGLE || rec->kind == GD_REC_SPEED ||
                     rec->kind == GD_REC_SPEED_RATIO)) {
        /* run-up: the nominal angle ratio phi(t) and speed ratio W(t) (not reduced) */
        double phi, w;
        gd_tr_profile_eval(tr->prof, tr->prof_cum, t, &phi, &w, NULL);
        if (rec->kind == GD_REC_ANGLE) return tr->ratio[i] * phi + q[i];
        if (rec->kind == GD_REC_SPEED) return tr->ratio[i] * w + v[i];
        int j = rec->index2;
        double den = tr->ratio[j] * w + v[j];
        return den != 0.0 ? (tr->ratio[i] * w + v[i]) / den : 0.0;
    }
    switch (rec->kind) {
    case GD_REC_DISP:
        return gd_tr_full_value(tr, i, q);
    case GD_REC_VEL:
        return gd_tr_full_value(tr, i, v);
    case GD_REC_ANGLE:
        return gd_tr_full_rate(tr, i) * t + gd_tr_full_value(tr, i, q);
    case GD_REC_SPEED:
        return gd_tr_full_rate(tr, i) + gd_tr_full_value(tr, i, v);
    case GD_REC_SPEED_RATIO: {
        int j = rec->index2;
        double den = gd_tr_full_rate(tr, j) + gd_tr_full_value(tr, j, v);
        return den != 0.0 ? (gd_tr_full_rate(tr, i) + gd_tr_full_value(tr, i, v)) / den : 0.0;
    }
    case GD_REC_MESH_FORCE:
    case GD_REC_MESH_DEFLECTION:
    case GD_REC_MESH_STATE:
    case GD_REC_MESH_STIFFNESS: {
        int nl = tr->nl_of_mesh[i];
        if (nl >= 0) { /* the mesh law's records, in the same order */
            const gd_law *L = &tr->law[nl];
            gd_law_point x;
            gd_tr_law_point(L, gd_tr_law_t(tr, nl, t), q, v, tr->lq, tr->lv, &x);
            return L->type->record(L, (int)(rec->kind - GD_REC_MESH_FORCE), &x);
        }
        /* a mesh without a law: its assembled linear force */
        const gd_mesh_vector *a = &tr->model_a[i];
        double d = 0.0, dd = 0.0;
        for (int j = 0; j < a->n; j++) {
            d += a->a[j] * q[a->dof[j]];
            dd += a->a[j] * v[a->dof[j]];
        }
        double k = model->meshes[i].stiffness;
        if (rec->kind == GD_REC_MESH_FORCE) return k * d + model->meshes[i].damping * dd;
        if (rec->kind == GD_REC_MESH_DEFLECTION) return d;
        if (rec->kind == GD_REC_MESH_STATE) return (double)GD_CONTACT_DRIVE;
        return k;
    }
    case GD_REC_SFD_FX:
    case GD_REC_SFD_FY:
    case GD_REC_SFD_ECCENTRICITY:
    case GD_REC_LAW: {
        /* a damper's records are its law's fx, fy, ecc */
        int which = rec->kind == GD_REC_LAW ? rec->index2 : (int)(rec->kind - GD_REC_SFD_FX);
        const int li = rec->kind == GD_REC_LAW ? tr->law_spec0 + i : tr->nmesh + i;
        const gd_law *L = &tr->law[li];
        gd_law_point x;
        gd_tr_law_point(L, gd_tr_law_t(tr, li, t), q, v, tr->lq, tr->lv, &x);
        return L->type->record(L, which, &x);
    }
    }
    return 0.0;
}
