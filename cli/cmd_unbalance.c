/* geardyn unbalance MODEL --speeds FROM:TO:COUNT: steady response to the model's
 * unbalances: amplitudes and phases, orbits, bearing and mesh forces, torsion. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "operating_point.h"
#include "options.h"
#include "sweep_output.h"

#define PI 3.14159265358979323846
#define MAXOUT 64

typedef struct unbalance_args {
    gd_unbalance_options opt;
    const char *speeds, *coupling, *out, *outs[MAXOUT], *plot, *units;
    int nouts, json;
    double orbit_speed;
    gd_cli_sets sets;
    gd_cli_operating op;
} unbalance_args;

#define F(m) offsetof(unbalance_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("speeds", GD_CLI_STRING, F(speeds), "FROM:TO:COUNT",
               "reference speeds, units allowed: 0:12000rpm:241", .required = 1),
    GD_CLI_ROW("output", GD_CLI_LIST, F(outs), "WHAT",
               "repeatable: NODE.DOF (amplitude, phase), orbit:NODE (major and minor semi-axes, "
               "whirl), mesh:NAME (dynamic mesh force), bearing:NAME.DIR (bearing force). "
               "Default: x, y, rz and the orbit of every unbalanced node, every mesh force, x and "
               "y of every bearing",
               .aux = F(nouts), .hi = MAXOUT),
    GD_CLI_ROW_THREADS(unbalance_args, opt.nthreads, "speeds"),
    GD_CLI_ROWS_OPERATING(unbalance_args, op),
    GD_CLI_ROW_MODEL(unbalance_args, coupling, sets),
    GD_CLI_ROW_JSON(unbalance_args, json),
    GD_CLI_ROW_OUT(unbalance_args, out, "write DIR/unbalance.csv and DIR/orbits.csv (long form)"),
    GD_CLI_ROW_UNITS(unbalance_args, units),
    GD_CLI_ROW_PLOT(unbalance_args, plot),
    GD_CLI_ROW("orbit-speed", GD_CLI_QUANTITY, F(orbit_speed), "V",
               "the plot's orbits at the nearest speed to V", .lo = GD_CLI_ZERO_OR_MORE,
               .def = "where the largest orbit is largest", .qty = GD_QTY_ANGULAR_SPEED,
               .example = "3000rpm"),
    {0}};
static const gd_cli_command CMD = {
    .name = "unbalance",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "Steady response to the unbalances of the model, each turning with its own shaft.\n"
        "Shafts with different |speed ratio| give different harmonics (order = |ratio| of the\n"
        "reference speed); each output is reported per harmonic.\n"};

static int add_default_outputs(const gd_system *s, gd_probe *pr, int *np, int *orb, int *nb)
{
    const gd_model *m = s->model;
    for (int u = 0; u < m->nunbalances; u++) {
        int node = m->unbalances[u].node, dup = 0;
        for (int k = 0; k < *nb; k++)
            dup |= orb[k] == node;
        if (dup) continue;
        static const gd_dof ds[3] = {GD_X, GD_Y, GD_RZ};
        for (int d = 0; d < 3 && *np < MAXOUT; d++) {
            int i = gd_system_dof(s, node, ds[d]);
            if (i < 0) continue;
            pr[*np] = (gd_probe){.element = NULL, .index = i};
            snprintf(pr[*np].name, sizeof pr[*np].name, "%s.%s", m->nodes[node].name,
                     gd_dof_names[ds[d]]);
            (*np)++;
        }
        if (*nb < MAXOUT && gd_system_dof(s, node, GD_X) >= 0 && gd_system_dof(s, node, GD_Y) >= 0)
            orb[(*nb)++] = node;
    }
    *np += gd_probe_defaults(s, pr + *np, MAXOUT - *np);
    return 0;
}

int gd_cmd_unbalance(int argc, char **argv)
{
    unbalance_args a = {0};
    gd_unbalance_options_init(&a.opt);
    const char *cmd = "unbalance", *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_unbalance_options opt = a.opt;
    const char *speeds = a.speeds, *out = a.out, *plot = a.plot, *const *outs = a.outs;
    int nouts = a.nouts;
    double *sp = NULL;
    gd_cli_units u = {.speed_rpm = 1, .freq_hz = 1}; /* rpm unless rad/s is written */
    if (gd_cli_units_parse(cmd, a.units, speeds, NULL, &u)) return GD_EXIT_INPUT;
    rc = gd_cli_parse_range(cmd, "--speeds", speeds, &sp, &opt.nspeeds);
    if (rc) return rc;
    opt.speeds = sp;
    gd_error err;
    gd_error_clear(&err);
    if ((out && gd_outdir_check(out, &err)) || (plot && gd_plot_check_path(plot, NULL, &err))) {
        free(sp);
        return gd_cli_report(&err);
    }
    gd_model *m;
    gd_system *s;
    if ((rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s))) {
        free(sp);
        return rc;
    }
    gd_probe pr[MAXOUT];
    int orb[MAXOUT], np = 0, nb = 0;
    gd_unbalance_result *r = NULL;
    gd_series *ser = NULL;
    int *bad = NULL;
    if ((rc = gd_cli_operating_apply(s, &a.op, -1, 0))) goto done;
    for (int k = 0; k < nouts; k++) {
        if (!strncmp(outs[k], "orbit:", 6)) {
            int node = gd_model_find_node(m, outs[k] + 6);
            if (node < 0) {
                rc = gd_cli_usage_error(cmd, "--output: unknown node '%s'", outs[k] + 6);
                goto done;
            }
            if (gd_system_dof(s, node, GD_X) < 0 || gd_system_dof(s, node, GD_Y) < 0) {
                rc = gd_cli_usage_error(
                    cmd, "--output: node '%s' has no active x and y for an orbit", outs[k] + 6);
                goto done;
            }
            orb[nb++] = node;
        } else if ((rc = gd_cli_parse_probe(cmd, "--output", s, outs[k], &pr[np++]))) {
            goto done;
        }
    }
    if (!nouts) add_default_outputs(s, pr, &np, orb, &nb);
    opt.outputs = pr;
    opt.noutputs = np;
    opt.orbit_nodes = orb;
    opt.norbits = nb;
    gd_blas_set_threads(1);
    if (gd_unbalance_response(s, &opt, &r, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    /* an amplitude past 1e308 at a speed the system solves (an unbalance of 1e308
     * kg m printed inf and NaN with exit 0, issue 38 M7) */
    for (int h = 0; h < r->nharmonics; h++)
        for (int o = 0; o < r->noutputs; o++)
            for (int k = 0; k < r->nspeeds; k++) {
                size_t at = ((size_t)h * r->noutputs + o) * r->nspeeds + k;
                if (r->singular[k] || (isfinite(r->re[at]) && isfinite(r->im[at]))) continue;
                gd_error_set(&err, GD_EINPUT, file, 0, 0, "unbalances",
                             "check the unbalances' amounts (kg m) and the speeds",
                             "the response overflows at %g rad/s (amplitudes beyond 1e308)",
                             r->speeds[k]);
                rc = gd_cli_report(&err);
                goto done;
            }
    if ((bad = calloc((size_t)r->nspeeds + 1, sizeof *bad)))
        gd_cli_operating_scan(s, r->speeds, r->nspeeds, bad);
    if (plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_unbalance(s, &opt, r, a.orbit_speed, &p, &err);
        if (!pst && !u.speed_rpm) gd_plot_convert_x(p, "rpm", "rad/s", 3.14159265358979323846 / 30);
        if ((rc = gd_cli_plot_finish(pst, p, &err, plot))) goto done;
    }
    int nh = r->nharmonics, ns = r->nspeeds;
    ser = calloc((size_t)(nh * np > 0 ? nh * np : 1), sizeof *ser);
    if (!ser) {
        rc = GD_EXIT_FAIL;
        goto done;
    }
    for (int h = 0; h < nh; h++)
        for (int o = 0; o < np; o++) {
            gd_series *z = &ser[h * np + o];
            snprintf(z->name, sizeof z->name, "%s", pr[o].name);
            z->harmonic = r->harmonics[h].order;
            z->xname = "speed_rad_s";
            z->n = ns;
            z->x = r->speeds;
            z->re = r->re + ((size_t)h * np + o) * ns;
            z->im = r->im + ((size_t)h * np + o) * ns;
        }
    if (out) {
        gd_outdir od;
        FILE *f = NULL;
        if (gd_outdir_begin(&od, out, &err)) {
            rc = gd_cli_report(&err);
            goto done;
        }
        if (!(f = gd_outdir_open(&od, "unbalance.csv", &err))) goto fail;
        fprintf(f, "output,harmonic_order,speed_rad_s,speed_rpm,magnitude,phase_deg,real,imag\n");
        for (int k = 0; k < nh * np; k++)
            for (int i = 0; i < ns; i++) {
                double re = ser[k].re[i], im = ser[k].im[i];
                fprintf(f, "%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", ser[k].name,
                        ser[k].harmonic, r->speeds[i], r->speeds[i] * 30 / PI, hypot(re, im),
                        atan2(im, re) * 180 / PI, re, im);
            }
        if (gd_outdir_close(&od, f, "unbalance.csv", &err)) goto fail;
        if (!(f = gd_outdir_open(&od, "orbits.csv", &err))) goto fail;
        fprintf(f, "node,harmonic_order,speed_rad_s,speed_rpm,major,minor,angle_deg,whirl\n");
        for (int h = 0; h < nh; h++)
            for (int b = 0; b < nb; b++)
                for (int i = 0; i < ns; i++) {
                    const gd_orbit *ob = &r->orbits[((size_t)h * nb + b) * ns + i];
                    fprintf(f, "%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.6g,%s\n", m->nodes[orb[b]].name,
                            r->harmonics[h].order, r->speeds[i], r->speeds[i] * 30 / PI, ob->major,
                            ob->minor, ob->angle * 180 / PI, gd_whirl_names[ob->whirl]);
                }
        if (gd_outdir_close(&od, f, "orbits.csv", &err) || gd_outdir_commit(&od, &err)) goto fail;
        goto written;
    fail:
        gd_outdir_abort(&od);
        rc = gd_cli_report(&err);
        goto done;
    }
written:
    if (a.json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "model", m->file);
        cJSON *ha = cJSON_AddArrayToObject(o, "harmonics");
        for (int h = 0; h < nh; h++) {
            cJSON *x = cJSON_CreateObject();
            cJSON_AddNumberToObject(x, "order", r->harmonics[h].order);
            cJSON_AddNumberToObject(x, "unbalances", r->harmonics[h].nunbalances);
            cJSON_AddItemToArray(ha, x);
        }
        cJSON *arr = cJSON_AddArrayToObject(o, "outputs");
        for (int k = 0; k < nh * np; k++)
            cJSON_AddItemToArray(arr, gd_series_json(&ser[k]));
        cJSON *oa = cJSON_AddArrayToObject(o, "orbits");
        for (int h = 0; h < nh; h++)
            for (int b = 0; b < nb; b++) {
                cJSON *x = cJSON_CreateObject();
                cJSON_AddStringToObject(x, "node", m->nodes[orb[b]].name);
                cJSON_AddNumberToObject(x, "harmonic_order", r->harmonics[h].order);
                cJSON *sa = cJSON_AddArrayToObject(x, "speed_rad_s"),
                      *ma = cJSON_AddArrayToObject(x, "major");
                cJSON *mi = cJSON_AddArrayToObject(x, "minor"),
                      *an = cJSON_AddArrayToObject(x, "angle_deg");
                cJSON *wh = cJSON_AddArrayToObject(x, "whirl");
                for (int i = 0; i < ns; i++) {
                    const gd_orbit *ob = &r->orbits[((size_t)h * nb + b) * ns + i];
                    cJSON_AddItemToArray(sa, cJSON_CreateNumber(r->speeds[i]));
                    cJSON_AddItemToArray(ma, gd_cli_json_number(ob->major));
                    cJSON_AddItemToArray(mi, gd_cli_json_number(ob->minor));
                    cJSON_AddItemToArray(an, gd_cli_json_number(ob->angle * 180 / PI));
                    cJSON_AddItemToArray(wh, cJSON_CreateString(gd_whirl_names[ob->whirl]));
                }
                cJSON_AddItemToArray(oa, x);
            }
        gd_cli_operating_json(o, s, &a.op, r->speeds, bad, bad ? ns : 0);
        gd_cli_print_json(stdout, o);
        cJSON_Delete(o);
    } else {
        for (int h = 0; h < nh; h++) {
            printf("%s: unbalance response, harmonic %g x reference speed (%d unbalance%s)\n\n",
                   m->file, r->harmonics[h].order, r->harmonics[h].nunbalances,
                   r->harmonics[h].nunbalances == 1 ? "" : "s");
            gd_series_table(stdout, ser + (size_t)h * np, np, gd_cli_speed_unit(&u),
                            gd_cli_speed_out(&u, 1.0));
            for (int b = 0; b < nb; b++) {
                printf("\norbit of %s\n%12s %12s %12s %10s  %s\n", m->nodes[orb[b]].name,
                       gd_cli_speed_unit(&u), "major", "minor", "angle(deg)", "whirl");
                for (int i = 0; i < ns; i++) {
                    const gd_orbit *ob = &r->orbits[((size_t)h * nb + b) * ns + i];
                    printf("%12.6g %12.5g %12.5g %10.2f  %s\n", gd_cli_speed_out(&u, r->speeds[i]),
                           ob->major, ob->minor, ob->angle * 180 / PI, gd_whirl_names[ob->whirl]);
                }
            }
            printf("\n");
        }
        gd_cli_operating_print(s, &a.op, 1);
    }
done:
    free(bad);
    free(ser);
    gd_unbalance_free(r);
    gd_system_free(s);
    gd_model_free(m);
    free(sp);
    return rc;
}
