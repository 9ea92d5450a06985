#include "io/render_slice.hpp"

#include <cmath>
#include <cstdio>

#include "io/atomic_file.hpp"
#include "io/io_error.hpp"
#include "io/regular_file.hpp"
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

// Simulated time for a caption: 10 significant digits hide the round-off that summing dt
// accumulates (6000.000000013062 -> 6000).
std::string time_label(double t) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", t);
  return buf;
}

// Maps simulation coordinates (u, w) to SVG pixels (w upwards).
struct Canvas {
  double lo_u, hi_u, lo_w, hi_w, scale, margin, top;
  double x(double u) const { return margin + (u - lo_u) * scale; }
  double y(double w) const { return top + (hi_w - w) * scale; }
  double width() const { return 2 * margin + (hi_u - lo_u) * scale; }
  double height() const { return top + margin + (hi_w - lo_w) * scale; }
};

void num(std::string& out, double v) {
  text::append_fixed(out, v, 2);
}

// Periodic copies to draw for a shape spanning [min, max] along an in-plane axis: the shape
// itself and its image one period away if it sticks out of [lo, hi).
std::vector<double> image_shifts(bool periodic, double lo, double hi, double min, double max) {
  std::vector<double> shifts{0.0};
  if (!periodic) return shifts;
  if (min < lo) shifts.push_back(hi - lo);
  if (max > hi) shifts.push_back(lo - hi);
  return shifts;
}

void line(std::string& out, double x1, double y1, double x2, double y2, bool wall) {
  out += "  <line x1=\"";
  num(out, x1);
  out += "\" y1=\"";
  num(out, y1);
  out += "\" x2=\"";
  num(out, x2);
  out += "\" y2=\"";
  num(out, y2);
  out += wall ? "\" stroke=\"black\" stroke-width=\"4\"/>\n"
              : "\" stroke=\"black\" stroke-width=\"1\" stroke-dasharray=\"6,4\"/>\n";
}

// Circles for discs and their in-plane periodic copies; `id` names the attribute holding the
// disc's index, `style` is the fill and stroke.
void draw_discs(std::string& out, const Canvas& cv, const Slice& s,
                const std::vector<SliceDisc>& discs, const char* id, const char* style) {
  const Box& box = s.box;
  for (const SliceDisc& d : discs) {
    const double r = d.radius;
    const double u = d.centre[0], w = d.centre[1];
    for (double du : image_shifts(box.periodic(s.u_axis), cv.lo_u, cv.hi_u, u - r, u + r))
      for (double dw : image_shifts(box.periodic(s.w_axis), cv.lo_w, cv.hi_w, w - r, w + r)) {
        out += "    <circle ";
        out += id;
        out += "=\"" + std::to_string(d.cell) + "\" cx=\"";
        num(out, cv.x(u + du));
        out += "\" cy=\"";
        num(out, cv.y(w + dw));
        out += "\" r=\"";
        num(out, r * cv.scale);
        out += "\" ";
        out += style;
        out += "/>\n";
      }
  }
}

}  // namespace

std::string slice_svg(const Slice& s, double size_px) {
  const int u = s.u_axis, w = s.w_axis;
  const Box& box = s.box;
  const double Lu = box.length(u), Lw = box.length(w);
  Canvas cv{box.lo()[u], box.hi()[u], box.lo()[w], box.hi()[w], size_px / std::max(Lu, Lw),
            20.0,        40.0};
  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" ";
  out += "width=\"";
  num(out, cv.width());
  out += "\" height=\"";
  num(out, cv.height());
  out += "\" viewBox=\"0 0 ";
  num(out, cv.width());
  out += ' ';
  num(out, cv.height());
  out += "\">\n";
  out += "  <title>";
  std::string title;
  title += "xyz"[s.plane.axis];
  title += " = " + text::str(s.plane.value) + ", step " + std::to_string(s.step) +
           ", t = " + time_label(s.time);
  out += xml_escape(title);
  out += "</title>\n  <rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  out += "  <text x=\"";
  num(out, cv.margin);
  out += "\" y=\"25\" font-family=\"sans-serif\" font-size=\"16\">" + xml_escape(title);
  out += std::string(" (horizontal ") + "xyz"[u] + ", vertical " + "xyz"[w] + ")</text>\n";
  out += "  <defs><clipPath id=\"box\"><rect x=\"";
  num(out, cv.x(cv.lo_u));
  out += "\" y=\"";
  num(out, cv.y(cv.hi_w));
  out += "\" width=\"";
  num(out, Lu * cv.scale);
  out += "\" height=\"";
  num(out, Lw * cv.scale);
  out += "\"/></clipPath></defs>\n  <g clip-path=\"url(#box)\">\n";

  draw_discs(out, cv, s, s.vertex_discs, "data-vertex", "fill=\"cyan\"");
  for (const SlicePolygon& p : s.polygons) {
    double min_u = INFINITY, max_u = -INFINITY, min_w = INFINITY, max_w = -INFINITY;
    for (const Point2& q : p.points) {
      min_u = std::min(min_u, q[0]), max_u = std::max(max_u, q[0]);
      min_w = std::min(min_w, q[1]), max_w = std::max(max_w, q[1]);
    }
    for (double du : image_shifts(box.periodic(u), cv.lo_u, cv.hi_u, min_u, max_u))
      for (double dw : image_shifts(box.periodic(w), cv.lo_w, cv.hi_w, min_w, max_w)) {
        out += p.closed ? "    <polygon" : "    <polyline";
        out += " data-body=\"" + std::to_string(p.body) + "\" points=\"";
        for (const Point2& q : p.points) {
          num(out, cv.x(q[0] + du));
          out += ',';
          num(out, cv.y(q[1] + dw));
          out += ' ';
        }
        out += p.closed ? "\" fill=\"cyan\" stroke=\"#007b8a\" stroke-width=\"1\"/>\n"
                        : "\" fill=\"none\" stroke=\"#007b8a\" stroke-width=\"1\"/>\n";
      }
  }
  draw_discs(out, cv, s, s.discs, "data-cell",
             "fill=\"red\" stroke=\"#800000\" stroke-width=\"0.5\"");
  out += "  </g>\n";
  // Box edges: walls (non-periodic axes) thick, periodic edges dashed.
  const double x0 = cv.x(cv.lo_u), x1 = cv.x(cv.hi_u), y0 = cv.y(cv.lo_w), y1 = cv.y(cv.hi_w);
  line(out, x0, y0, x0, y1, !box.periodic(u));
  line(out, x1, y0, x1, y1, !box.periodic(u));
  line(out, x0, y0, x1, y0, !box.periodic(w));
  line(out, x0, y1, x1, y1, !box.periodic(w));
  out += "</svg>\n";
  return out;
}

RenderCounts render_frame(const Frame& frame, const SlicePlane& plane,
                          const std::filesystem::path& out) {
  const Slice s = cut_frame(frame, plane);
  write_file_atomically(out, slice_svg(s));
  return count_shapes(s);
}

namespace {

// Box and step of two frame files of one snapshot must agree (the box up to the round-off of
// the formats, see same_box).
void check_same_frame(const Frame& a, const std::filesystem::path& a_file, const Frame& b,
                      const std::filesystem::path& file) {
  auto box_text = [](const Box& box) {
    std::string t = "lo (";
    for (int k = 0; k < 3; ++k) text::append(t += k ? ", " : "", box.lo()[k]);
    t += ") hi (";
    for (int k = 0; k < 3; ++k) text::append(t += k ? ", " : "", box.hi()[k]);
    return t + ")";
  };
  if (a.step != b.step)
    fail_io(quoted(file), ": its step ", b.step, " differs from step ", a.step, " of ",
            quoted(a_file), " (the files of one frame must agree)");
  if (!same_box(a.box, b.box))
    fail_io(quoted(file), ": its box ", box_text(b.box), " differs from the box ", box_text(a.box),
            " of ", quoted(a_file), " beyond round-off (the files of one frame must agree)");
}

Frame load_vtp_alone(const std::filesystem::path& path) {
  const VtpData vtp = read_vtp(path);
  return vtp.poly_offsets.empty() && !vtp.vert_offsets.empty()
             ? cell_frame_from_vtp(vtp, quoted(path))
             : mesh_frame_from_vtp(vtp, quoted(path));
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
    return snapshot.extension() == ".xyz" ? read_xyz(snapshot) : load_vtp_alone(snapshot);

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
    f = read_xyz(cells);
    first = cells;
  } else if (exists(spheres)) {
    f = cell_frame_from_vtp(read_vtp(spheres), quoted(spheres));
    first = spheres;
  }
  if (exists(meshes)) {
    Frame m = mesh_frame_from_vtp(read_vtp(meshes), quoted(meshes));
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
  return render_frame(load_snapshot_frame(snapshot), plane, out);
}

}  // namespace invasim
