/* Continuation in the frequency of the time-harmonic loads (gd_periodic_param's
 * load_frequency): the caller's problem with every GD_LOAD_HARMONIC_TIME load at the
 * value (several keep their ratios to the first), no model rebuilt. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic_impl.h"

int gd_per_frequency_spec(const gd_transient_spec *spec, double value, gd_tr_load **loads,
                          gd_transient_spec *out, char *msg, size_t cap)
{
    *loads = NULL;
    *out = *spec;
    double f0 = 0.0;
    for (int i = 0; i < spec->nloads && f0 == 0.0; i++)
        if (spec->loads[i].law.kind == GD_LOAD_HARMONIC_TIME) f0 = spec->loads[i].law.frequency;
    if (!(f0 > 0)) {
        snprintf(msg, cap,
                 "the model has no time-harmonic load to continue in (a load with "
                 "amplitude and frequency in excitations.loads)");
        return 1;
    }
    if (!(value > 0)) {
        snprintf(msg, cap, "load frequency %g rad/s: give a positive frequency", value);
        return 1;
    }
    gd_tr_load *l = malloc((size_t)spec->nloads * sizeof *l);
    if (!l) {
        snprintf(msg, cap, "out of memory");
        return 1;
    }
    memcpy(l, spec->loads, (size_t)spec->nloads * sizeof *l);
    for (int i = 0; i < spec->nloads; i++)
        if (l[i].law.kind == GD_LOAD_HARMONIC_TIME) l[i].law.frequency *= value / f0;
    out->loads = l;
    *loads = l;
    return 0;
}
