/* The folder of the file the library was loaded from (libgeardyn.so, or the program
 * that linked libgeardyn.a): where the installed data (plotly.js) and plugins
 * (geardyn-raster.so) are found relative to it. */
#define _GNU_SOURCE /* dladdr */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/auxv.h>

#include "plot/plot_impl.h"

/* a byte of the library, to find the file it was loaded from */
static const char anchor = 0;

int pl_self_dir(char *dir, size_t size)
{
    Dl_info info, prog;
    if (!dladdr(&anchor, &info) || !info.dli_fname) return 0;
    /* inside the program itself (it linked the library's objects, as geardyn does) the
     * loader names the program by its argv[0], which a run found on PATH gives without a
     * folder ("geardyn"): the kernel's name of it instead */
    const void *phdr = (const void *)getauxval(AT_PHDR);
    int in_program = phdr && dladdr(phdr, &prog) && prog.dli_fbase == info.dli_fbase;
    /* the real path (the loader reports it as found: bin/../lib/libgeardyn.so.0) */
    char *real = realpath(in_program ? "/proc/self/exe" : info.dli_fname, NULL);
    snprintf(dir, size, "%s", real ? real : info.dli_fname);
    free(real);
    char *s = strrchr(dir, '/');
    if (!s) return 0;
    *s = '\0';
    return 1;
}
