/* Writers shared by frf and unbalance: one JSON object per output with arrays
 * (x_name, magnitude, phase_deg, real, imag), a table and a long-form CSV. */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "sweep_output.h"

#define PI 3.14159265358979323846

cJSON *gd_series_json(const gd_series *s)
{
    cJSON *o = cJSON_CreateObject();
    cJSON_AddStringToObject(o, "name", s->name);
    if (s->quantity) cJSON_AddStringToObject(o, "quantity", s->quantity);
    if (s->harmonic > 0) cJSON_AddNumberToObject(o, "harmonic_order", s->harmonic);
    cJSON *x = cJSON_AddArrayToObject(o, s->xname);
    cJSON *mg = cJSON_AddArrayToObject(o, "magnitude"),
          *ph = cJSON_AddArrayToObject(o, "phase_deg");
    cJSON *re = cJSON_AddArrayToObject(o, "real"), *im = cJSON_AddArrayToObject(o, "imag");
    for (int k = 0; k < s->n; k++) {
        double a = s->re[k], b = s->im[k];
        cJSON_AddItemToArray(x, cJSON_CreateNumber(s->x[k]));
        cJSON_AddItemToArray(mg, gd_cli_json_number(hypot(a, b)));
        cJSON_AddItemToArray(ph, gd_cli_json_number(atan2(b, a) * 180 / PI));
        cJSON_AddItemToArray(re, gd_cli_json_number(a));
        cJSON_AddItemToArray(im, gd_cli_json_number(b));
    }
    return o;
}

void gd_series_csv(FILE *f, const gd_series *s)
{
    for (int k = 0; k < s->n; k++) {
        double a = s->re[k], b = s->im[k];
        fprintf(f, "%s,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", s->name, s->x[k], s->x[k] / (2 * PI),
                hypot(a, b), atan2(b, a) * 180 / PI, a, b);
    }
}

void gd_series_table(FILE *f, const gd_series *s, int ns, const char *xlabel, double xscale)
{
    fprintf(f, "%12s", xlabel);
    for (int j = 0; j < ns; j++)
        fprintf(f, "  %-24.24s", s[j].name);
    fprintf(f, "\n%12s", "");
    for (int j = 0; j < ns; j++)
        fprintf(f, "  %12s %11s", "magnitude", "phase(deg)");
    fprintf(f, "\n");
    for (int k = 0; k < (ns ? s[0].n : 0); k++) {
        fprintf(f, "%12.6g", s[0].x[k] * xscale);
        for (int j = 0; j < ns; j++) {
            /* no value (a singular frequency: the JSON's null) is "-", not "nan" */
            double mag = hypot(s[j].re[k], s[j].im[k]);
            if (isnan(mag) || isnan(s[j].re[k]) || isnan(s[j].im[k]))
                fprintf(f, "  %12s %11s", "-", "-");
            else
                fprintf(f, "  %12.5g %11.2f", mag, atan2(s[j].im[k], s[j].re[k]) * 180 / PI);
        }
        fprintf(f, "\n");
    }
}
