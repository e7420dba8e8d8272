/* --plot and geardyn report: the SVG is valid XML (parsed by libxml2), holds the expected
 * curves and markers, and plots exactly the numbers the same run prints with --json;
 * the HTML is self-contained; bad plot requests fail with exit 2 and write nothing.
 * (The HTML pages are opened in headless Chromium by tests/plot/check_html.sh.) */
#include <libxml/parser.h>
#include <libxml/xpath.h>
#include <libxml/xpathInternals.h>

#include "cli_support.h"
#include "geardyn/plot.h"
#include "harness.h"

#define PI 3.14159265358979323846
/* The SVG carries each plotted number in shortest round-trip form (%.17g) and the
 * plotted value is the same expression of the result as the --json value: equal to a
 * few ulps (1e-13 relative). */
#define EXACT 1e-13

typedef struct svg {
    xmlDocPtr doc;
    xmlXPathContextPtr ctx;
} svg;

static int svg_open(svg *s, const char *path)
{
    s->doc = xmlReadFile(path, NULL, XML_PARSE_NONET | XML_PARSE_NOWARNING | XML_PARSE_NOERROR);
    s->ctx = s->doc ? xmlXPathNewContext(s->doc) : NULL;
    if (s->ctx) xmlXPathRegisterNs(s->ctx, BAD_CAST "s", BAD_CAST "http://www.w3.org/2000/svg");
    return s->ctx != NULL;
}

static void svg_close(svg *s)
{
    if (s->ctx) xmlXPathFreeContext(s->ctx);
    if (s->doc) xmlFreeDoc(s->doc);
}

/* Number of nodes matching an XPath expression (printf-style). */
static int count(svg *s, const char *fmt, ...)
{
    char xp[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(xp, sizeof xp, fmt, ap);
    va_end(ap);
    xmlXPathObjectPtr o = xmlXPathEvalExpression(BAD_CAST xp, s->ctx);
    int n = o && o->nodesetval ? o->nodesetval->nodeNr : -1;
    xmlXPathFreeObject(o);
    return n;
}

/* The numbers of attribute attr ("data-x", "data-y") of the first trace matching xpath;
 * returns how many (nan for "nan"), -1 if there is no such trace. */
static int trace_numbers(svg *s, const char *xpath, const char *attr, double *out, int max)
{
    xmlXPathObjectPtr o = xmlXPathEvalExpression(BAD_CAST xpath, s->ctx);
    int n = -1;
    if (o && o->nodesetval && o->nodesetval->nodeNr > 0) {
        xmlChar *v = xmlGetProp(o->nodesetval->nodeTab[0], BAD_CAST attr);
        n = 0;
        for (char *p = (char *)v, *end; p && *p && n < max; p = end) {
            while (*p == ' ')
                p++;
            if (!*p) break;
            out[n++] = strtod(p, &end);
            if (end == p) break;
        }
        xmlFree(v);
    }
    xmlXPathFreeObject(o);
    return n;
}

/* JSON array item k as a number (null: NaN). */
static double jat(const cJSON *arr, int k)
{
    const cJSON *v = cJSON_GetArrayItem(arr, k);
    return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static int same(double a, double b)
{
    if (isnan(a) || isnan(b)) return isnan(a) && isnan(b);
    return fabs(a - b) <= EXACT * fmax(fabs(b), 1e-300);
}

/* One geardyn run whose --plot is an SVG in the scratch folder: its exit code, its
 * --json output and the parsed SVG. args has one %s: the SVG's path. */
typedef struct plot_run {
    run_result r;
    cJSON *json;
    svg s;
} plot_run;

static void plot_start(gd_test_state *gd_ts_, plot_run *pr, scratch *d, const char *args)
{
    char path[256], cmd[1024];
    snprintf(path, sizeof path, "%s/plot.svg", d->dir);
    snprintf(cmd, sizeof cmd, args, path);
    run(d, &pr->r, "%s", cmd);
    CHECK(pr->r.code == 0);
    if (pr->r.code) show(&pr->r);
    pr->json = cJSON_Parse(pr->r.out);
    CHECK(pr->json != NULL);
    memset(&pr->s, 0, sizeof pr->s);
    CHECK(svg_open(&pr->s, path));
}

static void plot_end(plot_run *pr)
{
    svg_close(&pr->s);
    cJSON_Delete(pr->json);
    run_free(&pr->r);
}

#define TRACE(panel, name)                                                                         \
    "//s:g[@class='panel'][starts-with(@data-title,'" panel                                        \
    "')]/s:g[@class='trace'][@data-name='" name "']"

TEST(campbell_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "campbell tests/plot/study.yaml --speeds 0:6000rpm:4 --modes 6 --json "
               "--plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *modes = cJSON_GetObjectItem(j, "modes"),
                    *rpm = cJSON_GetObjectItem(j, "speeds_rpm");
        int nt = cJSON_GetArraySize(modes),
            ncrit = cJSON_GetArraySize(cJSON_GetObjectItem(j, "critical_speeds"));
        CHECK(nt == 6);
        /* one curve per tracked mode in both panels, the critical speeds as markers */
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]") == nt);
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'stability')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]") == nt);
        CHECK(ncrit > 0);
        CHECK(count(s, TRACE("modes by whirl", "critical speeds") "/*[@class='marker']") == ncrit);
        for (int t = 0; t < nt; t++) {
            const cJSON *m = cJSON_GetArrayItem(modes, t);
            char xp[400];
            snprintf(xp, sizeof xp,
                     "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                     "s:g[@class='trace'][starts-with(@data-name,'mode %d (')]",
                     (int)jnum(m, "id"));
            double y[16], x[16];
            int n = trace_numbers(s, xp, "data-y", y, 16);
            CHECK(n == 4 && trace_numbers(s, xp, "data-x", x, 16) == 4);
            for (int k = 0; k < n && k < 4; k++) {
                CHECK(same(y[k], jat(cJSON_GetObjectItem(m, "frequency_hz"), k)));
                CHECK(same(x[k], jat(rpm, k)));
            }
            snprintf(xp, sizeof xp,
                     "//s:g[@class='panel'][starts-with(@data-title,'stability')]/"
                     "s:g[@class='trace'][starts-with(@data-name,'mode %d (')]",
                     (int)jnum(m, "id"));
            n = trace_numbers(s, xp, "data-y", y, 16);
            CHECK(n == 4);
            for (int k = 0; k < n && k < 4; k++)
                CHECK(same(y[k], jat(cJSON_GetObjectItem(m, "log_decrement"), k)));
        }
        /* each point in the colour of its whirl at that speed (forward #1f4fd6, backward
         * #d62728) */
        int fwd = 0, bwd = 0;
        for (int t = 0; t < nt; t++) {
            const cJSON *w = cJSON_GetObjectItem(cJSON_GetArrayItem(modes, t), "whirl_by_speed");
            for (int k = 0; k < cJSON_GetArraySize(w); k++) {
                const char *v = cJSON_GetStringValue(cJSON_GetArrayItem(w, k));
                fwd += v && !strcmp(v, "forward");
                bwd += v && !strcmp(v, "backward");
            }
        }
        CHECK(fwd > 0 && bwd > 0);
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]/"
                       "*[@class='marker'][@fill='#1f4fd6']") == fwd);
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]/"
                       "*[@class='marker'][@fill='#d62728']") == bwd);
        /* the critical-speed table lists them all */
        CHECK(count(s, "//s:g[@class='table'][@data-rows='%d']", ncrit) >= 1);
    }
    plot_end(&pr);
    scratch_close(&d);
}

TEST(frf_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh "
               "--output pinion.y --freq 100:26000:20 --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        /* magnitude, phase, Nyquist: two curves each; no refinement of the Nyquist curves
         * of this undamped pair (its peaks are singular; frf_peaks_located refines the
         * damped rig's) */
        CHECK(count(s, "//s:g[@class='panel']") == 3);
        CHECK(count(s, "//s:g[@class='panel']/s:g[@class='trace'][not(contains(@data-name,'"
                       "refined'))][@data-name!='peaks (located)']") == 6);
        CHECK(count(s, TRACE("FRF: Nyquist", "pinion.y (1/N) (refined around the peaks)")) == 0);
        const cJSON *outs = cJSON_GetObjectItem(j, "outputs");
        CHECK(cJSON_GetArraySize(outs) == 2);
        double y[32], x[32], re[32];
        int n = trace_numbers(s, TRACE("FRF: magnitude", "mesh:mesh (1/m)"), "data-y", y, 32);
        CHECK(n == 20);
        CHECK(trace_numbers(s, TRACE("FRF: magnitude", "mesh:mesh (1/m)"), "data-x", x, 32) == 20);
        const cJSON *o = cJSON_GetArrayItem(outs, 0);
        for (int k = 0; k < n && k < 20; k++) {
            CHECK(same(y[k], jat(cJSON_GetObjectItem(o, "magnitude"), k)));
            CHECK(same(x[k] * 2 * PI, jat(cJSON_GetObjectItem(o, "frequency_rad_s"), k)) ||
                  fabs(x[k] * 2 * PI / jat(cJSON_GetObjectItem(o, "frequency_rad_s"), k) - 1) <
                      1e-15);
        }
        n = trace_numbers(s, TRACE("FRF: phase", "pinion.y (1/N)"), "data-y", y, 32);
        CHECK(n == 20);
        o = cJSON_GetArrayItem(outs, 1);
        for (int k = 0; k < n && k < 20; k++)
            CHECK(same(y[k], jat(cJSON_GetObjectItem(o, "phase_deg"), k)));
        n = trace_numbers(s, TRACE("FRF: Nyquist", "pinion.y (1/N)"), "data-x", re, 32);
        CHECK(n == 20);
        for (int k = 0; k < n && k < 20; k++)
            CHECK(same(re[k], jat(cJSON_GetObjectItem(o, "real"), k)));
        /* Nyquist points are markers on the curve */
        CHECK(count(s, TRACE("FRF: Nyquist", "pinion.y (1/N)") "/*[@class='marker']") == 20);
    }
    plot_end(&pr);
    scratch_close(&d);
}

TEST(unbalance_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "unbalance examples/chen1998_gear_pair.yaml --speeds 100:6000:8 --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *outs = cJSON_GetObjectItem(j, "outputs");
        int no = cJSON_GetArraySize(outs),
            nh = cJSON_GetArraySize(cJSON_GetObjectItem(j, "harmonics"));
        CHECK(nh == 1 && no > 0);
        CHECK(count(s, "//s:g[@class='panel'][contains(@data-title,'amplitude: "
                       "magnitude')]/s:g[@class='trace']") == no);
        /* one set of panels per quantity: m, rad and N (the chen pair's defaults) */
        CHECK(count(s, "//s:g[@class='panel'][contains(@data-title,'amplitude: magnitude')]") == 3);
        CHECK(count(s, "//s:g[@class='panel'][@data-title='force amplitude: magnitude']/"
                       "s:g[@class='trace'][not(contains(@data-name,'(N)'))]") == 0);
        for (int o = 0; o < no; o++) {
            const cJSON *ser = cJSON_GetArrayItem(outs, o);
            char xp[400];
            snprintf(xp, sizeof xp,
                     "//s:g[@class='panel'][contains(@data-title,'amplitude: "
                     "magnitude')]/s:g[@class='trace'][starts-with(@data-name,'%s (')]",
                     jstr(ser, "name"));
            double y[16];
            int n = trace_numbers(s, xp, "data-y", y, 16);
            CHECK(n == 8);
            for (int k = 0; k < n && k < 8; k++)
                CHECK(same(y[k], jat(cJSON_GetObjectItem(ser, "magnitude"), k)));
        }
        /* one orbit (an ellipse of 73 points) per orbit node */
        int norb = cJSON_GetArraySize(cJSON_GetObjectItem(j, "orbits"));
        CHECK(norb > 0);
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'orbits at')]/"
                       "s:g[@class='trace'][@data-n='73']") == norb);
    }
    plot_end(&pr);
    scratch_close(&d);
}

/* Runs of equal pair counts (1, or >= 2) in the JSON: the shaded zones. */
static int zone_runs(const cJSON *pairs, int want)
{
    int n = cJSON_GetArraySize(pairs), runs = 0, prev = 0;
    for (int i = 0; i < n; i++) {
        int p = (int)jat(pairs, i), in = p == want;
        runs += in && !prev;
        prev = in;
    }
    return runs;
}

TEST(mesh_stiffness_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "mesh-stiffness examples/rig2018_pair.yaml --cycles 2 --points 90 --json --plot %s "
               "--compare-helix 10deg,20deg");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *k = cJSON_GetObjectItem(j, "stiffness"),
                    *a = cJSON_GetObjectItem(j, "angle_rad");
        int n = cJSON_GetArraySize(k);
        CHECK(n == 180);
        static double y[400], x[400];
        const char *xp = TRACE("time-varying mesh stiffness", "k (normal plane)");
        CHECK(trace_numbers(s, xp, "data-y", y, 400) == n);
        CHECK(trace_numbers(s, xp, "data-x", x, 400) == n);
        for (int i = 0; i < n; i++) {
            CHECK(same(y[i], jat(k, i)));
            CHECK(same(x[i], jat(a, i) * 180 / PI));
        }
        /* a spur pair of contact ratio 1.7: alternating single and double contact, one
         * shaded polygon per run of each */
        const cJSON *pairs = cJSON_GetObjectItem(j, "pairs_in_contact");
        int n1 = zone_runs(pairs, 1), n2 = zone_runs(pairs, 2);
        CHECK(n1 >= 2 && n2 >= 2);
        CHECK(count(s, TRACE("time-varying mesh stiffness", "1 pair in contact") "/s:polygon") ==
              n1);
        CHECK(count(s, TRACE("time-varying mesh stiffness", "2 pairs in contact") "/s:polygon") ==
              n2);
        /* the comparison: this pair and two other helix angles */
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'comparison')]/"
                       "s:g[@class='trace']") == 3);
        CHECK(count(s, TRACE("Fourier harmonics", "amplitude") "/*[@class='marker']") ==
              cJSON_GetArraySize(cJSON_GetObjectItem(j, "harmonics")));
    }
    plot_end(&pr);
    /* a helical pair of total contact ratio 2.6 (Table 1 of [JMSTHelical]): 2 and 3 pairs in
     * contact, shaded as such, none as 1 pair; the y axis around the ripple */
    plot_start(
        gd_ts_, &pr, &d,
        "mesh-stiffness examples/helical_pair1.yaml --cycles 2 --points 60 --json --plot %s");
    s = &pr.s;
    j = pr.json;
    if (j && s->ctx) {
        const cJSON *pairs = cJSON_GetObjectItem(j, "pairs_in_contact");
        int n2 = zone_runs(pairs, 2), n3 = zone_runs(pairs, 3);
        CHECK(n2 >= 2 && n3 >= 2 && zone_runs(pairs, 1) == 0);
        CHECK(count(s, TRACE("time-varying mesh stiffness", "2 pairs in contact") "/s:polygon") ==
              n2);
        CHECK(count(s, TRACE("time-varying mesh stiffness", "3 pairs in contact") "/s:polygon") ==
              n3);
        CHECK(count(s, TRACE("time-varying mesh stiffness", "1 pair in contact")) == 0);
        static double zy[64];
        int nz = trace_numbers(s, TRACE("time-varying mesh stiffness", "2 pairs in contact"),
                               "data-y", zy, 64);
        CHECK(nz > 0 && zy[0] > 0.5 * jnum(j, "stiffness_min")); /* the axis does not start at 0 */
    }
    plot_end(&pr);
    scratch_close(&d);
}

TEST(modal_and_transient_plots)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d, "modal examples/chen1998_gear_pair.yaml --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *modes = cJSON_GetObjectItem(j, "modes");
        int elastic = 0;
        for (int k = 0; k < cJSON_GetArraySize(modes); k++)
            elastic +=
                !cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetArrayItem(modes, k), "rigid_body"));
        CHECK(elastic == 6);
        /* shape panels titled with the mode's frequency (one per shaft that moves), whirl
         * and zeta written out; the energy table */
        for (int k = 1; k <= elastic; k++)
            CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'mode %d: ')]", k) >= 1);
        char title[200];
        snprintf(title, sizeof title,
                 "//s:g[@class='panel'][starts-with(@data-title,'mode 1: %.6g Hz, ')]"
                 "[contains(@data-title,'whirl: ')]",
                 jnum(cJSON_GetArrayItem(modes, 0), "frequency_hz"));
        CHECK(count(s, "%s", title) >= 1);
        CHECK(count(s, "//s:g[@class='panel'][contains(@data-title,' whirl,')]") == 0);
        CHECK(count(s, "//s:g[@class='table'][@data-rows='%d']", elastic) == 1);
    }
    plot_end(&pr);

    plot_start(gd_ts_, &pr, &d,
               "transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet --json "
               "--plot %s");
    s = &pr.s;
    j = pr.json;
    if (j && s->ctx) {
        const cJSON *recs = cJSON_GetObjectItem(j, "records");
        int nr = cJSON_GetArraySize(recs), ns = (int)jnum(j, "samples");
        CHECK(count(s, "//s:g[@class='panel'][contains(@data-title,'time "
                       "history')]/s:g[@class='trace']") == nr);
        /* each record's curve: its samples, with the --json statistics */
        xmlXPathObjectPtr o = xmlXPathEvalExpression(
            BAD_CAST
            "//s:g[@class='panel'][contains(@data-title,'time history')]/s:g[@class='trace']",
            s->ctx);
        static double y[4096];
        for (int k = 0; o && o->nodesetval && k < o->nodesetval->nodeNr && k < nr; k++) {
            xmlChar *v = xmlGetProp(o->nodesetval->nodeTab[k], BAD_CAST "data-y");
            int n = 0;
            double mx = -INFINITY;
            for (char *p = (char *)v, *end; p && *p && n < 4096; p = end) {
                y[n] = strtod(p, &end);
                if (end == p) break;
                mx = fmax(mx, y[n++]);
            }
            xmlFree(v);
            CHECK(n == ns);
            /* the panels group records by quantity: find this curve's record by maximum */
            int found = 0;
            for (int q = 0; q < nr; q++)
                found |= same(mx, jnum(cJSON_GetArrayItem(recs, q), "max"));
            CHECK(found);
        }
        xmlXPathFreeObject(o);
        /* contact states of the backlash meshes get their own panel, no spectrum */
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'contact state')]") == 1);
        CHECK(count(s, "//s:g[@class='panel'][contains(@data-title,'spectrum')]") >= 1);
    }
    plot_end(&pr);
    scratch_close(&d);
}

TEST(report_has_every_section)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result r;
    run(&d, &r, "report tests/plot/study.yaml --speeds 0:6000rpm:5 --freq-points 40 --out %s/r.svg",
        d.dir);
    CHECK(r.code == 0);
    char path[256];
    snprintf(path, sizeof path, "%s/r.svg", d.dir);
    CHECK(contains(r.out, path));
    svg s = {0};
    CHECK(svg_open(&s, path));
    run_result k;
    run(&d, &k, "mesh-stiffness tests/plot/study.yaml --json");
    cJSON *j = cJSON_Parse(k.out);
    if (s.ctx && j) {
        /* model, modes, Campbell, FRF, unbalance (one harmonic), the run-up's note (not
         * asked for: how to ask), mesh stiffness */
        CHECK(count(&s, "//s:g[@class='section']") == 7);
        CHECK(count(&s,
                    "//s:g[@class='panel'][@data-title='the model to scale (side view)']/"
                    "s:g[@class='trace'][@data-name!='nodes']") == 3); /* shafts, gears, bearings */
        CHECK(count(&s, TRACE("the model to scale", "bearings") "/*[@class='marker']") == 4);
        CHECK(count(&s, "//s:g[@class='panel'][@data-title='FRF: magnitude']/s:g[@class='trace']"
                        "[@data-name!='peaks (located)']") ==
              9); /* the mesh force and x, y of four bearings */
        static double y[200];
        const cJSON *kk = cJSON_GetObjectItem(j, "stiffness");
        int n = trace_numbers(&s, TRACE("time-varying mesh stiffness", "k (normal plane)"),
                              "data-y", y, 200);
        CHECK(n == 60 && cJSON_GetArraySize(kk) == 60);
        for (int i = 0; i < n && i < 60; i++)
            CHECK(same(y[i], jat(kk, i)));
    }
    cJSON_Delete(j);
    run_free(&k);
    svg_close(&s);
    run_free(&r);
    scratch_close(&d);
}

/* value of a JSON point's record statistic */
static double prec(const cJSON *pt, const char *rec, const char *field)
{
    return jnum(cJSON_GetObjectItem(cJSON_GetObjectItem(pt, "records"), rec), field);
}

/* The damped-Mathieu pair (tests/plot/mathieu_pair.yaml, one DOF) across its primary
 * tongue: period doubling at 698.97 and 715.17 rad/s, the four points inside unstable.
 * Stable peak-to-peak solid, unstable dashed (with the stable neighbours that join
 * them), both equal to the --json numbers; the bifurcation markers sit on the dashed
 * curve (interpolated between the bracketing points); harmonic 1 (named as the mesh
 * order it is) and |mu| max as in --json. */
TEST(periodic_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "periodic tests/plot/mathieu_pair.yaml --speeds 680:730:11 --harmonics 4 --record "
               "mesh:m:force --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *pts = cJSON_GetObjectItem(j, "points"),
                    *bif = cJSON_GetObjectItem(j, "bifurcations");
        REQUIRE(cJSON_GetArraySize(pts) == 11 && cJSON_GetArraySize(bif) == 2);
        CHECK(count(s, "//s:g[@class='panel']") == 3);
        CHECK(count(s, "//s:g[@class='table'][@data-rows='2']") == 1);
#define P2P "peak-to-peak: m force"
        double ys[16], yu[16], x[16], h1[16], mu[16];
        CHECK(trace_numbers(s, TRACE(P2P, "stable"), "data-y", ys, 16) == 11);
        CHECK(trace_numbers(s, TRACE(P2P, "unstable"), "data-y", yu, 16) == 11);
        CHECK(trace_numbers(s, TRACE(P2P, "stable"), "data-x", x, 16) == 11);
        /* the period is the mesh's (w = 20 W): harmonic 1 is the mesh order */
        CHECK(trace_numbers(s, TRACE("amplitudes at the excitation orders", "mesh m 20x a"),
                            "data-y", h1, 16) == 11);
        CHECK(trace_numbers(s, TRACE("stability", "|mu| max"), "data-y", mu, 16) == 11);
        int nst = 0, nun = 0, joined = 0;
        for (int i = 0; i < 11; i++) {
            const cJSON *pt = cJSON_GetArrayItem(pts, i);
            int st = cJSON_IsTrue(cJSON_GetObjectItem(pt, "stable"));
            int near =
                !st ||
                (i > 0 &&
                 !cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetArrayItem(pts, i - 1), "stable"))) ||
                (i < 10 &&
                 !cJSON_IsTrue(cJSON_GetObjectItem(cJSON_GetArrayItem(pts, i + 1), "stable")));
            double v = prec(pt, "mesh:m:force", "peak_to_peak");
            nst += st;
            nun += !st;
            joined += near;
            CHECK(same(ys[i], st ? v : NAN));
            CHECK(same(yu[i], near ? v : NAN));
            CHECK(fabs(x[i] * PI / 30 / jnum(pt, "speed_rad_s") - 1) < EXACT);
            CHECK(same(h1[i], jat(cJSON_GetObjectItem(
                                      cJSON_GetObjectItem(cJSON_GetObjectItem(pt, "records"),
                                                          "mesh:m:force"),
                                      "amplitudes"),
                                  1)));
            CHECK(same(mu[i], jnum(pt, "floquet_multiplier_max_abs")));
        }
        CHECK(nst == 7 && nun == 4 && joined == 6); /* 700..715 inside the tongue */
        CHECK(count(s, TRACE(P2P, "stable") "/*[@class='marker']") == nst);
        CHECK(count(s, TRACE(P2P, "unstable") "/*[@class='marker']") == joined);
        CHECK(count(s, TRACE(P2P, "unstable") "/*[@stroke-dasharray]") >= 1);
        CHECK(count(s, TRACE(P2P, "stable") "/*[@stroke-dasharray]") == 0);
        /* the two period doublings, at their located speeds, on the p2p line between the
         * bracketing points 695|700 and 715|720 rad/s */
        double bx[4], by[4];
        CHECK(trace_numbers(s, TRACE(P2P, "period_doubling"), "data-x", bx, 4) == 2);
        CHECK(trace_numbers(s, TRACE(P2P, "period_doubling"), "data-y", by, 4) == 2);
        CHECK(count(s, TRACE(P2P, "period_doubling") "/*[@class='marker']") == 2);
        for (int b = 0; b < 2; b++) {
            double w = jnum(cJSON_GetArrayItem(bif, b), "speed_rad_s");
            CHECK(fabs(bx[b] * PI / 30 / w - 1) < EXACT);
            int lo = (int)floor((w - 680) / 5); /* the bracketing points lo, lo + 1 */
            const cJSON *a = cJSON_GetArrayItem(pts, lo), *c = cJSON_GetArrayItem(pts, lo + 1);
            double wa = jnum(a, "speed_rad_s"), wc = jnum(c, "speed_rad_s");
            double ya = prec(a, "mesh:m:force", "peak_to_peak"),
                   yc = prec(c, "mesh:m:force", "peak_to_peak");
            /* rpm vs rad/s interpolation weights agree to rounding: 1e-12 */
            CHECK_REL(by[b], ya + (yc - ya) * (w - wa) / (wc - wa), 1e-12);
        }
        CHECK(count(s, TRACE("stability", "period_doubling") "/*[@class='marker']") == 2);
#undef P2P
    }
    plot_end(&pr);
    scratch_close(&d);
}

TEST(html_is_self_contained)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result r;
    run(&d, &r,
        "campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:3 --modes 3 --plot %s/c.html",
        d.dir);
    CHECK(r.code == 0);
    char path[256];
    snprintf(path, sizeof path, "%s/c.html", d.dir);
    char *html = read_file(path);
    CHECK(html != NULL);
    if (html) {
        CHECK(contains(html, "plotly.js (gl3d - minified) v4.1.1")); /* inlined, as pinned */
        CHECK(contains(html, "Plotly.newPlot"));
        CHECK(!contains(html, "<script src")); /* nothing fetched */
        CHECK(contains(html, "a class=\"csv\""));
    }
    free(html);
    run_free(&r);
    scratch_close(&d);
}

/* exit 2, the message, and nothing in the scratch folder */
static void check_refused(gd_test_state *gd_ts_, scratch *d, const char *args, const char *msg)
{
    run_result r;
    run(d, &r, "%s", args);
    CHECK(r.code == 2);
    CHECK(contains(r.err, msg));
    if (r.code != 2 || !contains(r.err, msg)) show(&r);
    CHECK(count_entries(d->dir) == 2); /* stdout.txt and stderr.txt of the run only */
    run_free(&r);
}

TEST(bad_plot_requests_write_nothing)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    char args[512];
    snprintf(args, sizeof args, "modal examples/chen1998_gear_pair.yaml --plot %s/m.gif", d.dir);
    check_refused(gd_ts_, &d, args, "unknown plot format '.gif'");
    snprintf(args, sizeof args,
             "frf examples/kumar2011_coupled.yaml --input torque:motor --output "
             "mesh:mesh --freq 100:200:3 --plot %s/plot",
             d.dir);
    check_refused(gd_ts_, &d, args, "FILE.svg, FILE.png, FILE.pdf (static) or FILE.html");
    snprintf(args, sizeof args,
             "campbell examples/kumar2011_coupled.yaml --speeds 0:100:2 --plot %s/no/c.svg", d.dir);
    check_refused(gd_ts_, &d, args, "does not exist");
    /* a folder that refuses the file (even to root): found when writing, after computing */
    check_refused(gd_ts_, &d, "mesh-stiffness examples/rig2018_pair.yaml --plot /proc/k.svg",
                  "/proc/k.svg");
    /* nothing to plot: the only mode asked for is the rigid-body one */
    snprintf(args, sizeof args,
             "modal examples/kumar2011_torsional.yaml --modes 1 --plot %s/m.svg --out %s/o", d.dir,
             d.dir);
    check_refused(gd_ts_, &d, args, "nothing to plot");
    /* periodic: the plot file is checked before the harmonic balance runs; a branch with
     * no converged point (speed 0: the period is undefined) has nothing to plot */
    snprintf(args, sizeof args,
             "periodic tests/plot/mathieu_pair.yaml --speeds 700:700:1 --plot %s/p.jpg", d.dir);
    check_refused(gd_ts_, &d, args, "unknown plot format '.jpg'");
    snprintf(args, sizeof args,
             "periodic examples/chen1998_gear_pair.yaml --speeds 0:0:1 --harmonics 2 --plot "
             "%s/p.svg --out %s/o",
             d.dir, d.dir);
    check_refused(gd_ts_, &d, args, "nothing to plot: no point converged");
    /* ... and the table that says why is still printed */
    {
        run_result r;
        run(&d, &r, "%s", args);
        CHECK(r.code == 2 && contains(r.out, "converged"));
        if (!contains(r.out, "converged")) show(&r);
        run_free(&r);
    }
    /* HTML without plotly.js */
    setenv("GEARDYN_PLOTLY_JS", "/nonexistent/plotly.min.js", 1);
    snprintf(args, sizeof args, "report tests/plot/study.yaml --out %s/r.html", d.dir);
    check_refused(gd_ts_, &d, args, "GEARDYN_PLOTLY_JS");
    unsetenv("GEARDYN_PLOTLY_JS");
    check_refused(gd_ts_, &d, "report tests/plot/study.yaml", "--out FILE.html is required");
    scratch_close(&d);
}

/* largest |y| of the traces of the panels of one mode whose names match (or not) a
 * prefix; markers of gears and bearings (drawn on the axis) left aside */
static double mode_trace_max(svg *s, int mode, const char *prefix, int matching, int *ntraces)
{
    char xp[300];
    snprintf(xp, sizeof xp,
             "//s:g[@class='panel'][starts-with(@data-title,'mode %d: ')]/s:g[@class='trace']"
             "[@data-name!='gears and disks'][@data-name!='bearings']",
             mode);
    xmlXPathObjectPtr o = xmlXPathEvalExpression(BAD_CAST xp, s->ctx);
    double mx = 0;
    *ntraces = 0;
    for (int k = 0; o && o->nodesetval && k < o->nodesetval->nodeNr; k++) {
        xmlChar *name = xmlGetProp(o->nodesetval->nodeTab[k], BAD_CAST "data-name");
        int is = name && !strncmp((const char *)name, prefix, strlen(prefix));
        xmlFree(name);
        if (is != matching) continue;
        ++*ntraces;
        xmlChar *v = xmlGetProp(o->nodesetval->nodeTab[k], BAD_CAST "data-y");
        for (char *p = (char *)v, *end; p && *p; p = end) {
            double y = strtod(p, &end);
            if (end == p) break;
            mx = fmax(mx, fabs(y));
        }
        xmlFree(v);
    }
    xmlXPathFreeObject(o);
    return mx;
}

/* The motor of the two-stage gearbox tilts on its bearings alone (the coupling is
 * torsional): those two modes are drawn as the motor's rx and ry, the largest 1, in
 * one panel (the input shaft's, where the motor is coupled), and nothing else of the
 * 30 DOF families (numerical noise, ~1e-7 of the motor's tilt) is drawn above 1 %. */
TEST(pure_tilt_mode_drawn_alone)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "modal tests/plot/gearbox_two_stage.yaml --modes 12 --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    int found = 0;
    if (j && s->ctx) {
        const cJSON *modes = cJSON_GetObjectItem(j, "modes");
        for (int k = 0; k < cJSON_GetArraySize(modes); k++) {
            const cJSON *md = cJSON_GetArrayItem(modes, k);
            if (strcmp(jstr(md, "dominant_motion"), "tilt") ||
                strcmp(jstr(md, "dominant_component"), "motor_bearings"))
                continue;
            found++;
            int n = (int)jnum(md, "mode"), nm, no;
            CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'mode %d: ')]", n) == 1);
            CHECK(count(s,
                        "//s:g[@class='panel'][starts-with(@data-title,'mode %d: ')]"
                        "[contains(@data-title,'shaft shaft1 (with motor)')]",
                        n) == 1);
            double motor = mode_trace_max(s, n, "motor r", 1, &nm);
            double other = mode_trace_max(s, n, "motor r", 0, &no);
            CHECK(nm == 2); /* rx and ry */
            CHECK(fabs(motor - 1) < 1e-12);
            CHECK(other <= 0.01); /* nothing else above 1 % (none is drawn at all here) */
            CHECK(no == 0);
            /* whirl and zeta written readably: |zeta| < 1e-9 is shown as 0 */
            CHECK(count(s,
                        "//s:g[@class='panel'][starts-with(@data-title,'mode %d: ')]"
                        "[contains(@data-title,'whirl: %s, zeta 0;')]",
                        n, jstr(md, "whirl")) == 1);
        }
    }
    CHECK(found == 2); /* the motor's tilt pair */
    plot_end(&pr);
    scratch_close(&d);
}

/* The two-stage gearbox with its motor and brake has repeated pairs (the motor's and
 * the brake's x/y on isotropic bearings, whose eigensolver basis changes from speed to
 * speed, even to nearly parallel vectors): 16 modes asked for are 16 tracks, each
 * present at every speed (the MAC with a pair's whole eigenspace keeps it a pair; the
 * sum of the separate MACs had made 19-22 fragments). */
TEST(campbell_pairs_stay_pairs)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "campbell tests/plot/gearbox_two_stage.yaml --speeds 0:6000rpm:31 --modes 16 "
               "--json --plot %s");
    cJSON *j = pr.json;
    svg *s = &pr.s;
    if (j && s->ctx) {
        const cJSON *modes = cJSON_GetObjectItem(j, "modes");
        CHECK(cJSON_GetArraySize(modes) == 16);
        for (int k = 0; k < cJSON_GetArraySize(modes); k++) {
            const cJSON *f = cJSON_GetObjectItem(cJSON_GetArrayItem(modes, k), "frequency_hz");
            CHECK(cJSON_GetArraySize(f) == 31);
            int gaps = 0;
            double jump = 0;
            for (int i = 0; i < cJSON_GetArraySize(f); i++) {
                gaps += !isfinite(jat(f, i));
                /* continuous: no step between speeds larger than 5 % (the fastest
                 * track, a forward tilt whirl, moves 1.4 % a step) */
                if (i) jump = fmax(jump, fabs(jat(f, i) - jat(f, i - 1)) / jat(f, i - 1));
            }
            CHECK(gaps == 0);
            CHECK(jump < 0.05);
        }
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]") == 16);
    }
    plot_end(&pr);
    scratch_close(&d);
}

/* --max-frequency and --operating-range: the modes above the limit left out (Kumar:
 * 2 of 7 below 120 Hz), each order line named on the plot, the critical speeds where
 * --json puts them, with their separation margins to the range in the table. */
TEST(campbell_limit_labels_margins)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:31 --max-frequency "
               "120 --operating-range 1000:1400rpm --json --plot %s");
    cJSON *j = pr.json;
    svg *s = &pr.s;
    if (j && s->ctx) {
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'modes by whirl')]/"
                       "s:g[@class='trace'][starts-with(@data-name,'mode ')]") == 2);
        CHECK(count(s, "//s:text[@class='label'][.='1x input']") == 1);
        CHECK(count(s, "//s:text[@class='label'][.='1x output']") == 1);
        CHECK(count(s, "//s:g[@class='trace'][@data-name='operating range']") == 1);
        const cJSON *cs = cJSON_GetObjectItem(j, "critical_speeds");
        int n = cJSON_GetArraySize(cs);
        CHECK(n == 3);
        static double x[16];
        int m = trace_numbers(s, TRACE("modes by whirl", "critical speeds"), "data-x", x, 16);
        CHECK(m == n);
        for (int k = 0; k < n && k < m; k++)
            CHECK(same(x[k], jnum(cJSON_GetArrayItem(cs, k), "speed_rpm")));
        /* two inside 1000-1400 rpm, 2941 rpm is (2941.32 - 1400) / 1400 = 110 % above */
        CHECK(count(s, "//s:g[@class='table'][@data-rows='3'][@data-cols='5']") == 1);
        CHECK(count(s, "//s:g[@class='table']/s:text[.='0 (inside)']") == 2);
        CHECK(count(s, "//s:g[@class='table']/s:text[.='110']") == 1);
    }
    plot_end(&pr);
    scratch_close(&d);
}

/* --units: by default the units written on the command line (--freq ...Hz gives a Hz
 * table), else as asked; the Campbell axes follow (rad/s: the plotted speeds are the
 * --json speeds_rad_s, the frequencies 2 pi x frequency_hz). */
TEST(units_follow_the_command_line)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result r;
    run(&d, &r,
        "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --freq "
        "100:2000Hz:3");
    CHECK(r.code == 0 && contains(r.out, "f(Hz)") && !contains(r.out, "w(rad/s)"));
    CHECK(contains(r.out, "\n        1050 ")); /* the middle frequency, in Hz */
    run_free(&r);
    run(&d, &r,
        "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --freq "
        "100:2000Hz:3 --units rad/s");
    CHECK(r.code == 0 && contains(r.out, "w(rad/s)") && contains(r.out, "\n     628.319 "));
    run_free(&r);
    run(&d, &r, "unbalance examples/chen1998_gear_pair.yaml --speeds 100:600rad/s:2");
    CHECK(r.code == 0 && contains(r.out, "\n       rad/s  ") && contains(r.out, "\n         600 "));
    run_free(&r);
    run(&d, &r, "campbell examples/kumar2011_coupled.yaml --speeds 0:300:3 --units rad/s");
    CHECK(r.code == 0 && contains(r.out, "damped natural frequencies (rad/s)\n     rad/s "));
    run_free(&r);
    run(&d, &r, "campbell examples/kumar2011_coupled.yaml --speeds 0:300:3 --units kHz");
    CHECK(r.code == 2 && contains(r.err, "--units: 'kHz' is not rpm, Hz or rad/s"));
    run_free(&r);
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:4 --units rad/s "
               "--json --plot %s");
    cJSON *j = pr.json;
    svg *s = &pr.s;
    if (j && s->ctx) {
        static double x[8], y[8];
        int n =
            trace_numbers(s, TRACE("modes by whirl", "mode 1 (none, torsional)"), "data-x", x, 8);
        int m =
            trace_numbers(s, TRACE("modes by whirl", "mode 1 (none, torsional)"), "data-y", y, 8);
        const cJSON *sp = cJSON_GetObjectItem(j, "speeds_rad_s");
        const cJSON *f = cJSON_GetObjectItem(cJSON_GetArrayItem(cJSON_GetObjectItem(j, "modes"), 0),
                                             "frequency_hz");
        CHECK(n == 4 && m == 4);
        for (int k = 0; k < n && k < 4; k++) {
            CHECK(same(x[k], jat(sp, k)));
            CHECK(fabs(y[k] - 2 * PI * jat(f, k)) <= 1e-12 * y[k]);
        }
        CHECK(count(s, "//s:text[.='reference speed (rad/s)']") == 2);
    }
    plot_end(&pr);
    /* the FRF's frequency axis in rad/s when asked for: the --json frequencies */
    plot_start(gd_ts_, &pr, &d,
               "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh "
               "--freq 100:2000Hz:3 --units rad/s --json --plot %s");
    s = &pr.s;
    j = pr.json;
    if (j && s->ctx) {
        static double x[8];
        const cJSON *o = cJSON_GetArrayItem(cJSON_GetObjectItem(j, "outputs"), 0);
        int n = trace_numbers(s, TRACE("FRF: magnitude", "mesh:mesh"), "data-x", x, 8);
        CHECK(n == 3);
        for (int k = 0; k < n; k++)
            CHECK(fabs(x[k] / jat(cJSON_GetObjectItem(o, "frequency_rad_s"), k) - 1) < 1e-14);
        CHECK(count(s, "//s:text[.='frequency (rad/s)']") == 2);
    }
    plot_end(&pr);
    /* hover labels follow: the Nyquist points and the located peaks in rad/s (1050 Hz =
     * 6597.34 rad/s), none left in Hz */
    char html[300];
    snprintf(html, sizeof html, "%s/frf.html", d.dir);
    run(&d, &r,
        "frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh --freq "
        "100:2000Hz:3 --units rad/s --plot %s",
        html);
    CHECK(r.code == 0);
    run_free(&r);
    char *page = read_file(html);
    CHECK(page && contains(page, "mesh:mesh at 6597.34 rad/s: Re "));
    CHECK(page && !contains(page, " Hz: Re ") && !contains(page, "1050 Hz"));
    free(page);
    scratch_close(&d);
}

/* The FRF's peaks are located, not sampled: on a 10 Hz grid the rig's mesh-force peaks
 * fall within 1e-4 of damped natural frequencies from `modal` (measured: 126.53038 vs
 * 126.5304 Hz, 1324.709 vs 1324.737 Hz, where the modes' damping ratio is 7e-4), and the
 * Nyquist curve gets the points around them. */
TEST(frf_peaks_located)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    run_result k;
    run(&d, &k, "modal examples/rig2018.yaml --speed 3000rpm --modes 20 --json");
    cJSON *mj = cJSON_Parse(k.out);
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "frf examples/rig2018.yaml --input torque:gear48 --output mesh:mesh --freq "
               "10:3000Hz:300 --speed 3000rpm --json --plot %s");
    svg *s = &pr.s;
    if (mj && s->ctx) {
        static double x[64], re[4096];
        int n = trace_numbers(s, TRACE("FRF: magnitude", "peaks (located)"), "data-x", x, 64);
        CHECK(n >= 3);
        const cJSON *modes = cJSON_GetObjectItem(mj, "modes");
        for (int i = 0; i < n; i++) {
            double best = INFINITY;
            for (int m = 0; m < cJSON_GetArraySize(modes); m++) {
                double f = jnum(cJSON_GetArrayItem(modes, m), "damped_frequency_hz");
                if (f > 0) best = fmin(best, fabs(x[i] / f - 1));
            }
            CHECK(best < 1e-4);
            CHECK(fabs(x[i] / 10 - round(x[i] / 10)) > 1e-3); /* not a grid point */
        }
        int nr = trace_numbers(s, TRACE("FRF: Nyquist", "mesh:mesh (refined around the peaks)"),
                               "data-x", re, 4096);
        CHECK(nr == 300 + n * 61); /* the 300 given, 30 each side of each peak and the peak */
    }
    cJSON_Delete(mj);
    run_free(&k);
    plot_end(&pr);
    scratch_close(&d);
}

/* PNG: the signature and the IHDR width */
static int png_width(const char *path)
{
    unsigned char h[24];
    FILE *f = fopen(path, "rb");
    size_t n = f ? fread(h, 1, sizeof h, f) : 0;
    if (f) fclose(f);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    if (n < 24 || memcmp(h, sig, 8) || memcmp(h + 12, "IHDR", 4)) return -1;
    return (h[16] << 24) | (h[17] << 16) | (h[18] << 8) | h[19];
}

/* PDF: the page count poppler's pdfinfo reads, -1 if it cannot parse the file */
static int pdf_pages(const char *path)
{
    char cmd[512], line[256];
    snprintf(cmd, sizeof cmd, "pdfinfo '%s' 2>/dev/null", path);
    FILE *f = popen(cmd, "r");
    int pages = -1;
    while (f && fgets(line, sizeof line, f))
        sscanf(line, "Pages: %d", &pages);
    if (f && pclose(f) != 0) pages = -1;
    return pages;
}

/* PNG and PDF of every plot type: valid files (signature and size; pdfinfo parses the
 * PDF), one PDF page per section at least. Without the plugin geardyn-raster.so (a build
 * without librsvg/cairo) they are refused with exit 2 naming it (tests/plot/test_raster.c). */
TEST(png_and_pdf_of_every_plot)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    static const struct {
        const char *args;
        int sections;
    } runs[] = {
        {"modal examples/chen1998_gear_pair.yaml --plot %s", 1},
        {"campbell examples/kumar2011_coupled.yaml --speeds 0:3000rpm:4 --modes 4 --plot %s", 1},
        {"frf examples/kumar2011_coupled.yaml --input torque:motor --output mesh:mesh "
         "--freq 100:26000:20 --plot %s",
         1},
        {"unbalance examples/chen1998_gear_pair.yaml --speeds 100:6000:8 --plot %s", 1},
        {"transient examples/ducati_timing_geartrain.yaml --revolutions 0.2 --quiet --plot %s", 1},
        {"mesh-stiffness examples/rig2018_pair.yaml --cycles 2 --points 90 --plot %s", 1},
        {"periodic tests/plot/mathieu_pair.yaml --speeds 680:730:5 --harmonics 4 --record "
         "mesh:m:force --plot %s",
         1},
        {"transient tests/plot/runup_pair.yaml --sweep-speeds 6000:8000rpm:3 --poincare shaft_a "
         "--points 8 --settle 10rev --waterfall gear_a.x --quiet --plot %s",
         1},
        {"report tests/plot/study.yaml --speeds 0:6000rpm:5 --freq-points 40 --out %s", 6},
    };
    gd_error err;
    gd_error_clear(&err);
    int can = gd_plot_check_path("/tmp/x.png", NULL, &err) == GD_OK;
    for (size_t k = 0; k < sizeof runs / sizeof runs[0]; k++)
        for (int pdf = 0; pdf < 2; pdf++) {
            char path[256], args[1024];
            snprintf(path, sizeof path, "%s/fig%zu.%s", d.dir, k, pdf ? "pdf" : "png");
            snprintf(args, sizeof args, runs[k].args, path);
            run_result r;
            run(&d, &r, "%s", args);
            if (!can) {
                CHECK(r.code == 2 && contains(r.err, "geardyn-raster.so") && !file_exists(path));
            } else if (pdf) {
                CHECK(r.code == 0);
                int n = pdf_pages(path);
                CHECK(n >= runs[k].sections);
                if (r.code || n < runs[k].sections)
                    fprintf(stderr, "  %s: %d pages\n", args, n), show(&r);
            } else {
                CHECK(r.code == 0);
                /* figures at twice the SVG's 960 px; a report (taller than 8000 px) at 1x */
                CHECK(png_width(path) == (runs[k].sections > 1 ? 960 : 1920));
                if (r.code) show(&r);
            }
            run_free(&r);
        }
    scratch_close(&d);
}

/* The run-up waterfall (transient --sweep-speeds --waterfall): the order lines lie at
 * order x speed / 2 pi, the order cuts are the --json order amplitudes, one cascade curve
 * per speed; and the 1x cut of the run-up through the pair's lateral critical speed peaks
 * at the 1x critical speed of `campbell` within half the speed step (the run's resolution). */
TEST(waterfall_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "transient tests/plot/runup_pair.yaml --sweep-speeds 6800:8400rpm:9 --poincare "
               "shaft_a --points 32 --settle 30rev --record gear_a.x --waterfall gear_a.x --quiet "
               "--json --plot %s");
    run_result rc;
    run(&d, &rc, "campbell tests/plot/runup_pair.yaml --speeds 0:9000rpm:31 --json");
    CHECK(rc.code == 0);
    cJSON *cj = cJSON_Parse(rc.out);
    const cJSON *wf = pr.json ? cJSON_GetObjectItem(pr.json, "waterfall") : NULL;
    svg *s = &pr.s;
    CHECK(wf != NULL && cj != NULL);
    if (wf && cj && s->ctx) {
        const cJSON *orders = cJSON_GetObjectItem(wf, "orders");
        const cJSON *spectra = cJSON_GetObjectItem(wf, "spectra");
        int ns = cJSON_GetArraySize(spectra), no = cJSON_GetArraySize(orders);
        CHECK(ns == 9 && no == 3); /* 1x shaft_a, 1x shaft_b, mesh 16x shaft_a */
        double w0 = 6800 * PI / 30, w1 = 8400 * PI / 30;
        CHECK(fabs(jnum(cJSON_GetArrayItem(spectra, 0), "speed_rad_s") - w0) < 1e-9 * w0);
        static double x[64], y[64];
        /* the mesh order line of the cascade: f = 16 x speed / 2 pi at the ends of the range
         * (the axis ends above 16 x 8400 rpm / 60, so the line is not cut) */
        CHECK(trace_numbers(s, TRACE("gear_a.x: cascade", "mesh 16x shaft_a"), "data-x", x, 4) ==
              2);
        CHECK(trace_numbers(s, TRACE("gear_a.x: cascade", "mesh 16x shaft_a"), "data-y", y, 4) ==
              2);
        CHECK(fabs(x[0] - 16 * w0 / (2 * PI)) < 1e-9 * x[0] &&
              fabs(x[1] - 16 * w1 / (2 * PI)) < 1e-9 * x[1]);
        CHECK(fabs(y[0] - 6800) < 1e-9 * 6800 && fabs(y[1] - 8400) < 1e-9 * 8400);
        /* the same line on the colour map, axes swapped, named on the plot */
        CHECK(trace_numbers(s, TRACE("gear_a.x: colour map", "1x shaft_a"), "data-y", y, 4) == 2);
        CHECK(fabs(y[0] - w0 / (2 * PI)) < 1e-9 * y[0] && fabs(y[1] - w1 / (2 * PI)) < 1e-9 * y[1]);
        CHECK(count(s, "//s:text[@class='label'][.='mesh 16x shaft_a']") == 2);
        /* one cascade curve per speed */
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'gear_a.x: cascade')]/"
                       "s:g[@class='trace'][contains(@data-name,' rpm')]") == 9);
        /* the order cuts are the --json amplitudes */
        const cJSON *o1 = NULL;
        for (int k = 0; k < no; k++)
            if (!strcmp(cJSON_GetObjectItem(cJSON_GetArrayItem(orders, k), "label")->valuestring,
                        "1x shaft_a"))
                o1 = cJSON_GetArrayItem(orders, k);
        CHECK(o1 != NULL);
        int n = trace_numbers(s, TRACE("gear_a.x: order cuts", "1x shaft_a"), "data-y", y, 64);
        CHECK(n == ns);
        int peak = 0;
        for (int k = 0; o1 && k < n; k++) {
            double a = jat(cJSON_GetObjectItem(o1, "amplitude"), k);
            CHECK(same(y[k], a));
            if (y[k] > y[peak]) peak = k;
        }
        /* the peak speed against campbell's nearest 1x shaft_a critical speed */
        double speak = 6800 + 200.0 * peak, best = INFINITY;
        const cJSON *cs = cJSON_GetObjectItem(cj, "critical_speeds");
        for (int k = 0; k < cJSON_GetArraySize(cs); k++) {
            const cJSON *c = cJSON_GetArrayItem(cs, k);
            if (!strcmp(cJSON_GetObjectItem(c, "order")->valuestring, "1x shaft_a") &&
                fabs(jnum(c, "speed_rpm") - speak) < fabs(best - speak))
                best = jnum(c, "speed_rpm");
        }
        CHECK(fabs(speak - best) <= 100); /* 7600 rpm against 7589.26 rpm */
        if (fabs(speak - best) > 100)
            fprintf(stderr, "  1x peak %g rpm, critical %g rpm\n", speak, best);
    }
    cJSON_Delete(cj);
    run_free(&rc);
    plot_end(&pr);
    scratch_close(&d);
}

/* The order-tracked waterfall of a speed ramp (transient --speed-ramp --waterfall): the
 * order cuts are the --json amplitudes, the order map's 1x line stands at order 1 over
 * the blocks' speeds, one cascade curve per block. */
TEST(ramp_waterfall_plot_matches_json)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "transient tests/transient/runup_rotor.yaml --speed-ramp 5000:8000rpm --duration "
               "0.5s --record gear48.x --waterfall gear48.x --revs-per-block 8 --method galpha "
               "--step 1e-4 --quiet --json --plot %s");
    const cJSON *wf = pr.json ? cJSON_GetObjectItem(pr.json, "waterfall") : NULL;
    svg *s = &pr.s;
    CHECK(wf != NULL);
    if (wf && s->ctx) {
        const cJSON *spectra = cJSON_GetObjectItem(wf, "spectra");
        const cJSON *o1 = cJSON_GetArrayItem(cJSON_GetObjectItem(wf, "orders"), 0);
        int ns = cJSON_GetArraySize(spectra);
        CHECK(ns > 5);
        static double x[256], y[256];
        int n = trace_numbers(s, TRACE("gear48.x: order cuts", "1x driving"), "data-y", y, 256);
        CHECK(n == ns);
        for (int k = 0; k < n && k < ns; k++)
            CHECK(same(y[k], jat(cJSON_GetObjectItem(o1, "amplitude"), k)));
        n = trace_numbers(s, TRACE("gear48.x: order map", "1x driving"), "data-x", x, 4);
        CHECK(n == 2 && x[0] == 1 && x[1] == 1);
        CHECK(trace_numbers(s, TRACE("gear48.x: order map", "1x driving"), "data-y", y, 4) == 2);
        CHECK(same(y[0], jnum(cJSON_GetArrayItem(spectra, 0), "speed_rpm")));
        CHECK(same(y[1], jnum(cJSON_GetArrayItem(spectra, ns - 1), "speed_rpm")));
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'gear48.x: cascade')]/"
                       "s:g[@class='trace'][contains(@data-name,' rpm')]") == ns);
    }
    plot_end(&pr);
    scratch_close(&d);
}

/* The periodic plot names the harmonics by the orders they are: on the two-stage
 * helical gearbox the period is the common period of both meshes (mesh 1 is harmonic 36,
 * mesh 2 harmonic 11), so the curves are the two mesh orders and 2 x, 3 x
 * mesh 2, each the --json amplitude of its harmonic (not harmonics 1-4, which are noise
 * there). */
TEST(periodic_orders_named)
{
    scratch d;
    REQUIRE(scratch_open(&d));
    plot_run pr;
    plot_start(gd_ts_, &pr, &d,
               "periodic examples/helical_two_stage.yaml --speeds 3000rpm:3100rpm:2 --harmonics 36 "
               "--no-estimate --no-stability --record mesh:pair1:force --json --plot %s");
    svg *s = &pr.s;
    cJSON *j = pr.json;
    if (j && s->ctx) {
        const cJSON *pts = cJSON_GetObjectItem(j, "points");
        REQUIRE(cJSON_GetArraySize(pts) == 2);
#define AMP "amplitudes at the excitation orders"
        static const struct {
            const char *name;
            int k;
        } want[4] = {{"mesh pair2 22x shaft2", 11},
                     {"2 x mesh pair2 22x shaft2", 22},
                     {"3 x mesh pair2 22x shaft2", 33},
                     {"mesh pair1 52x shaft1", 36}};
        CHECK(count(s, "//s:g[@class='panel'][starts-with(@data-title,'" AMP "')]/"
                       "s:g[@class='trace']") == 4);
        for (int c = 0; c < 4; c++) {
            char xp[300];
            double y[4];
            snprintf(xp, sizeof xp,
                     "//s:g[@class='panel'][starts-with(@data-title,'" AMP
                     "')]/s:g[@class='trace'][@data-name='%s']",
                     want[c].name);
            CHECK(trace_numbers(s, xp, "data-y", y, 4) == 2);
            for (int i = 0; i < 2; i++) {
                const cJSON *a = cJSON_GetObjectItem(
                    cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetArrayItem(pts, i), "records"),
                                        "mesh:pair1:force"),
                    "amplitudes");
                CHECK(same(y[i], jat(a, want[c].k)));
            }
        }
        /* mesh 1 carries the 50 N m load's fluctuation: far above harmonic 1 of the period */
        const cJSON *a0 = cJSON_GetObjectItem(
            cJSON_GetObjectItem(cJSON_GetObjectItem(cJSON_GetArrayItem(pts, 0), "records"),
                                "mesh:pair1:force"),
            "amplitudes");
        CHECK(jat(a0, 36) > 100 * jat(a0, 1));
    }
    plot_end(&pr);
    scratch_close(&d);
}

RUN_TESTS(T(campbell_plot_matches_json), T(frf_plot_matches_json), T(unbalance_plot_matches_json),
          T(mesh_stiffness_plot_matches_json), T(modal_and_transient_plots),
          T(periodic_plot_matches_json), T(report_has_every_section), T(html_is_self_contained),
          T(bad_plot_requests_write_nothing), T(png_and_pdf_of_every_plot),
          T(pure_tilt_mode_drawn_alone), T(campbell_pairs_stay_pairs),
          T(campbell_limit_labels_margins), T(units_follow_the_command_line), T(frf_peaks_located),
          T(waterfall_plot_matches_json), T(ramp_waterfall_plot_matches_json),
          T(periodic_orders_named))
