#pragma once
// One snapshot frame: what the writers put in files and what the readers and the slice
// renderer get back, independent of System so that frames read from disk and frames taken
// from a running simulation are handled by the same code.
#include <array>
#include <cstdint>
#include <vector>

#include "core/box.hpp"
#include "state/system.hpp"

namespace invasim {

// The cancer cells (free spheres) of a frame, positions wrapped into the box.
struct CellFrame {
  std::vector<Vec3> pos, vel, orient;
  std::vector<double> radius;
  std::vector<std::uint64_t> id;  // System::site_ids, if asked for (else empty)
  std::size_t size() const { return pos.size(); }
};

// All adipocyte meshes of a frame as one triangle soup with a body id per triangle. Each
// body's points are unwrapped (the mesh is whole) and shifted by whole box periods so that its
// vertex centroid lies in the primary box.
struct MeshFrame {
  std::vector<Vec3> points;
  std::vector<double> point_radius;           // contact radius of each vertex (0 if unknown)
  std::vector<std::array<int, 3>> triangles;  // indices into points, outward oriented
  std::vector<int> triangle_body;             // body id of each triangle
  std::vector<double> triangle_shape;         // that body's 3D shape parameter
  int n_bodies() const;
};

struct Frame {
  Box box;
  std::uint64_t step = 0;
  double time = 0.0;
  CellFrame cells;
  MeshFrame meshes;
};

// The frame of the current state: every SiteKind::kCancer site as a cell (radius = diameter/2,
// and its System::site_ids entry if `ids`) and every body as a mesh.
Frame frame_from_system(const System& sys, bool ids = false);

// Whether two boxes read from the files of one frame are the same box. The formats store
// different quantities (extended XYZ: Origin and Lattice lengths; VTP: box_lo and box_hi), each
// in its shortest round-trip form, so a box read back from XYZ has hi = lo + (hi - lo), which
// can differ from the written hi by one rounding of each operation. The periodic flags must
// match exactly; corners may differ by at most 4 ulp of the axis's largest magnitude
// (max(|lo|, |hi|, length)): far below any physical difference, far above the round-off.
bool same_box(const Box& a, const Box& b);

// Shifts a whole body (points unwrapped) by whole periods along periodic axes so that its
// centroid lies in [lo, hi).
void shift_into_box(const Box& box, std::vector<Vec3>& points);

}  // namespace invasim
