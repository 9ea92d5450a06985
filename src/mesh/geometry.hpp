#pragma once
// Geometry of one mesh body from its (unwrapped) vertex positions: volume, face areas,
// shape parameter, and their gradients. Pure functions; used by the shape force, by
// measurements and by tests.
#include <cmath>
#include <vector>

#include "mesh/topology.hpp"

namespace invasim {

// u . (v x w), six times the signed volume of the tetrahedron (0, u, v, w), and |e x f|, twice
// the area of the triangle spanned by e and f: the one expression of each that mesh_volume,
// face_area and the shape force's kernel (forces/shape_kernel.cpp) evaluate, so that a body at
// its reference shape has exactly zero shape energy.
inline double triple_product(double ux, double uy, double uz, double vx, double vy, double vz,
                             double wx, double wy, double wz) {
  return ux * (vy * wz - vz * wy) + (uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx));
}
inline double twice_triangle_area(double ex, double ey, double ez, double fx, double fy,
                                  double fz) {
  const double nx = ey * fz - ez * fy, ny = ez * fx - ex * fz, nz = ex * fy - ey * fx;
  return std::sqrt(nx * nx + (ny * ny + nz * nz));
}

// Enclosed volume (positive for an outward-oriented mesh), via the divergence theorem
// about the vertex centroid for accuracy far from the origin.
double mesh_volume(const MeshTopology& topo, const Vec3* x);
// Area of face k.
double face_area(const MeshTopology& topo, const Vec3* x, int k);
// Sum of face areas.
double mesh_area(const MeshTopology& topo, const Vec3* x);
// 3D shape parameter A = S^(3/2) / (6 sqrt(pi) V): 1 for a sphere, > 1 otherwise.
double shape_parameter(double area, double volume);
// Centroid of the vertices (the paper's centre of mass R_i, equal vertex masses).
Vec3 vertex_centroid(int n, const Vec3* x);

// Gradient of the enclosed volume with respect to every vertex (added into grad, scaled).
void add_volume_gradient(const MeshTopology& topo, const Vec3* x, double scale, Vec3* grad);

// Volume of the union of the mesh interior and the vertex spheres of the given diameter
// (the paper's V_i), estimated on a regular grid of spacing h; error O(h). A grid of more than
// kMaxUnionVolumeGridPoints points (the default h = 0.05 of placement.hpp gives ~1e6 for an
// adipocyte of diameter 6) is an InputError naming volume_grid and the smallest allowed h.
inline constexpr double kMaxUnionVolumeGridPoints = 1e8;
double union_volume(const MeshTopology& topo, const Vec3* x, double vertex_diameter, double h);

}  // namespace invasim
