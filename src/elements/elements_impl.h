/* Element matrices. Local DOF order per node: x, y, z, rx, ry, rz; two-node elements
 * stack node 1 then node 2. Matrices are row-major. */
#ifndef GD_ELEMENTS_H
#define GD_ELEMENTS_H
#include "geardyn/model.h"

/* 2-node Timoshenko shaft element with torsion and axial rod: mass, stiffness and
 * gyroscopic matrix per unit spin speed (12 x 12). */
void gd_shaft_element_matrices(const gd_element *e, const gd_material *mat, double M[144],
                               double K[144], double G[144]);

/* Shear coefficient of a hollow circular section (Hutchinson 2001). */
double gd_shear_coefficient(double poisson, double outer_diameter, double inner_diameter);

/* Rigid disk at a node (6 x 6): mass matrix and gyroscopic matrix per unit spin. */
void gd_disk_matrices(const gd_disk *d, double M[36], double G[36]);

/* Bearing coefficients at the speed of the bearing's shaft (rad/s, magnitude):
 * linear interpolation in a speed table, held constant beyond its ends. */
void gd_bearing_coeffs_at(const gd_bearing *b, double shaft_speed, gd_bearing_coeffs *out);
/* 6 x 6 stiffness and damping of a bearing on one node. */
void gd_bearing_matrices(const gd_bearing_coeffs *c, double K[36], double C[36]);

/* Mesh deformation vector a (12: driver then driven) such that d = a . q is the
 * compression of the tooth contact along the contact normal, with the mesh's
 * coupling level applied. */
void gd_mesh_vector_local(const gd_mesh *g, double a[12]);

#endif
