/* Internals of the element kinds: the physics each kind's file provides to its
 * gd_element_type (include/geardyn/elements.h) and to the tests that check one matrix
 * against hand values. Local DOF order per node: x, y, z, rx, ry, rz; two-node
 * elements stack node 1 then node 2. Matrices are row-major. */
#ifndef GD_ELEMENTS_IMPL_H
#define GD_ELEMENTS_IMPL_H
#include "geardyn/elements.h"

/* ---- shaft.c ---- */
/* 2-node Timoshenko shaft element with torsion and axial rod: mass, stiffness and
 * gyroscopic matrix per unit spin speed (12 x 12). */
void gd_shaft_element_matrices(const gd_element *e, const gd_material *mat, double M[144],
                               double K[144], double G[144]);
/* Shear coefficient of a hollow circular section (Cowper 1966). */
double gd_shear_coefficient(double poisson, double outer_diameter, double inner_diameter);

/* ---- disk.c ---- */
/* Rigid disk at a node (6 x 6): mass matrix and gyroscopic matrix per unit spin. */
void gd_disk_matrices(const gd_disk *d, double M[36], double G[36]);

/* ---- bearing.c ---- */
/* Bearing coefficients at the speed of the bearing's shaft (rad/s, magnitude):
 * linear interpolation in a speed table, held constant beyond its ends. */
void gd_bearing_coeffs_at(const gd_bearing *b, double shaft_speed, gd_bearing_coeffs *out);
/* 6 x 6 stiffness and damping of a bearing's coefficients on one node. */
void gd_bearing_matrices(const gd_bearing_coeffs *c, double K[36], double C[36]);

/* ---- gear_mesh.c ---- */
/* Mesh deformation vector a (12: driver then driven) such that d = a . q is the
 * compression of the tooth contact along the contact normal, with the mesh's
 * coupling level applied. */
void gd_mesh_vector_local(const gd_mesh *g, double a[12]);

/* ---- planetary.c ---- */
/* Deformation vector (12: sun or ring, then planet n) of planet n's sun mesh (ring 0) or
 * ring mesh (ring 1), [LinParker1999] Eqs. 2-3 in the node coordinates. */
void gd_planetary_mesh_vector(const gd_planetary *g, int ring, int n, double a[12]);
/* Radial and tangential deformation vectors (12: carrier, then planet n) of planet n's
 * bearing, [LinParker1999] Eq. 4. */
void gd_planetary_bearing_vectors(const gd_planetary *g, int n, double radial[12],
                                  double tangential[12]);
/* Geometric stiffness (12 x 12: carrier, then planet n) of planet n's centrifugal bearing
 * preload F = m_p w^2 r_c at carrier speed w (rad/s): the Hessian of
 * E = F (th_c e_t . (u_n - u_c) - r_c th_c^2 / 2) (docs/planetary.md, "Rotating carrier"). */
void gd_planetary_centrifugal_stiffness(const gd_planetary *g, int n, double carrier_speed,
                                        double K[144]);

/* ---- connector.c: what bearings and springs share ---- */
/* Motion types of a support's DOFs: x, y lateral, z axial, rx, ry tilt, rz torsion. */
extern const gd_motion gd_support_motion[6];
/* Nodes of a connector from node1 to node2 (-1: ground): 1 or 2. */
int gd_connector_nodes(int node1, int node2, int node[2]);
/* The local matrix of a connector acting on the relative motion of its nodes: A
 * (6 x 6) to ground (nnodes 1), or [A -A; -A A] (12 x 12) between two nodes. */
void gd_connector_expand(const double a6[36], int nnodes, double *out);
/* Row dir of a connector's local K and C (6 x nnodes entries). */
void gd_connector_row(const double K6[36], const double C6[36], int nnodes, gd_dof dir, double *k,
                      double *c);
/* |speed| of the shaft carrying node at reference speed W. */
double gd_node_shaft_speed(const gd_model *m, int node, double speed);

#endif
