/* The folder of the file the library was loaded from (libgeardyn.so, or the program
 * that linked libgeardyn.a): where the installed data (plotly.js) and plugins
 * (geardyn-raster.so) are found relative to it. */
#define _GNU_SOURCE /* dladdr */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plot/plot_impl.h"

/* a byte of the library, to find the file it was loaded from */
static const char anchor = 0;

int pl_self_dir(char *dir, size_t size)
{
    Dl_info info;
    if (!dladdr(&anchor, &info) || !info.dli_fname) return 0;
    /* the real path (the loader reports it as found: bin/../lib/libgeardyn.so.0) */
    char *real = realpath(info.dli_fname, NULL);
    snprintf(dir, size, "%s", real ? real : info.dli_fname);
    free(real);
    char *s = strrchr(dir, '/');
    if (!s) return 0;
    *s = '\0';
    return 1;
}
