/* A CSparse view of the system's CSC matrices (transient_impl.h), shared by the problem
 * set-up and the speed profile's bearing tables: no copy. */
#include "transient/transient_impl.h"

cs gd_tr_cs_view(const gd_csc *a)
{
    cs v;
    v.nzmax = a->colptr[a->n] > 0 ? a->colptr[a->n] : 1;
    v.m = v.n = a->n;
    v.p = a->colptr;
    v.i = a->rowind;
    v.x = a->values;
    v.nz = -1;
    return v;
}
