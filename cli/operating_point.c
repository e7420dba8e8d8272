/* The operating point of the linear analyses (operating_point.h). */
#include "operating_point.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "geardyn/static.h"

int gd_cli_operating_apply(gd_system *s, const gd_cli_operating *op, double speed, int check)
{
    gd_error err;
    gd_error_clear(&err);
    if (!s->nlaws) return GD_EXIT_OK;
    if (op->kind == GD_OPERATING_ZERO) {
        if (gd_system_set_operating_point(s, GD_OPERATING_ZERO, NULL, NULL, &err))
            return gd_cli_report(&err);
        return GD_EXIT_OK;
    }
    gd_static_options so;
    gd_static_options_init(&so);
    so.speed = speed;
    so.input_torque = op->torque;
    if (gd_static_operating_point(s, &so, check, &err)) {
        if (err.status == GD_EINPUT && check) {
            static const char more[] = "; or --operating-point zero to linearise at q = 0";
            size_t len = strlen(err.hint);
            if (len + sizeof more <= sizeof err.hint) memcpy(err.hint + len, more, sizeof more);
        }
        return gd_cli_report(&err);
    }
    return GD_EXIT_OK;
}

void gd_cli_operating_warn(const double *speeds, const int *bad, int n)
{
    int count = 0, first = -1;
    for (int k = 0; bad && k < n; k++)
        if (bad[k]) {
            if (first < 0) first = k;
            count++;
        }
    if (count)
        fprintf(stderr,
                "geardyn: warning: the laws find no static equilibrium at %d of %d speeds "
                "(the first %.6g rpm): they are linearised at q = 0 there, where a journal or "
                "rolling bearing may have no stiffness\n",
                count, n, speeds[first] * 30 / M_PI);
}

int gd_cli_operating_scan(const gd_system *s, const double *speeds, int n, int *bad)
{
    if (!s->nlaws || s->op_kind == GD_OPERATING_ZERO) return 0;
    double *q = malloc((size_t)(s->ndof > 0 ? s->ndof : 1) * sizeof *q);
    int count = 0;
    for (int k = 0; k < n; k++) {
        int found = q ? gd_system_law_state(s, speeds[k], q) : 0;
        if (bad) bad[k] = !found;
        count += !found;
    }
    free(q);
    if (bad) gd_cli_operating_warn(speeds, bad, n);
    return count;
}

static const char *state_words(const gd_system *s, const gd_cli_operating *op)
{
    (void)s;
    return op->kind == GD_OPERATING_ZERO ? "q = 0 (--operating-point zero)"
                                         : "the static equilibrium under the mean loads and "
                                           "gravity";
}

void gd_cli_operating_print(const gd_system *s, const gd_cli_operating *op, int per_speed)
{
    if (!s->nlaws) return;
    printf("\noperating point: %d law(s) linearised about %s", s->nlaws, state_words(s, op));
    if (op->kind != GD_OPERATING_ZERO && op->torque != 0)
        printf(", input torque %g N m", op->torque);
    if (op->kind != GD_OPERATING_ZERO && per_speed) printf(", solved at each speed");
    printf("\n");
}

void gd_cli_operating_json(cJSON *o, const gd_system *s, const gd_cli_operating *op,
                           const double *speeds, const int *bad, int n)
{
    if (!s->nlaws) return;
    cJSON *j = cJSON_AddObjectToObject(o, "operating_point");
    cJSON_AddStringToObject(j, "state", op->kind == GD_OPERATING_ZERO ? "zero" : "static");
    cJSON_AddNumberToObject(j, "torque_n_m", op->kind == GD_OPERATING_ZERO ? 0 : op->torque);
    cJSON_AddNumberToObject(j, "laws", s->nlaws);
    if (!bad) return;
    cJSON *b = cJSON_AddArrayToObject(j, "no_equilibrium_speeds_rpm");
    for (int k = 0; k < n; k++)
        if (bad[k]) cJSON_AddItemToArray(b, cJSON_CreateNumber(speeds[k] * 30 / M_PI));
}
