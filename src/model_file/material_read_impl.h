/* Reading materials: a map {density, E, G | poisson} either inline or named in the
 * document's top-level `materials:` map. Two of E, G, poisson fix the third. */
#ifndef GD_MATERIAL_READ_H
#define GD_MATERIAL_READ_H
#include "geardyn/material.h"
#include "model_file/yaml_doc_impl.h"

/* Reads one material map. need_density: density is required. */
gd_status gd_material_read(gd_yreader *r, const gd_ynode *map, const char *path, const char *name,
                           int need_density, gd_material *out);

/* ref is a scalar naming an entry of root's `materials:` map, or an inline map. */
gd_status gd_material_resolve(gd_yreader *r, const gd_ynode *root, const gd_ynode *ref,
                              const char *path, int need_density, gd_material *out);

#endif
