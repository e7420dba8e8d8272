/* The static analysis's options (geardyn/static.h): their defaults and their checks. */
#include <math.h>
#include <string.h>

#include "static/static_impl.h"

void gd_static_options_init(gd_static_options *opt)
{
    memset(opt, 0, sizeof *opt);
    opt->speed = -1;
    opt->input_node = -1;
    opt->hold_node = -1;
    opt->loads = 1;
    opt->gravity = 1;
}

gd_status gd_st_check_options(const gd_model *m, const gd_static_options *opt, gd_error *err)
{
    if (opt->input_node < -1 || opt->input_node >= m->nnodes)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "input_node", "give a node of the model",
                            "input node %d out of range", opt->input_node);
    if (opt->hold_node < -1 || opt->hold_node >= m->nnodes)
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "hold_node", "give a node of the model",
                            "hold node %d out of range", opt->hold_node);
    if (!isfinite(opt->input_torque) || !isfinite(opt->speed))
        return gd_error_set(err, GD_EINPUT, "", 0, 0, "", "give finite values",
                            "input torque %g or speed %g is not finite", opt->input_torque,
                            opt->speed);
    return GD_OK;
}
