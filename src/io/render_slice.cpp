#include "io/render_slice.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/frame_check.hpp"
#include "io/io_error.hpp"
#include "io/regular_file.hpp"
#include "io/slice_axes.hpp"
#include "io/slice_outline.hpp"
#include "io/snapshot_writer.hpp"
#include "io/text_format.hpp"
#include "io/vtk_format.hpp"
#include "io/xml.hpp"
#include "io/xyz_format.hpp"

namespace invasim {

RenderCounts count_shapes(const Slice& slice) {
  RenderCounts c;
  c.discs = int(slice.discs.size());
  c.vertex_discs = int(slice.vertex_discs.size());
  for (const SlicePolygon& p : slice.polygons) ++(p.closed ? c.polygons : c.open_chains);
  return c;
}

namespace {

// Periodic copies to draw for a shape spanning [min, max] along an in-plane axis: the shape
// itself and its image one period away if it sticks out of [lo, hi).
std::vector<double> image_shifts(bool periodic, double lo, double hi, double min, double max) {
  std::vector<double> shifts{0.0};
  if (!periodic) return shifts;
  if (min < lo) shifts.push_back(hi - lo);
  if (max > hi) shifts.push_back(lo - hi);
  return shifts;
}

// A box edge: a wall (thick) or a periodic edge (dashed).
void edge(std::string& out, double x1, double y1, double x2, double y2, bool wall) {
  if (wall)
    svg_line(out, "data-edge=\"wall\"", x1, y1, x2, y2, "stroke=\"black\" stroke-width=\"4\"");
  else
    svg_line(out, "data-edge=\"periodic\"", x1, y1, x2, y2,
             "stroke=\"black\" stroke-width=\"1\" stroke-dasharray=\"6,4\"");
}

// Calls draw(du, dw) for a shape spanning [min_u, max_u] x [min_w, max_w] and for each of its
// in-plane periodic copies that reaches into the box.
template <typename Draw>
void each_image(const SliceCanvas& cv, const Slice& s, double min_u, double max_u, double min_w,
                double max_w, Draw draw) {
  const Box& box = s.box;
  for (double du : image_shifts(box.periodic(s.u_axis), cv.lo_u, cv.hi_u, min_u, max_u))
    for (double dw : image_shifts(box.periodic(s.w_axis), cv.lo_w, cv.hi_w, min_w, max_w))
      draw(du, dw);
}

// Whether the cells' discs are drawn in two colours (both active and passive cells present).
bool two_kinds(const Slice& s) {
  bool active = false, passive = false;
  for (const SliceDisc& d : s.discs) (d.active == 1 ? active : passive) |= d.active >= 0;
  return active && passive;
}

void draw_cells(std::string& out, const SliceCanvas& cv, const Slice& s) {
  const bool two = two_kinds(s);
  for (const SliceDisc& d : s.discs) {
    const double r = d.radius, u = d.centre[0], w = d.centre[1];
    const char* style = two && d.active == 0 ? slice_style::kCellPassive : slice_style::kCellActive;
    each_image(cv, s, u - r, u + r, w - r, w + r, [&](double du, double dw) {
      out += "    <circle data-cell=\"" + std::to_string(d.cell) + "\" cx=\"";
      svg_number(out, cv.x(u + du));
      out += "\" cy=\"";
      svg_number(out, cv.y(w + dw));
      out += "\" r=\"";
      svg_number(out, r * cv.scale);
      out += "\" ";
      out += style;
      out += "/>\n";
    });
  }
}

// The SVG path data of outline loops shifted by (du, dw): "M x y L ... A ... Z" per loop;
// arcs are counter-clockwise in (u, w), i.e. sweep-flag 0 with the w axis drawn upwards.
std::string path_data(const SliceCanvas& cv, const std::vector<OutlineLoop>& loops, double du,
                      double dw) {
  std::string d;
  auto point = [&](const Point2& p) {
    svg_number(d, cv.x(p[0] + du));
    d += ' ';
    svg_number(d, cv.y(p[1] + dw));
  };
  for (const OutlineLoop& loop : loops) {
    d += d.empty() ? "M " : " M ";
    point(loop.start);
    for (const OutlineStep& step : loop.steps) {
      if (step.radius > 0.0) {
        d += " A ";
        svg_number(d, step.radius * cv.scale);
        d += ' ';
        svg_number(d, step.radius * cv.scale);
        d += step.large_arc ? " 0 1 0 " : " 0 0 0 ";
      } else {
        d += " L ";
      }
      point(step.to);
    }
    d += " Z";
  }
  return d;
}

// The adipocytes: every envelope section filled, then the mesh sections as thin lines, then
// every envelope outline, so that overlapping neighbours keep both outlines visible.
void draw_adipocytes(std::string& out, const SliceCanvas& cv, const Slice& s) {
  struct Drawn {
    int body;
    std::string d;
  };
  std::vector<Drawn> paths;
  for (const BodyOutline& b : body_outlines(s)) {
    double min_u = INFINITY, max_u = -INFINITY, min_w = INFINITY, max_w = -INFINITY;
    auto extend = [&](const Point2& p, double r) {
      min_u = std::min(min_u, p[0] - r), max_u = std::max(max_u, p[0] + r);
      min_w = std::min(min_w, p[1] - r), max_w = std::max(max_w, p[1] + r);
    };
    for (const OutlineLoop& loop : b.loops) {
      extend(loop.start, 0.0);
      for (const OutlineStep& step : loop.steps)
        extend(step.radius > 0.0 ? step.centre : step.to, step.radius);
    }
    each_image(cv, s, min_u, max_u, min_w, max_w, [&](double du, double dw) {
      paths.push_back({b.body, path_data(cv, b.loops, du, dw)});
    });
  }
  for (const Drawn& p : paths)
    out += "    <path data-body=\"" + std::to_string(p.body) + "\" d=\"" + p.d + "\" " +
           slice_style::kAdipocyteFill + "/>\n";
  for (const SlicePolygon& p : s.polygons) {
    double min_u = INFINITY, max_u = -INFINITY, min_w = INFINITY, max_w = -INFINITY;
    for (const Point2& q : p.points) {
      min_u = std::min(min_u, q[0]), max_u = std::max(max_u, q[0]);
      min_w = std::min(min_w, q[1]), max_w = std::max(max_w, q[1]);
    }
    each_image(cv, s, min_u, max_u, min_w, max_w, [&](double du, double dw) {
      out += p.closed ? "    <polygon" : "    <polyline";
      out += " data-body=\"" + std::to_string(p.body) + "\" points=\"";
      for (const Point2& q : p.points) {
        svg_number(out, cv.x(q[0] + du));
        out += ',';
        svg_number(out, cv.y(q[1] + dw));
        out += ' ';
      }
      out += "\" ";
      out += slice_style::kMesh;
      out += "/>\n";
    });
  }
  for (const Drawn& p : paths)
    out += "    <path data-outline=\"" + std::to_string(p.body) + "\" d=\"" + p.d + "\" " +
           slice_style::kAdipocyteOutline + "/>\n";
}

// The legend: the kinds of cells in the slice, adipocytes, and the kinds of box edge shown.
std::vector<LegendEntry> legend_of(const Slice& s) {
  std::vector<LegendEntry> legend;
  bool active = false, passive = false;
  for (const SliceDisc& d : s.discs) (d.active == 1 ? active : passive) |= d.active >= 0;
  if (active && passive) {
    legend.push_back({"cell-active", "active cancer cell"});
    legend.push_back({"cell-passive", "passive cancer cell"});
  } else {
    legend.push_back({"cell", active    ? "cancer cell (active)"
                              : passive ? "cancer cell (passive)"
                                        : "cancer cell"});
  }
  legend.push_back({"adipocyte", "adipocyte (mesh + vertex spheres)"});
  legend.push_back({"mesh", "mesh section"});
  const Box& box = s.box;
  if (!box.periodic(s.u_axis) || !box.periodic(s.w_axis)) legend.push_back({"wall", "wall"});
  if (box.periodic(s.u_axis) || box.periodic(s.w_axis))
    legend.push_back({"periodic", "periodic boundary"});
  return legend;
}

}  // namespace

std::string slice_svg(const Slice& s, double size_px) {
  const int u = s.u_axis, w = s.w_axis;
  const Box& box = s.box;
  const std::vector<LegendEntry> legend = legend_of(s);
  const SliceCanvas cv = slice_canvas(s, size_px, legend);
  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" ";
  out += "width=\"";
  svg_number(out, cv.width());
  out += "\" height=\"";
  svg_number(out, cv.height());
  out += "\" viewBox=\"0 0 ";
  svg_number(out, cv.width());
  out += ' ';
  svg_number(out, cv.height());
  out += "\">\n";
  const std::string caption = slice_caption(s);
  out += "  <title>" + xml_escape(caption) + "</title>\n";
  out +=
      "  <desc>Slice of an invasim frame. Lengths in sigma (the mean cancer-cell diameter), "
      "time in tau = sqrt(m sigma^2/eps_c).</desc>\n";
  out += "  <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out += "  <text x=\"";
  svg_number(out, cv.left);
  out += "\" y=\"26\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"16\">" +
         xml_escape(caption) + "</text>\n";
  out += "  <defs><clipPath id=\"box\"><rect x=\"";
  svg_number(out, cv.x(cv.lo_u));
  out += "\" y=\"";
  svg_number(out, cv.y(cv.hi_w));
  out += "\" width=\"";
  svg_number(out, box.length(u) * cv.scale);
  out += "\" height=\"";
  svg_number(out, box.length(w) * cv.scale);
  out += "\"/></clipPath></defs>\n  <g clip-path=\"url(#box)\">\n";
  draw_adipocytes(out, cv, s);
  draw_cells(out, cv, s);
  out += "  </g>\n";
  // Box edges: walls (non-periodic axes) thick, periodic edges dashed.
  const double x0 = cv.x(cv.lo_u), x1 = cv.x(cv.hi_u), y0 = cv.y(cv.lo_w), y1 = cv.y(cv.hi_w);
  edge(out, x0, y0, x0, y1, !box.periodic(u));
  edge(out, x1, y0, x1, y1, !box.periodic(u));
  edge(out, x0, y0, x1, y0, !box.periodic(w));
  edge(out, x0, y1, x1, y1, !box.periodic(w));
  append_axes(out, cv, s);
  append_legend(out, cv, legend);
  out += "</svg>\n";
  return out;
}

namespace {

// Box and step of two frame files of one snapshot must agree (the box up to the round-off of
// the formats, see same_box).
void check_same_frame(const Frame& a, const std::filesystem::path& a_file, const Frame& b,
                      const std::filesystem::path& file) {
  auto box_text = [](const Box& box) {
    return "lo " + text::vec_text(box.lo()) + " hi " + text::vec_text(box.hi());
  };
  if (a.step != b.step)
    fail_io(quoted(file), ": its step ", b.step, " differs from step ", a.step, " of ",
            quoted(a_file), " (the files of one frame must agree)");
  if (!same_box(a.box, b.box))
    fail_io(quoted(file), ": its box ", box_text(b.box), " differs from the box ", box_text(a.box),
            " of ", quoted(a_file), " beyond round-off (the files of one frame must agree)");
}

// The frame files, each checked for what a picture needs (io/frame_check.hpp).
Frame load_xyz_cells(const std::filesystem::path& path) {
  Frame f = read_xyz(path);
  require_drawable_cells(f.cells, quoted(path), 3);  // frame 0: its rows start on line 3
  return f;
}

Frame load_vtp_cells(const std::filesystem::path& path) {
  Frame f = cell_frame_from_vtp(read_vtp(path), quoted(path));
  require_drawable_cells(f.cells, quoted(path));
  return f;
}

Frame load_vtp_meshes(const std::filesystem::path& path) {
  Frame f = mesh_frame_from_vtp(read_vtp(path), quoted(path));
  require_drawable_meshes(f.meshes, quoted(path));
  return f;
}

Frame load_vtp_alone(const std::filesystem::path& path) {
  const VtpData vtp = read_vtp(path);
  const bool cells = vtp.poly_offsets.empty() && !vtp.vert_offsets.empty();
  Frame f = cells ? cell_frame_from_vtp(vtp, quoted(path)) : mesh_frame_from_vtp(vtp, quoted(path));
  require_drawable_cells(f.cells, quoted(path));
  require_drawable_meshes(f.meshes, quoted(path));
  return f;
}

}  // namespace

Frame load_snapshot_frame(const std::filesystem::path& snapshot) {
  std::error_code ec;
  if (!std::filesystem::exists(snapshot, ec))
    fail_io("cannot read snapshot ", quoted(snapshot), ": no such file");
  require_regular_file(snapshot, "snapshot");  // a FIFO, directory or device: refused
  const std::string name = snapshot.filename().string();
  const std::int64_t step = SnapshotWriter::step_of_file_name(name);
  const std::string kind = step >= 0 ? name.substr(0, name.rfind('_')) : "";
  if (kind != "cells" && kind != "spheres" && kind != "adipocytes")
    return snapshot.extension() == ".xyz" ? load_xyz_cells(snapshot) : load_vtp_alone(snapshot);

  const std::filesystem::path dir = snapshot.parent_path();
  auto sibling = [&](const char* k, const char* ext) {
    return dir / SnapshotWriter::frame_file_name(k, std::uint64_t(step), ext);
  };
  // Frame files are found by step; the name given may use more digits than the default.
  auto exists = [&](const std::filesystem::path& p) { return std::filesystem::exists(p, ec); };
  std::filesystem::path cells = sibling("cells", "xyz"), spheres = sibling("spheres", "vtp"),
                        meshes = sibling("adipocytes", "vtp");
  if (kind == "cells") cells = snapshot;
  if (kind == "spheres") spheres = snapshot;
  if (kind == "adipocytes") meshes = snapshot;

  Frame f;
  std::filesystem::path first;  // the file f was read from
  if (kind != "spheres" && exists(cells)) {
    f = load_xyz_cells(cells);
    first = cells;
  } else if (exists(spheres)) {
    f = load_vtp_cells(spheres);
    first = spheres;
  }
  if (exists(meshes)) {
    Frame m = load_vtp_meshes(meshes);
    if (!first.empty()) {
      check_same_frame(f, first, m, meshes);
      f.meshes = std::move(m.meshes);
    } else {
      f = std::move(m);
    }
  }
  return f;
}

RenderCounts render_snapshot(const std::filesystem::path& snapshot, const SlicePlane& plane,
                             const std::filesystem::path& out) {
  const Slice s = cut_frame(load_snapshot_frame(snapshot), plane);
  write_file_atomically(out, slice_svg(s));
  return count_shapes(s);
}

}  // namespace invasim
