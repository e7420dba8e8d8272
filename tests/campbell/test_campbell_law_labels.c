/* Campbell's mode labels (whirl, dominant motion, dominant component) at a speed S equal
 * those of `geardyn modal --speed S` on models whose bearings are linearised laws: the
 * sparse Campbell solves left the laws' strain energy out of the split (modal adds it,
 * gd_modal_energies_laws), so on examples/reducer_three_stage.yaml the output shaft's
 * axial mode at 174.6 Hz, 59 % in bearing OUTA, was credited to the shaft "output" by
 * Campbell (component label differs at every speed), and rig2018_geometry's bearing
 * modes likewise. Every mode of every track is compared with the modal mode of the same
 * frequency at its speed, on the path Campbell chooses (auto) and on the sparse one. */
#include <math.h>
#include <string.h>

#include "geardyn/campbell.h"
#include "geardyn/modal.h"
#include "geardyn/model_file.h"
#include "geardyn/static.h"
#include "harness.h"

#define REQUIRE_RET(cond, v)                                                                       \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "  %s:%d: REQUIRE(%s) failed\n", __FILE__, __LINE__, #cond);           \
            gd_ts_->checks_failed++;                                                               \
            return v;                                                                              \
        }                                                                                          \
    } while (0)

/* The elastic mode of r whose eigenvalue is nearest that of c, -1 if none within rel of
 * |lambda| (by the eigenvalue, not |lambda|: the reducer's axial mode at 290.576 Hz has
 * the |lambda| of the lateral pair beside it). */
static int nearest(const gd_modal_result *r, const gd_mode *c, double rel)
{
    int best = -1;
    double bd = INFINITY;
    for (int j = 0; j < r->nmodes; j++) {
        if (r->modes[j].rigid_body) continue;
        double d =
            hypot(r->modes[j].lambda_re - c->lambda_re, r->modes[j].lambda_im - c->lambda_im);
        if (d < bd) {
            bd = d;
            best = j;
        }
    }
    return bd <= rel * c->omega_n ? best : -1;
}

/* Returns the number of (speed, mode) labels compared; *law_dominated counts those whose
 * dominant component is a law (the modes the defect mislabelled). */
static int compare(gd_test_state *gd_ts_, const char *file, const double *rpm, int ns, int nmodes,
                   gd_eig_method method, int *law_dominated)
{
    gd_model *m = NULL;
    gd_system *s = NULL;
    gd_error err;
    *law_dominated = 0;
    REQUIRE_RET(gd_model_load(file, &m, &err) == GD_OK, 0);
    REQUIRE_RET(gd_system_build(m, &s, &err) == GD_OK, 0);
    /* as `geardyn campbell` and `geardyn modal` set it: the static operating point,
       solved at each speed */
    gd_static_options so;
    gd_static_options_init(&so);
    so.speed = -1;
    REQUIRE_RET(gd_static_operating_point(s, &so, 0, &err) == GD_OK, 0);
    double W[8];
    for (int k = 0; k < ns; k++)
        W[k] = rpm[k] * M_PI / 30;
    gd_campbell_options co;
    gd_campbell_options_init(&co);
    co.speeds = W;
    co.nspeeds = ns;
    co.nmodes = nmodes;
    co.method = method;
    co.nthreads = 1;
    gd_campbell_result *c = NULL;
    REQUIRE_RET(gd_campbell(s, &co, &c, &err) == GD_OK, 0);
    int nlaw_first = s->ncomponents - s->nlaws, compared = 0;
    for (int k = 0; k < ns; k++) {
        gd_modal_options mo;
        gd_modal_options_init(&mo);
        mo.speed = W[k];
        mo.nmodes = nmodes + 4; /* rigid-body modes and the window's edge */
        mo.want_left = 0;
        gd_modal_result *r = NULL;
        REQUIRE_RET(gd_modal_solve(s, &mo, &r, &err) == GD_OK, 0);
        for (int t = 0; t < c->ntracks; t++) {
            const gd_mode *cm = &c->modes[(size_t)t * ns + k];
            if (cm->rigid_body < 0) continue;
            int j = nearest(r, cm, 1e-6);
            if (j < 0) continue; /* at the modal window's edge */
            const gd_mode *md = &r->modes[j];
            compared++;
            *law_dominated += cm->dominant_component >= nlaw_first;
            if (cm->dominant_component != md->dominant_component ||
                cm->dominant_motion != md->dominant_motion || cm->whirl != md->whirl)
                fprintf(stderr, "%s %g rpm, %.6g Hz: campbell %d/%s/%s, modal %d/%s/%s\n", file,
                        rpm[k], cm->frequency_hz, cm->dominant_component,
                        gd_motion_names[cm->dominant_motion], gd_whirl_names[cm->whirl],
                        md->dominant_component, gd_motion_names[md->dominant_motion],
                        gd_whirl_names[md->whirl]);
            CHECK(cm->dominant_component == md->dominant_component);
            CHECK(cm->dominant_motion == md->dominant_motion);
            CHECK(cm->whirl == md->whirl);
            for (int e = 0; e < GD_NMOTIONS; e++)
                CHECK_ABS(cm->energy_share[e], md->energy_share[e], 1e-6);
        }
        gd_modal_free(r);
    }
    gd_campbell_free(c);
    gd_system_free(s);
    gd_model_free(m);
    return compared;
}

TEST(campbell_labels_equal_modal_reducer)
{
    static const double rpm[] = {500, 1000, 1500};
    for (int pass = 0; pass < 2; pass++) {
        int law = 0;
        /* 6 elastic modes: up to the motor's tilt pair at 226 Hz, well below the next
           (290.6 Hz), so no window cuts a repeated pair */
        int n = compare(gd_ts_, "examples/reducer_three_stage.yaml", rpm, 3, 6,
                        pass ? GD_EIG_SPARSE : GD_EIG_AUTO, &law);
        CHECK(n == 3 * 6);
        CHECK(law >= 3); /* the axial mode (OUTA) at each speed, at least */
    }
}

TEST(campbell_labels_equal_modal_rig2018_geometry)
{
    static const double rpm[] = {300, 1500, 3000};
    for (int pass = 0; pass < 2; pass++) {
        int law = 0;
        /* its modes are the shafts' (bearings from geometry are stiff): the labels agree
           with and without the laws' energy, and must stay so */
        int n = compare(gd_ts_, "examples/rig2018_geometry.yaml", rpm, 3, 10,
                        pass ? GD_EIG_SPARSE : GD_EIG_AUTO, &law);
        CHECK(n == 3 * 10);
    }
}

RUN_TESTS(T(campbell_labels_equal_modal_reducer), T(campbell_labels_equal_modal_rig2018_geometry))
