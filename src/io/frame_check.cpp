#include "io/frame_check.hpp"

#include <cmath>

#include "core/range.hpp"
#include "io/io_error.hpp"
#include "io/text_format.hpp"

namespace invasim {

namespace {

// Whether a picture can place and draw a point of this position and radius.
bool drawable(const Vec3& pos, double radius) {
  return pos.allFinite() && std::isfinite(radius) && radius >= 0.0;
}

// Refuses point `what` (e.g. "cell 3 (line 6)") unless its position and radius can be drawn.
void check_point(const std::string& origin, const std::string& what, const Vec3& pos,
                 double radius) {
  if (!pos.allFinite())
    fail_io(origin, ": ", what, ": position ", text::vec_text(pos),
            " is not finite (a picture cannot place it)");
  if (!std::isfinite(radius) || radius < 0.0)
    fail_io(origin, ": ", what, ": radius ", format_number(radius),
            radius < 0.0 ? " is negative" : " is not finite", " (a picture cannot draw it)");
}

}  // namespace

void require_drawable_cells(const CellFrame& cells, const std::string& origin,
                            std::size_t first_row_line) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (drawable(cells.pos[i], cells.radius[i])) continue;
    std::string what = "cell " + std::to_string(i);
    if (first_row_line != 0) what += " (line " + std::to_string(first_row_line + i) + ")";
    check_point(origin, what, cells.pos[i], cells.radius[i]);
  }
}

void require_drawable_meshes(const MeshFrame& meshes, const std::string& origin) {
  for (std::size_t p = 0; p < meshes.points.size(); ++p) {
    const double r = p < meshes.point_radius.size() ? meshes.point_radius[p] : 0.0;
    if (drawable(meshes.points[p], r)) continue;
    check_point(origin, "adipocyte point " + std::to_string(p), meshes.points[p], r);
  }
}

}  // namespace invasim
