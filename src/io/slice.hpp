#pragma once
// Cross-section of a frame by an axis-aligned plane (x, y or z = value), as in the paper's
// Fig. 1(c-d): every cancer cell cut by the plane gives a disc of radius sqrt(r^2 - d^2), every
// adipocyte mesh cut by it gives closed polygons (the triangle mesh intersected with the
// plane, segments chained through the mesh edges they cross), and every adipocyte vertex
// sphere cut by it a disc (the mesh surface runs through the vertex centres; the adipocyte's
// contact envelope reaches one vertex radius further). Periodic images across the
// plane's own axis are considered; in-plane periodic copies are left to the drawing.
#include <array>
#include <string_view>
#include <vector>

#include "io/frame.hpp"

namespace invasim {

struct SlicePlane {
  int axis = 2;  // 0, 1, 2 = x, y, z
  double value = 0.0;
};
// Parses "x=1.5", "y=0", "z=12" (also "z = 12"). Throws InputError naming the text.
SlicePlane parse_slice_plane(std::string_view spec);

using Point2 = std::array<double, 2>;

struct SliceDisc {
  int cell;       // index in the frame's cells (vertex discs: the point index)
  Point2 centre;  // in-plane coordinates (u, w)
  double radius;
  int body = -1;  // vertex discs: the adipocyte the point belongs to (cells: -1)
  // Cells: 1 active (the frame gives it an orientation), 0 passive (zero orientation), -1
  // unknown (the frame has no orientations).
  int active = -1;
};

struct SlicePolygon {
  int body;
  std::vector<Point2> points;  // in-plane (u, w), mesh unwrapped: may extend past the box
  bool closed = true;          // false only for a mesh that is not closed
};

struct Slice {
  SlicePlane plane;            // value wrapped into the box on a periodic axis
  int u_axis = 0, w_axis = 1;  // in-plane axes: horizontal and vertical in a picture
  Box box;
  std::uint64_t step = 0;
  double time = 0.0;
  std::vector<SliceDisc> discs;
  std::vector<SlicePolygon> polygons;
  // Sections of the adipocyte vertices' contact spheres (`cell` = point index, `body` its
  // adipocyte): with the polygons they outline the adipocyte's contact envelope (mesh plus
  // vertex spheres; io/slice_outline.hpp).
  std::vector<SliceDisc> vertex_discs;
};

// Cuts a frame. A plane outside the walls of a non-periodic axis is an InputError; on a
// periodic axis a plane within one period of the box is wrapped into it, a farther one is an
// InputError.
Slice cut_frame(const Frame& frame, const SlicePlane& plane);

// The cross-section(s) of one triangle mesh with the plane points[.][axis] = value, by
// cut_by_plane (mesh/plane_cut.hpp): polygons in the coordinates of the two other axes. A
// vertex exactly on the plane counts as above it (value <= coordinate), so every crossing is
// well defined; polygons with fewer than 3 distinct points (a plane touching a vertex) are
// dropped. Open chains (closed = false) only for a mesh that is not closed; triangles that
// are not consistently oriented are a SimulationError.
std::vector<SlicePolygon> cut_mesh(const std::vector<Vec3>& points,
                                   const std::vector<std::array<int, 3>>& triangles, int axis,
                                   double value);

}  // namespace invasim
