#include <stdlib.h>

#include "modal/modal_impl.h"

gd_modal_result *gd_modal_result_new(const gd_system *sys, int nmodes, int with_left)
{
    gd_modal_result *r = calloc(1, sizeof *r);
    if (!r) return NULL;
    size_t n = (size_t)sys->ndof * (size_t)(nmodes > 0 ? nmodes : 1);
    r->ndof = sys->ndof;
    r->nmodes = nmodes;
    r->ncomponents = sys->ncomponents;
    r->modes = calloc((size_t)(nmodes > 0 ? nmodes : 1), sizeof *r->modes);
    r->shape_re = calloc(n, sizeof(double));
    r->shape_im = calloc(n, sizeof(double));
    r->energy_by_component = calloc((size_t)(sys->ncomponents > 0 ? sys->ncomponents : 1) *
                                        (size_t)(nmodes > 0 ? nmodes : 1),
                                    sizeof(double));
    if (with_left) {
        r->left_re = calloc(n, sizeof(double));
        r->left_im = calloc(n, sizeof(double));
    }
    if (!r->modes || !r->shape_re || !r->shape_im || !r->energy_by_component ||
        (with_left && (!r->left_re || !r->left_im))) {
        gd_modal_free(r);
        return NULL;
    }
    return r;
}

void gd_modal_free(gd_modal_result *r)
{
    if (!r) return;
    free(r->modes);
    free(r->shape_re);
    free(r->shape_im);
    free(r->left_re);
    free(r->left_im);
    free(r->energy_by_component);
    free(r);
}
