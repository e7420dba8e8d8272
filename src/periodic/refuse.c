/* `--method auto` refuses (issue 33 item 6) a problem whose excitations have a common
 * period of many periods of the highest, which neither ordinary harmonic balance of that
 * period (its workspace at the H it would need over the memory limit) nor the
 * multi-frequency torus (more than GD_QP_MAXD bases, an unbalance, a non-smooth law, too
 * many coordinates) can take: before any point is solved, naming the common period and
 * the H it would need. Its own file: the multi-frequency folder needs nothing of this one,
 * and period.c, which choose.c uses, needs nothing of choose.c. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "geardyn/periodic.h"
#include "periodic/multifreq/qphb_impl.h"
#include "periodic/periodic_impl.h"

#define TWO_PI 6.28318530717958647692
/* harmonics per period of the highest excitation a point needs at least (the torus'
 * first order: a mesh's TVMS from geometry, docs/periodic.md "Several base frequencies") */
#define H_PER_CYCLE 24
/* common periods up to this many periods of the highest: ordinary harmonic balance */
#define LONG_ORDER 16
/* the torus' own DOF limit without condensation (choose.c, QP_AUTO_NF) */
#define TORUS_NF 64

int gd_per_qp_refusal(const gd_system *sys, const gd_transient_spec *spec, double speed,
                      const gd_periodic_options *opt, char *msg, size_t cap)
{
    double w0 = 0.0;
    int order = 0;
    gd_error err;
    if (!opt->adaptive || opt->subharmonic > 1 || speed == 0.0) return 0;
    if (gd_periodic_fundamental(sys, spec, speed, &w0, &order, &err) || order <= LONG_ORDER)
        return 0;
    gd_transient *tr = NULL;
    if (gd_transient_new(sys, spec, speed, &tr, &err)) return 0;
    int mnf, mnt, mng;
    long mknz;
    gd_hb_memory_params_tr(tr, &mnf, &mnt, &mng, &mknz);
    const long Hn = (long)order * H_PER_CYCLE;
    const int Hc = Hn > 1000000 ? 1000000 : (int)Hn;
    const double need = gd_hb_memory(mnf, Hc, gd_hb_samples_for(Hc), mnt, mng, mknz),
                 limit = gd_hb_memory_limit(opt);
    int refuse = 0;
    if (need > limit) {
        double W[GD_QP_MAXD];
        long qorder = 0;
        int nf = 0;
        char why[200] = "";
        const int d = gd_per_qp_probe(sys, spec, speed, W, &qorder, &nf, why, sizeof why);
        /* only trains of several independent excitations (mesh groups, loads): one mesh
         * with unbalances (a single base the torus does not take) stays with harmonic
         * balance or shooting of its period */
        const int several = d >= 2 || !strncmp(why, "more than", 9);
        if (several && d >= 2 && gd_per_nonsmooth(sys, spec, speed))
            snprintf(why, sizeof why, "a law is not smooth (backlash or contact)");
        else if (several && d >= 2 && nf > TORUS_NF)
            snprintf(why, sizeof why, "%d DOFs that do not condense onto the laws' coordinates",
                     nf);
        refuse = several && why[0];
        if (refuse) {
            const double T = TWO_PI / w0;
            snprintf(msg, cap,
                     "no periodic method fits: the common period is %.6g input revolutions "
                     "(%.4g s), %d periods of the highest excitation; harmonic balance of it "
                     "would need H >= %ld (about %.3g GB, limit %.3g GB); multi-frequency: "
                     "%.150s",
                     speed / w0, T, order, Hn, need / 1e9, limit / 1e9, why);
        }
    }
    gd_transient_free(tr);
    return refuse;
}
