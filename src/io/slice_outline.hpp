#pragma once
// The outline of one adipocyte's section in a slice picture: the boundary of the union of its
// mesh section (closed polygons through the vertex centres) and the sections of its vertex
// spheres (discs), i.e. the section of the adipocyte's contact envelope. Each body gets its
// own closed loops, so two adipocytes whose envelopes touch or overlap stay two outlines.
#include <vector>

#include "io/slice.hpp"

namespace invasim {

// One piece of an outline loop, ending at `to`: a straight segment (radius == 0) or a circular
// arc about `centre` of that radius, counter-clockwise in the (u, w) plane.
struct OutlineStep {
  Point2 to;
  double radius = 0.0;
  Point2 centre{0.0, 0.0};
  bool large_arc = false;  // the arc spans more than half a turn
};

// A closed boundary curve, starting (and ending) at `start`. The union's interior lies to the
// left of the direction of travel: outer boundaries run counter-clockwise, holes clockwise.
struct OutlineLoop {
  Point2 start;
  std::vector<OutlineStep> steps;
};

// The boundary of the union of the regions inside `polygons` (closed loops; a point is inside
// if it is inside an odd number of them, so a hole loop cuts a hole) and the discs. Loops of
// pieces that meet only in degenerate configurations (three circles through one point, exact
// tangencies) are closed at the nearest free end, never left open.
std::vector<OutlineLoop> union_outline(const std::vector<std::vector<Point2>>& polygons,
                                       const std::vector<SliceDisc>& discs);

// The envelope section of one adipocyte: union_outline of its closed polygons and its vertex
// discs.
struct BodyOutline {
  int body;
  std::vector<OutlineLoop> loops;
};
// One entry per adipocyte the plane cuts (mesh or vertex spheres), in body order.
std::vector<BodyOutline> body_outlines(const Slice& s);

}  // namespace invasim
