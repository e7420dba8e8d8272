/* geardyn modal --directional: the complex-coordinate (r = x + i y) eigenvalues of
 * [Kumar2011], one per mode, Im > 0 forward and Im < 0 backward. */
#include "modal_directional.h"

#include <math.h>

#include "cli.h"

void gd_cli_print_directional(FILE *f, const gd_directional_result *d)
{
    fprintf(f, "\ndirectional modes (complex coordinates r = x + i y; Im > 0 forward, < 0 "
               "backward):\n");
    fprintf(f, "%4s %14s %14s %12s  %-9s %8s\n", "mode", "Re(lambda)", "Im(lambda)", "f_d(Hz)",
            "whirl", "forward%");
    for (int j = 0; j < d->nmodes; j++) {
        const gd_directional_mode *m = &d->modes[j];
        char fw[16] = "-";
        if (!isnan(m->forward_fraction)) snprintf(fw, sizeof fw, "%.1f", 100 * m->forward_fraction);
        fprintf(f, "%4d %14.8g %14.8g %12.6g  %-9s %8s\n", j + 1, m->lambda_re, m->lambda_im,
                m->lambda_im / (2 * M_PI), gd_whirl_names[m->whirl], fw);
    }
}

cJSON *gd_cli_directional_json(const gd_directional_result *d)
{
    cJSON *a = cJSON_CreateArray();
    for (int j = 0; j < d->nmodes; j++) {
        const gd_directional_mode *m = &d->modes[j];
        cJSON *o = cJSON_CreateObject();
        cJSON_AddNumberToObject(o, "eigenvalue_real", m->lambda_re);
        cJSON_AddNumberToObject(o, "eigenvalue_imag", m->lambda_im);
        cJSON_AddNumberToObject(o, "frequency_hz", m->lambda_im / (2 * M_PI));
        cJSON_AddStringToObject(o, "whirl", gd_whirl_names[m->whirl]);
        cJSON_AddItemToObject(o, "forward_fraction", gd_cli_json_number(m->forward_fraction));
        cJSON_AddItemToArray(a, o);
    }
    return a;
}
