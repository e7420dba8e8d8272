/* The version of the library as built (the headers a program compiled against may be
 * older: compare with GD_VERSION_STRING). */
#include "geardyn/version.h"

const char *gd_version(void)
{
    return GD_VERSION_STRING;
}
