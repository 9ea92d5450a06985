#pragma once
// Geometry of one mesh body from its (unwrapped) vertex positions: volume, face areas,
// shape parameter, and their gradients. Pure functions; used by the shape force, by
// measurements and by tests.
#include <vector>

#include "mesh/topology.hpp"

namespace invasim {

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
