/* geardyn unbalance MODEL --speeds FROM:TO:COUNT: steady response to the model's
 * unbalances: amplitudes and phases, orbits, bearing and mesh forces, torsion. */
#include <cblas.h>
#include <getopt.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "sweep_output.h"

static const char USAGE[] =
    "usage: geardyn unbalance MODEL.yaml --speeds FROM:TO:COUNT [--output WHAT ...]\n"
    "                         [--threads N] [--coupling LEVEL] [--dofs LIST] [--set "
    "PATH=VALUE]...\n"
    "                         [--json] [--out DIR] [--plot FILE] [--orbit-speed VALUE]\n\n"
    "Steady response to the unbalances of the model, each turning with its own shaft.\n"
    "Shafts with different |speed ratio| give different harmonics (order = |ratio| of the\n"
    "reference speed); each output is reported per harmonic.\n\n"
    "  --speeds FROM:TO:COUNT  reference speeds, units allowed: 0:12000rpm:241 (required)\n"
    "  --output WHAT     repeatable: NODE.DOF (amplitude, phase), orbit:NODE (major and\n"
    "                    minor semi-axes, whirl), mesh:NAME (dynamic mesh force),\n"
    "                    bearing:NAME.DIR (bearing force). Default: x, y, rz and the orbit\n"
    "                    of every unbalanced node, every mesh force, x and y of every bearing\n"
    "  --threads N       parallel threads over speeds (default: all cores)\n"
    "  --coupling LEVEL  torsional | lateral-torsional | full: every mesh's level\n"
    "  --dofs LIST       keep only these node DOFs, e.g. x,y,rz\n"
    "  --set PATH=VALUE  change a value of the model file, e.g.\n"
    "                    --set meshes.mesh.stiffness=3e8N/m (repeatable; docs/model-format.md)\n"
    "  --json            one JSON object on stdout\n"
    "  --out DIR         write DIR/unbalance.csv and DIR/orbits.csv (long form)\n" GD_CLI_UNITS_HELP
        GD_CLI_PLOT_HELP
    "  --orbit-speed V   the plot's orbits at the nearest speed to V (default: where the\n"
    "                    largest orbit is largest)\n";

#define PI 3.14159265358979323846
#define MAXOUT 64

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
            pr[*np] = (gd_probe){.kind = GD_PROBE_DOF, .index = i};
            snprintf(pr[*np].name, sizeof pr[*np].name, "%s.%s", m->nodes[node].name,
                     gd_dof_names[ds[d]]);
            (*np)++;
        }
        if (*nb < MAXOUT && gd_system_dof(s, node, GD_X) >= 0 && gd_system_dof(s, node, GD_Y) >= 0)
            orb[(*nb)++] = node;
    }
    for (int g = 0; g < m->nmeshes && *np < MAXOUT; g++) {
        pr[*np] = (gd_probe){.kind = GD_PROBE_MESH, .index = g};
        snprintf(pr[*np].name, sizeof pr[*np].name, "mesh:%s", m->meshes[g].name);
        (*np)++;
    }
    for (int b = 0; b < m->nbearings; b++)
        for (int d = 0; d < 2 && *np < MAXOUT; d++) {
            if (gd_system_dof(s, m->bearings[b].node, (gd_dof)d) < 0) continue;
            pr[*np] = (gd_probe){.kind = GD_PROBE_BEARING, .index = b, .dir = (gd_dof)d};
            snprintf(pr[*np].name, sizeof pr[*np].name, "bearing:%s.%s", m->bearings[b].name,
                     gd_dof_names[d]);
            (*np)++;
        }
    return 0;
}

int gd_cmd_unbalance(int argc, char **argv)
{
    static const struct option opts[] = {{"speeds", required_argument, 0, 's'},
                                         {"output", required_argument, 0, 'O'},
                                         {"threads", required_argument, 0, 't'},
                                         {"coupling", required_argument, 0, 'c'},
                                         {"json", no_argument, 0, 'j'},
                                         {"out", required_argument, 0, 'o'},
                                         GD_CLI_SET_OPTION,
                                         GD_CLI_DOFS_OPTION,
                                         {"help", no_argument, 0, 'h'},
                                         GD_CLI_PLOT_OPTION,
                                         {"units", required_argument, 0, 'U'},
                                         {"orbit-speed", required_argument, 0, 'B'},
                                         {0, 0, 0, 0}};
    const char *cmd = "unbalance", *speeds = NULL, *coupling = NULL, *out = NULL, *outs[MAXOUT],
               *plot = NULL, *orbit_speed = NULL, *units = NULL;
    int nouts = 0, json = 0, c;
    gd_cli_sets sets = {0};
    gd_unbalance_options opt;
    gd_unbalance_options_init(&opt);
    optind = 1;
    opterr = 0;
    while ((c = getopt_long(argc, argv, ":h", opts, NULL)) != -1) {
        switch (c) {
        case 's':
            speeds = optarg;
            break;
        case 'O':
            if (nouts == MAXOUT) return gd_cli_usage_error(cmd, "at most %d outputs", MAXOUT);
            outs[nouts++] = optarg;
            break;
        case 't':
            if (gd_cli_parse_threads(cmd, optarg, &opt.nthreads)) return GD_EXIT_INPUT;
            break;
        case 'c':
            coupling = optarg;
            break;
        case GD_CLI_OPT_SET:
            if (gd_cli_add_set(cmd, &sets, optarg)) return GD_EXIT_INPUT;
            break;
        case GD_CLI_OPT_DOFS:
            sets.dofs = optarg;
            break;
        case 'j':
            json = 1;
            break;
        case 'o':
            out = optarg;
            break;
        case GD_CLI_OPT_PLOT:
            plot = optarg;
            break;
        case 'U':
            units = optarg;
            break;
        case 'B':
            orbit_speed = optarg;
            break;
        case 'h':
            fputs(USAGE, stdout);
            return GD_EXIT_OK;
        default:
            return gd_cli_option_error(cmd, c, argv, optind);
        }
    }
    if (optind != argc - 1) return gd_cli_usage_error(cmd, "give exactly one model file");
    if (!speeds) return gd_cli_usage_error(cmd, "--speeds FROM:TO:COUNT is required");
    double *sp = NULL;
    gd_cli_units u = {.speed_rpm = 1, .freq_hz = 1}; /* rpm unless rad/s is written */
    if (gd_cli_units_parse(cmd, units, speeds, NULL, &u)) return GD_EXIT_INPUT;
    int rc = gd_cli_parse_range(cmd, "--speeds", speeds, &sp, &opt.nspeeds);
    if (rc) return rc;
    opt.speeds = sp;
    gd_error err;
    gd_error_clear(&err);
    double at = 0;
    if (orbit_speed && gd_cli_parse_speed(cmd, orbit_speed, &at)) {
        free(sp);
        return GD_EXIT_INPUT;
    }
    if ((out && gd_outdir_check(out, &err)) || (plot && gd_plot_check_path(plot, NULL, &err))) {
        free(sp);
        return gd_cli_report(&err);
    }
    gd_model *m;
    gd_system *s;
    if ((rc = gd_cli_load(argv[optind], &sets, coupling, &m, &s))) {
        free(sp);
        return rc;
    }
    gd_probe pr[MAXOUT];
    int orb[MAXOUT], np = 0, nb = 0;
    gd_unbalance_result *r = NULL;
    gd_series *ser = NULL;
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
    openblas_set_num_threads(1);
    if (gd_unbalance_response(s, &opt, &r, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    if (plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_unbalance(s, &opt, r, at, &p, &err);
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
                double a = ser[k].re[i], b = ser[k].im[i];
                fprintf(f, "%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", ser[k].name,
                        ser[k].harmonic, r->speeds[i], r->speeds[i] * 30 / PI, hypot(a, b),
                        atan2(b, a) * 180 / PI, a, b);
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
    if (json) {
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
    }
done:
    free(ser);
    gd_unbalance_free(r);
    gd_system_free(s);
    gd_model_free(m);
    free(sp);
    return rc;
}
