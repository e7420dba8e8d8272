/* geardyn frf MODEL --input WHAT --output WHAT --freq FROM:TO:COUNT: frequency
 * response functions, direct or by modal summation, and directional FRFs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "geardyn/blas.h"
#include "cli.h"
#include "operating_point.h"
#include "options.h"
#include "sweep_output.h"

#define MAXOUT 16

typedef struct frf_args {
    gd_frf_options opt;
    const char *input, *freq, *speed, *coupling, *out, *outs[MAXOUT], *plot, *units;
    int nouts, json;
    gd_cli_sets sets;
    gd_cli_operating op;
} frf_args;

#define F(m) offsetof(frf_args, m)
static const gd_cli_opt OPTS[] = {
    GD_CLI_ROW("input", GD_CLI_STRING, F(input), "WHAT", "the input (above)", .required = 1,
               .once = 1),
    GD_CLI_ROW("output", GD_CLI_LIST, F(outs), "WHAT",
               "an output (above); repeatable, or a comma list", .required = 1, .aux = F(nouts),
               .hi = MAXOUT),
    GD_CLI_ROW("freq", GD_CLI_STRING, F(freq), "FROM:TO:COUNT",
               "frequencies, units allowed: 0:26000:1001 (rad/s), 0:5kHz:501", .required = 1),
    GD_CLI_ROW("speed", GD_CLI_STRING, F(speed), "VALUE",
               "reference shaft speed (gyroscopics, bearing tables); default: model's"),
    GD_CLI_ROW("method", GD_CLI_CHOICE, F(opt.method), "M",
               "direct (sparse complex solve per frequency) or modal (summation over left/right "
               "eigenvectors, rigid-body modes exact)",
               .def = "direct", .word = "direct|modal"),
    GD_CLI_ROW("modes", GD_CLI_INT, F(opt.nmodes), "N|all",
               "modes summed by --method modal (default all; fewer truncates)", .lo = 1,
               .hi = 1000000, .word = "all", .ival = 0),
    GD_CLI_ROW("type", GD_CLI_CHOICE, F(opt.quantity), "T",
               "receptance, mobility or accelerance (DOF outputs)", .def = "receptance",
               .word = "receptance|mobility|accelerance"),
    GD_CLI_ROW_THREADS(frf_args, opt.nthreads, "frequencies"),
    GD_CLI_ROWS_OPERATING(frf_args, op),
    GD_CLI_ROW_MODEL(frf_args, coupling, sets),
    GD_CLI_ROW_JSON(frf_args, json),
    GD_CLI_ROW_OUT(frf_args, out, "write DIR/frf.csv (long form)"),
    GD_CLI_ROW_UNITS(frf_args, units),
    GD_CLI_ROW_PLOT(frf_args, plot),
    {0}};
static const gd_cli_command CMD = {
    .name = "frf",
    .args = "MODEL.yaml",
    .opts = OPTS,
    .about =
        "Response to a unit harmonic force or moment. Inputs:\n"
        "  NODE.DOF, node:NODE.DOF  force (x, y, z) or moment (rx, ry, rz) at a node, e.g. "
        "pinion.y\n"
        "  torque:NODE              torque about the shaft axis (= NODE.rz)\n"
        "  NODE.xy                  directional FRFs: forward and backward (outputs NODE.xy "
        "too)\n"
        "  planetary:SET:sun_mesh:L  planetary set SET's sun-planet (or ring_mesh) meshes at mesh\n"
        "                           harmonic L, each planet's phase applied, per unit\n"
        "                           transmission error\n"
        "Outputs (repeat --output):\n"
        "  NODE.DOF, node:NODE.DOF  displacement (or velocity/acceleration, --type)\n",
    .probes = 1};

/* --input planetary:SET:sun_mesh:L (or ring_mesh): planetary set SET's phased mesh
 * excitation at mesh harmonic L per unit static transmission error (docs/planetary.md,
 * "Planet phasing"). 0 and *re set (the caller frees re, im) when it is one, 0 and *re
 * NULL when text is another input, else the exit code of a usage error. */
static int planetary_input(const char *cmd, const gd_system *s, const char *text, double **re,
                           double **im, char *label, size_t cap)
{
    *re = *im = NULL;
    if (strncmp(text, "planetary:", 10)) return 0;
    const gd_model *m = s->model;
    char buf[256], *kind, *harm;
    snprintf(buf, sizeof buf, "%s", text + 10);
    if (!(kind = strchr(buf, ':')) || !(harm = strchr(kind + 1, ':')))
        return gd_cli_usage_error(cmd,
                                  "--input '%s': write planetary:SET:sun_mesh:L or "
                                  "planetary:SET:ring_mesh:L (L the mesh harmonic, 1, 2, ...)",
                                  text);
    *kind++ = 0;
    *harm++ = 0;
    int set = -1;
    for (int i = 0; i < m->nplanetary; i++)
        if (!strcmp(m->planetary[i].name, buf)) set = i;
    if (set < 0)
        return gd_cli_usage_error(cmd, "--input '%s': the model has no planetary set '%s'%s", text,
                                  buf, m->nplanetary ? "" : " (it has none)");
    int ring = !strcmp(kind, "ring_mesh");
    if (!ring && strcmp(kind, "sun_mesh"))
        return gd_cli_usage_error(
            cmd, "--input '%s': unknown mesh kind '%s' (sun_mesh or ring_mesh)", text, kind);
    char *end;
    long l = strtol(harm, &end, 10);
    if (*end || end == harm || l < 1 || l > 1000)
        return gd_cli_usage_error(
            cmd, "--input '%s': the harmonic '%s' is not a whole number from 1 to 1000", text,
            harm);
    *re = calloc((size_t)(s->ndof > 0 ? s->ndof : 1), sizeof **re);
    *im = calloc((size_t)(s->ndof > 0 ? s->ndof : 1), sizeof **im);
    if (!*re || !*im) return GD_EXIT_FAIL;
    gd_error err;
    if (gd_planetary_mesh_excitation(s, set, (int)l, ring, *re, *im, &err))
        return gd_cli_report(&err);
    snprintf(label, cap, "%s", text);
    return 0;
}

int gd_cmd_frf(int argc, char **argv)
{
    frf_args a = {0};
    gd_frf_options_init(&a.opt);
    const char *cmd = "frf", *file;
    int rc = gd_cli_parse(&CMD, argc, argv, &a, &file);
    if (rc) return rc < 0 ? GD_EXIT_OK : rc;
    gd_frf_options opt = a.opt;
    const char *input = a.input, *freq = a.freq, *speed = a.speed, *out = a.out, *plot = a.plot,
               *outs[MAXOUT];
    /* --output takes a comma list, as --record does */
    char *outbuf = NULL;
    int nouts = gd_cli_split_commas(cmd, "--output", a.outs, a.nouts, &outbuf, outs, MAXOUT);
    if (nouts > 0) {
        free(outbuf);
        return nouts;
    }
    nouts = -nouts;
    gd_cli_units u = {.speed_rpm = 0, .freq_hz = 0}; /* rad/s unless rpm or Hz is written */
    if (gd_cli_units_parse(cmd, a.units, speed, freq, &u)) {
        free(outbuf);
        return GD_EXIT_INPUT;
    }
    double *fr = NULL;
    rc = gd_cli_parse_range(cmd, "--freq", freq, &fr, &opt.nfreq);
    if (rc) {
        free(outbuf);
        return rc;
    }
    opt.freqs = fr;
    gd_error err;
    gd_error_clear(&err);
    if ((out && gd_outdir_check(out, &err)) || (plot && gd_plot_check_path(plot, NULL, &err))) {
        free(fr);
        free(outbuf);
        return gd_cli_report(&err);
    }
    gd_model *m;
    gd_system *s;
    if ((rc = gd_cli_load(file, &a.sets, a.coupling, &m, &s))) {
        free(fr);
        free(outbuf);
        return rc;
    }
    gd_probe probes[2 * MAXOUT];
    int inputs[2], xy = 0, np = 0;
    char inlabel[200];
    opt.speed = m->speed;
    gd_frf_result *r = NULL;
    gd_series *ser = NULL;
    double *dirbuf = NULL, *load_re = NULL, *load_im = NULL;
    int nser = 0;
    if (speed && gd_cli_parse_speed(cmd, speed, &opt.speed)) {
        rc = GD_EXIT_INPUT;
        goto done;
    }
    if ((rc = gd_cli_operating_apply(s, &a.op, opt.speed, 1))) goto done;
    if ((rc = planetary_input(cmd, s, input, &load_re, &load_im, inlabel, sizeof inlabel)))
        goto done;
    if (load_re) {
        inputs[0] = 0; /* the first DOF the load acts on, for the plot's label */
        for (int i = s->ndof - 1; i >= 0; i--)
            if (load_re[i] != 0 || load_im[i] != 0) inputs[0] = i;
    } else if ((rc = gd_cli_parse_input(cmd, s, input, &inputs[0], &xy, inlabel, sizeof inlabel))) {
        goto done;
    }
    if (xy) {
        const char *in = !strncmp(input, "node:", 5) ? input + 5 : input;
        char buf[256];
        snprintf(buf, sizeof buf, "%.*s.y", (int)strlen(in) - 3, in);
        gd_probe py;
        if ((rc = gd_cli_parse_probe(cmd, "--input", s, buf, &py))) goto done;
        inputs[1] = py.index;
        for (int k = 0; k < nouts; k++) {
            const char *o = !strncmp(outs[k], "node:", 5) ? outs[k] + 5 : outs[k];
            size_t len = strlen(o);
            if (len < 4 || strcmp(o + len - 3, ".xy")) {
                rc = gd_cli_usage_error(
                    cmd, "--output: with a directional input (%s) give outputs NODE.xy, not '%s'",
                    input, outs[k]);
                goto done;
            }
            for (int d = 0; d < 2; d++) {
                snprintf(buf, sizeof buf, "%.*s.%s", (int)len - 3, o, d ? "y" : "x");
                if ((rc = gd_cli_parse_probe(cmd, "--output", s, buf, &probes[np++]))) goto done;
            }
        }
        opt.ninputs = 2;
    } else {
        for (int k = 0; k < nouts; k++) {
            size_t len = strlen(outs[k]);
            if (len > 3 && !strcmp(outs[k] + len - 3, ".xy")) {
                rc = gd_cli_usage_error(
                    cmd, "--output '%s' is directional: give a directional input NODE.xy too",
                    outs[k]);
                goto done;
            }
            if ((rc = gd_cli_parse_probe(cmd, "--output", s, outs[k], &probes[np++]))) goto done;
        }
        opt.ninputs = 1;
    }
    if (opt.quantity != GD_FRF_RECEPTANCE)
        for (int k = 0; k < np; k++)
            if (probes[k].element) {
                rc = gd_cli_usage_error(
                    cmd, "--type %s applies to displacement outputs; '%s' is a force",
                    gd_frf_quantity_names[opt.quantity], probes[k].name);
                goto done;
            }
    opt.inputs = inputs;
    opt.outputs = probes;
    opt.noutputs = np;
    gd_blas_set_threads(1); /* parallel over frequencies instead */
    if (load_re ? gd_frf_load(s, &opt, load_re, load_im, &r, &err) : gd_frf(s, &opt, &r, &err)) {
        rc = gd_cli_report(&err);
        goto done;
    }
    if (r->nsingular)
        fprintf(
            stderr,
            "geardyn frf: note: %d frequenc%s hit a singular dynamic stiffness (a rigid-body "
            "mode at 0 rad/s or an undamped resonance); values there are null (JSON), - (tables)\n",
            r->nsingular, r->nsingular == 1 ? "y" : "ies");
    if (plot) {
        gd_plot *p = NULL;
        gd_status pst = gd_plot_frf(s, &opt, r, &p, &err);
        /* the axis in rad/s when asked for or written (plain numbers keep Hz) */
        if (!pst && !u.freq_hz && (a.units || strstr(freq, "rad/s")))
            gd_plot_convert_x(p, "Hz", "rad/s", 2 * 3.14159265358979323846);
        if ((rc = gd_cli_plot_finish(pst, p, &err, plot))) goto done;
    }
    nser = xy ? 2 * nouts : np;
    ser = calloc((size_t)nser, sizeof *ser);
    dirbuf = xy ? malloc((size_t)4 * nouts * opt.nfreq * sizeof *dirbuf) : NULL;
    if (!ser || (xy && !dirbuf)) {
        rc = GD_EXIT_FAIL;
        goto done;
    }
    for (int k = 0; k < nser; k++) {
        gd_series *z = &ser[k];
        z->xname = "frequency_rad_s";
        z->n = opt.nfreq;
        z->x = r->freqs;
        if (xy) {
            int o = k / 2, bwd = k % 2;
            double *b = dirbuf + (size_t)4 * o * opt.nfreq;
            if (!bwd)
                gd_frf_directional(r, 2 * o, 2 * o + 1, b, b + opt.nfreq, b + 2 * opt.nfreq,
                                   b + 3 * opt.nfreq);
            z->re = b + (size_t)(bwd ? 2 : 0) * opt.nfreq;
            z->im = b + (size_t)(bwd ? 3 : 1) * opt.nfreq;
            snprintf(z->name, sizeof z->name, "%s %s", outs[o], bwd ? "backward" : "forward");
            z->quantity = gd_frf_quantity_names[opt.quantity];
        } else {
            z->re = r->re + (size_t)k * opt.nfreq;
            z->im = r->im + (size_t)k * opt.nfreq;
            snprintf(z->name, sizeof z->name, "%s", probes[k].name);
            z->quantity = !probes[k].element ? gd_frf_quantity_names[opt.quantity] : "force";
        }
    }
    if (out) {
        gd_outdir od;
        FILE *f;
        if (gd_outdir_begin(&od, out, &err)) {
            rc = gd_cli_report(&err);
            goto done;
        }
        if (!(f = gd_outdir_open(&od, "frf.csv", &err))) {
            gd_outdir_abort(&od);
            rc = gd_cli_report(&err);
            goto done;
        }
        fprintf(f, "output,frequency_rad_s,frequency_hz,magnitude,phase_deg,real,imag\n");
        for (int k = 0; k < nser; k++)
            gd_series_csv(f, &ser[k]);
        if (gd_outdir_close(&od, f, "frf.csv", &err) || gd_outdir_commit(&od, &err)) {
            gd_outdir_abort(&od);
            rc = gd_cli_report(&err);
            goto done;
        }
    }
    if (a.json) {
        cJSON *o = cJSON_CreateObject();
        cJSON_AddStringToObject(o, "model", m->file);
        cJSON_AddStringToObject(o, "input", inlabel);
        cJSON_AddNumberToObject(o, "speed_rad_s", opt.speed);
        cJSON_AddStringToObject(o, "method", opt.method == GD_FRF_MODAL ? "modal" : "direct");
        if (opt.method == GD_FRF_MODAL) {
            cJSON_AddNumberToObject(o, "modes_summed", r->nmodes_used);
            cJSON_AddNumberToObject(o, "rigid_body_modes", r->nrigid);
        }
        cJSON *arr = cJSON_AddArrayToObject(o, "outputs");
        for (int k = 0; k < nser; k++)
            cJSON_AddItemToArray(arr, gd_series_json(&ser[k]));
        gd_cli_operating_json(o, s, &a.op, NULL, NULL, 0);
        gd_cli_print_json(stdout, o);
        cJSON_Delete(o);
    } else {
        printf("%s: FRF to a unit %s at %s, speed %g %s, %s method\n\n", m->file,
               load_re                           ? "mesh transmission error"
               : s->dof_type[inputs[0]] >= GD_RX ? "moment"
                                                 : "force",
               inlabel, gd_cli_speed_out(&u, opt.speed), gd_cli_speed_unit(&u),
               opt.method == GD_FRF_MODAL ? "modal" : "direct");
        gd_series_table(stdout, ser, nser, u.freq_hz ? "f(Hz)" : "w(rad/s)",
                        gd_cli_freq_out(&u, 1.0));
        gd_cli_operating_print(s, &a.op, 0);
    }
done:
    free(load_re);
    free(load_im);
    free(outbuf);
    free(ser);
    free(dirbuf);
    gd_frf_free(r);
    gd_system_free(s);
    gd_model_free(m);
    free(fr);
    return rc;
}
