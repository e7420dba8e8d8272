#include "model_file/material_read_impl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *const MATERIAL_KEYS[] = {"density", "E", "G", "poisson", NULL};

gd_status gd_material_read(gd_yreader *r, const gd_ynode *map, const char *path, const char *name,
                           int need_density, gd_material *out)
{
    gd_status st;
    if ((st = gd_yexpect(r, map, GD_Y_MAP, path))) return st;
    if ((st = gd_ycheck_keys(r, map, path, MATERIAL_KEYS))) return st;
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", name ? name : "");
    int has_e = 0, has_g = 0, has_nu = 0;
    if ((st = gd_yread_qty(r, map, "density", path, GD_QTY_DENSITY,
                           GD_YPOS | (need_density ? GD_YREQ : 0), &out->density, NULL)) ||
        (st = gd_yread_qty(r, map, "E", path, GD_QTY_PRESSURE, GD_YPOS | GD_YREQ, &out->E,
                           &has_e)) ||
        (st = gd_yread_qty(r, map, "G", path, GD_QTY_PRESSURE, GD_YPOS, &out->G, &has_g)) ||
        (st = gd_yread_qty(r, map, "poisson", path, GD_QTY_DIMLESS, 0, &out->poisson, &has_nu)))
        return st;
    char p[200];
    if (has_g && has_nu)
        return gd_yfail(r, gd_ymap_get(map, "G"), gd_ypath_key(p, sizeof p, path, "G"),
                        "give either G or poisson, not both", "G and poisson both given");
    if (!has_g && !has_nu)
        return gd_yfail(r, map, path, "add poisson (e.g. 0.3) or the shear modulus G",
                        "material needs poisson or G");
    if (has_nu) {
        if (!(out->poisson > -1.0 && out->poisson < 0.5))
            return gd_yfail(r, gd_ymap_get(map, "poisson"),
                            gd_ypath_key(p, sizeof p, path, "poisson"),
                            "Poisson's ratio lies between -1 and 0.5 (steel: 0.3)",
                            "poisson %g is not physical", out->poisson);
        out->G = out->E / (2.0 * (1.0 + out->poisson));
    } else {
        out->poisson = out->E / (2.0 * out->G) - 1.0;
        if (!(out->poisson > -1.0 && out->poisson < 0.5))
            return gd_yfail(
                r, gd_ymap_get(map, "G"), gd_ypath_key(p, sizeof p, path, "G"),
                "G must be greater than E/3 (a Poisson's ratio below 0.5); steel: G = 0.385 E",
                "E and G give a Poisson's ratio of %g", out->poisson);
    }
    return GD_OK;
}

gd_status gd_material_resolve(gd_yreader *r, const gd_ynode *root, const gd_ynode *ref,
                              const char *path, int need_density, gd_material *out)
{
    if (ref && ref->kind == GD_Y_MAP) return gd_material_read(r, ref, path, "", need_density, out);
    if (!ref || ref->kind != GD_Y_SCALAR)
        return gd_yfail(r, ref, path, "name a material from `materials:` or give a map",
                        "expected a material name or map");
    const gd_ynode *mats = gd_ymap_get(root, "materials");
    const gd_ynode *m = gd_ymap_get(mats, ref->text);
    if (!m) {
        char hint[256];
        snprintf(hint, sizeof hint,
                 "define it under `materials: {%s: {density: ..., E: ..., poisson: ...}}`",
                 ref->text);
        return gd_yfail(r, ref, path, hint, "unknown material '%s'", ref->text);
    }
    char p[200];
    snprintf(p, sizeof p, "materials.%s", ref->text);
    return gd_material_read(r, m, p, ref->text, need_density, out);
}
