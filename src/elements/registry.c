/* The element registry: every kind, in assembly order. Adding a kind is its file under
 * src/elements/, one line here, its reader in src/model_file/ and its docs. */
#include <string.h>

#include "elements/elements_impl.h"

const char *const gd_motion_names[GD_NMOTIONS] = {"lateral", "torsional", "axial", "tilt"};

const gd_element_type *const gd_element_types[] = {
    &gd_element_shaft,  &gd_element_disk, &gd_element_bearing,
    &gd_element_spring, &gd_element_mesh, &gd_element_planetary,
};
const int gd_nelement_types = (int)(sizeof gd_element_types / sizeof gd_element_types[0]);

const gd_element_type *gd_element_type_find(const char *name)
{
    for (int k = 0; k < gd_nelement_types; k++)
        if (!strcmp(gd_element_types[k]->name, name)) return gd_element_types[k];
    return NULL;
}
