/* --units: the speed and frequency units of the text tables and plot axes; by default
 * the ones the user wrote on the command line (docs/plots.md). */
#include <string.h>

#include "cli.h"

#define PI 3.14159265358979323846

static int has(const char *text, const char *unit)
{
    return text && strstr(text, unit) != NULL;
}

int gd_cli_units_parse(const char *cmd, const char *units, const char *speed_text,
                       const char *freq_text, gd_cli_units *u)
{
    /* what the user wrote: 3000rpm -> rpm, 500Hz or 2kHz -> Hz, rad/s -> rad/s */
    if (has(speed_text, "rpm")) u->speed_rpm = 1;
    if (has(speed_text, "rad/s")) u->speed_rpm = 0;
    if (has(freq_text, "Hz")) u->freq_hz = 1;
    if (has(freq_text, "rad/s") || has(freq_text, "rpm")) u->freq_hz = 0;
    if (!units) return 0;
    char buf[64];
    snprintf(buf, sizeof buf, "%s", units);
    int speed_set = 0, freq_set = 0, rad = 0;
    for (char *tok = strtok(buf, ","); tok; tok = strtok(NULL, ",")) {
        while (*tok == ' ')
            tok++;
        if (!strcmp(tok, "rpm"))
            u->speed_rpm = 1, speed_set = 1;
        else if (!strcmp(tok, "Hz") || !strcmp(tok, "hz"))
            u->freq_hz = 1, freq_set = 1;
        else if (!strcmp(tok, "rad/s"))
            rad = 1;
        else
            return gd_cli_usage_error(cmd,
                                      "--units: '%s' is not rpm, Hz or rad/s (e.g. --units rpm,Hz "
                                      "or --units rad/s)",
                                      tok);
    }
    /* rad/s: for whichever of speed and frequency was not named otherwise */
    if (rad && !speed_set) u->speed_rpm = 0;
    if (rad && !freq_set) u->freq_hz = 0;
    return 0;
}

double gd_cli_speed_out(const gd_cli_units *u, double rad_s)
{
    return u->speed_rpm ? rad_s * 30 / PI : rad_s;
}

double gd_cli_freq_out(const gd_cli_units *u, double rad_s)
{
    return u->freq_hz ? rad_s / (2 * PI) : rad_s;
}

const char *gd_cli_speed_unit(const gd_cli_units *u)
{
    return u->speed_rpm ? "rpm" : "rad/s";
}

const char *gd_cli_freq_unit(const gd_cli_units *u)
{
    return u->freq_hz ? "Hz" : "rad/s";
}
