/* An isotropic elastic material.
 *
 * Ownership and threads: a plain value struct; nothing to free.
 */
#ifndef GEARDYN_MATERIAL_H
#define GEARDYN_MATERIAL_H

typedef struct gd_material {
    char name[64];
    double density; /* kg/m^3 */
    double E;       /* Young's modulus, Pa */
    double G;       /* shear modulus, Pa */
    double poisson; /* Poisson's ratio */
} gd_material;

#endif
