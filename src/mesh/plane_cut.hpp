#pragma once
// The one mesh-plane slicer: the cross-section of a triangle mesh by a plane, used by the
// slice pictures (io/slice) and by the slice shape statistics (measure/slices).
//
// On-plane rule: a vertex whose signed distance (x - point) . normal is exactly 0 counts as
// on the normal's positive side (d >= 0). This is a symbolic perturbation (the plane moved
// infinitesimally against its normal), so every edge crossing is well defined: the cut of a
// plane through vertices is the limit of the cuts of planes just below it (a face in the
// plane, on the positive side of its mesh, is part of the section). The cut points at such
// a vertex coincide with it; repeated consecutive points are merged and loops left with
// fewer than 3 distinct points (a plane touching the mesh at a vertex or an edge) dropped.
#include <array>
#include <span>
#include <vector>

#include "core/vec3.hpp"

namespace invasim {

struct Plane {
  Vec3 point;   // any point of the plane
  Vec3 normal;  // normal (need not be unit for the cut; unit for signed areas)
};

// One boundary curve of a cross-section, in 3D points on the plane.
struct CutLoop {
  std::vector<Vec3> points;
  bool closed = true;  // false: an open chain, only where the mesh has a boundary
};

// Cuts the triangles (indices into x) by the plane. For an outward-oriented mesh, outer
// boundaries run counter-clockwise about the normal and holes clockwise. Loops come in the
// order of their first cut point (cut points are numbered as the triangles' edges are met);
// open chains come first. Throws SimulationError if two triangles cross an edge in the same
// direction (inconsistent orientation).
std::vector<CutLoop> cut_by_plane(const Vec3* x, std::span<const std::array<int, 3>> triangles,
                                  const Plane& plane);

}  // namespace invasim
