#pragma once
// Shape of adipocytes (docs/measurements_dynamics.md, "Shape of adipocytes"; the paper's
// Appendix A): the 3D shape parameter of every body, and random planar cross-sections
// ("slices", as in a histology section) with their 2D shape parameter A_2D = p^2 / (4 pi s)
// (p perimeter, s area; 1 for a disc, n tan(pi/n) / pi for a regular n-gon), plus a
// histogram helper for its distribution. Slices cut the triangle mesh through the vertex
// centres (the surface whose area and volume define the 3D shape parameter), not the vertex
// spheres, with the one mesh-plane slicer (mesh/plane_cut.hpp).
#include <cstdint>
#include <span>
#include <vector>

#include "mesh/plane_cut.hpp"
#include "state/system.hpp"

namespace invasim {

// 3D shape parameter S^(3/2) / (6 sqrt(pi) V) of every body, in body order.
std::vector<double> body_shape_parameters(const System& sys);

// One connected region of a cross-section: an outer boundary loop and the hole loops inside
// it (a region with a hole arises from a cup-shaped body).
struct SliceProfile {
  double perimeter = 0.0;  // outer boundary plus holes
  double area = 0.0;       // outer area minus holes
  int loops = 0;           // boundary loops (1 + holes)
  int corners = 0;         // polygon vertices over all loops
  double shape() const { return perimeter * perimeter / (4.0 * M_PI * area); }
};

// Cross-section of a closed, outward-oriented mesh (vertex positions x, unwrapped) by a
// plane with a unit normal: one profile per connected region (empty if the plane misses the
// mesh). Cut by cut_by_plane, so a vertex exactly on the plane counts as on the normal's
// positive side (mesh/plane_cut.hpp).
std::vector<SliceProfile> slice_mesh(const MeshTopology& topo, const Vec3* x, const Plane& plane);

struct SliceOptions {
  int per_body = 10;  // random planes per body
  // Plane offsets along the normal are uniform over this fraction of the body's extent
  // about its centroid. 1 = isotropic uniform random sections (every plane that hits the
  // body equally likely, as a histology section cuts cells), including caps near a vertex,
  // where the 42-vertex mesh's facets give flat, elongated polygons (A_2D up to ~8 for a
  // round body). The default 0.5 keeps to central cuts (sections of >= ~75% of the largest
  // area of a round body), where the mesh is a good polygonal approximation.
  double offset_fraction = 0.5;
  std::uint64_t seed = 1;  // random planes are keyed by (seed, step, body, slice)
  void validate() const;
};

// One profile of one random slice of one body.
struct BodySlice {
  int body = 0, slice = 0;
  Plane plane;  // the cutting plane (unwrapped coordinates of the body)
  SliceProfile profile;
  double shape = 0.0;  // profile.shape()
};

// per_body random slices of one mesh: unit normals uniform on the sphere, plane through the
// centroid shifted along the normal uniformly within offset_fraction of the extent of the
// vertices on each side. Planes are pure functions of (seed, step, body, slice index).
// Profiles come in slice order.
std::vector<BodySlice> random_slices(const MeshTopology& topo, const Vec3* x,
                                     const SliceOptions& options, std::uint64_t step, int body);
// Random slices of every body of a system (step = sys.step), in body order; parallel over
// bodies, independent of the thread count.
std::vector<BodySlice> random_slices(const System& sys, const SliceOptions& options);

// Histogram of values on [lo, hi) in equal bins (a value equal to hi goes in the last bin).
struct Histogram {
  std::vector<double> edges;          // bins + 1 bin edges
  std::vector<std::uint64_t> counts;  // per bin
  std::vector<double> density;        // counts / (in-range total * bin width): integrates to 1
  std::uint64_t below = 0, above = 0, invalid = 0;  // outside [lo, hi], NaN / inf
};
Histogram histogram(std::span<const double> values, double lo, double hi, int bins);

}  // namespace invasim
