#include "io/slice_axes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/text_format.hpp"
#include "io/xml.hpp"

namespace invasim {

namespace {

constexpr double kFont = 13.0;          // px, axis and legend text
constexpr double kCharWidth = 7.0;      // px, a generous mean width of a sans-serif glyph
constexpr double kLegendRow = 22.0;     // px per legend row
constexpr double kLegendSample = 26.0;  // px, width of a legend entry's sample
constexpr double kLegendGap = 18.0;     // px between legend entries

// Short decimal form for captions and tick labels: 10 significant digits hide the round-off
// that summing dt accumulates (6000.000000013062 -> 6000).
std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v == 0.0 ? 0.0 : v);  // no "-0"
  return buf;
}

// Where each legend entry goes: (x offset from the left margin, row), wrapping at `width`.
std::vector<std::pair<double, int>> legend_layout(const std::vector<LegendEntry>& legend,
                                                  double width) {
  std::vector<std::pair<double, int>> at;
  double x = 0.0;
  int row = 0;
  for (const LegendEntry& e : legend) {
    const double w = kLegendSample + 6.0 + kCharWidth * double(e.label.size());
    if (x > 0.0 && x + w > width) x = 0.0, ++row;
    at.push_back({x, row});
    x += w + kLegendGap;
  }
  return at;
}

// Appends ` name="value"` (value as svg_number writes it).
void svg_attribute(std::string& out, const char* name, double value) {
  out += ' ';
  out += name;
  out += "=\"";
  svg_number(out, value);
  out += '"';
}

void text_at(std::string& out, double x, double y, const char* anchor, const std::string& s,
             const char* extra = "") {
  out += "  <text";
  svg_attribute(out, "x", x);
  svg_attribute(out, "y", y);
  out += " text-anchor=\"";
  out += anchor;
  out += "\" font-family=\"DejaVu Sans, Arial, sans-serif\" font-size=\"";
  svg_number(out, kFont);
  out += "\"";
  out += extra;
  out += '>';  // appended piecewise: GCC 12 warns (-Wrestrict) on "..." + std::string&&
  out += xml_escape(s);
  out += "</text>\n";
}

void tick_line(std::string& out, const char* axis, double x1, double y1, double x2, double y2) {
  const std::string attributes = std::string("data-tick=\"") + axis + "\"";
  svg_line(out, attributes.c_str(), x1, y1, x2, y2, "stroke=\"black\" stroke-width=\"1\"");
}

// "x [σ], normal to the walls" for the wall axis, "y [σ], periodic" for a periodic one.
std::string axis_title(const Box& box, int axis) {
  std::string t(1, "xyz"[axis]);
  t += " [\u03c3]";
  t += box.periodic(axis) ? ", periodic" : ", normal to the walls";
  return t;
}

// Tick positions: multiples of a round step (1, 2 or 5 times a power of ten) in [lo, hi],
// about 4 to 10 of them.
std::vector<double> axis_ticks(double lo, double hi) {
  std::vector<double> ticks;
  const double span = hi - lo;
  if (!(span > 0.0) || !std::isfinite(span)) return ticks;
  const double raw = span / 6.0, mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double f = raw / mag;
  const double step = (f < 1.5 ? 1.0 : f < 3.5 ? 2.0 : f < 7.5 ? 5.0 : 10.0) * mag;
  const double eps = 1e-9 * span;
  for (double k = std::ceil((lo - eps) / step); k * step <= hi + eps; k += 1.0)
    ticks.push_back(k * step);
  return ticks;
}

}  // namespace

SliceCanvas slice_canvas(const Slice& s, double size_px, const std::vector<LegendEntry>& legend) {
  const Box& box = s.box;
  const int u = s.u_axis, w = s.w_axis;
  SliceCanvas cv{box.lo()[u], box.hi()[u], box.lo()[w], box.hi()[w],
                 size_px / std::max(box.length(u), box.length(w))};
  int rows = 0;
  for (const auto& [x, row] : legend_layout(legend, (cv.hi_u - cv.lo_u) * cv.scale))
    rows = std::max(rows, row + 1);
  cv.legend_height = rows * kLegendRow + 6.0;
  return cv;
}

std::string slice_caption(const Slice& s) {
  std::string t(1, "xyz"[s.plane.axis]);
  t += " = " + short_number(s.plane.value) + " \u03c3, step " + std::to_string(s.step) +
       ", t = " + short_number(s.time) + " \u03c4";
  return t;
}

void append_axes(std::string& out, const SliceCanvas& cv, const Slice& s) {
  const double x0 = cv.x(cv.lo_u), y0 = cv.y(cv.lo_w);
  out += "  <g id=\"axes\">\n";
  for (double t : axis_ticks(cv.lo_u, cv.hi_u)) {
    tick_line(out, "u", cv.x(t), y0, cv.x(t), y0 + 6.0);
    text_at(out, cv.x(t), y0 + 20.0, "middle", short_number(t), " data-tick-label=\"u\"");
  }
  for (double t : axis_ticks(cv.lo_w, cv.hi_w)) {
    tick_line(out, "w", x0 - 6.0, cv.y(t), x0, cv.y(t));
    text_at(out, x0 - 9.0, cv.y(t) + 4.5, "end", short_number(t), " data-tick-label=\"w\"");
  }
  text_at(out, 0.5 * (cv.x(cv.lo_u) + cv.x(cv.hi_u)), y0 + 40.0, "middle",
          axis_title(s.box, s.u_axis), " data-axis=\"u\"");
  const double ym = 0.5 * (cv.y(cv.lo_w) + cv.y(cv.hi_w));
  std::string rotate = " data-axis=\"w\" transform=\"rotate(-90 ";
  svg_number(rotate, 18.0);
  rotate += ' ';
  svg_number(rotate, ym);
  rotate += ")\"";
  text_at(out, 18.0, ym, "middle", axis_title(s.box, s.w_axis), rotate.c_str());
  out += "  </g>\n";
}

void append_legend(std::string& out, const SliceCanvas& cv,
                   const std::vector<LegendEntry>& legend) {
  const double top = cv.y(cv.lo_w) + cv.below;
  out += "  <g id=\"legend\">\n";
  const auto at = legend_layout(legend, (cv.hi_u - cv.lo_u) * cv.scale);
  for (std::size_t k = 0; k < legend.size(); ++k) {
    const LegendEntry& e = legend[k];
    const double x = cv.left + at[k].first, y = top + at[k].second * kLegendRow + 8.0;
    out += "   <g data-legend=\"" + xml_escape(e.kind) + "\">";
    std::string sample;
    auto attr = [&](const char* name, double v) {
      sample += ' ';
      sample += name;
      sample += "=\"";
      svg_number(sample, v);
      sample += '"';
    };
    if (e.kind.rfind("cell", 0) == 0) {
      sample += "<circle";
      attr("cx", x + 13.0);
      attr("cy", y);
      attr("r", 6.0);
      sample += ' ';
      sample += e.kind == "cell-passive" ? slice_style::kCellPassive : slice_style::kCellActive;
      sample += "/>";
    } else if (e.kind == "adipocyte") {
      for (const char* style : {slice_style::kAdipocyteFill, slice_style::kAdipocyteOutline}) {
        sample += "<rect";
        attr("x", x + 1.0);
        attr("y", y - 7.0);
        attr("width", 24.0);
        attr("height", 14.0);
        attr("rx", 6.0);
        sample += ' ';
        sample += style;
        sample += "/>";
      }
    } else {
      sample += "<line";
      attr("x1", x);
      attr("y1", y);
      attr("x2", x + kLegendSample);
      attr("y2", y);
      sample += ' ';
      sample += e.kind == "mesh"   ? slice_style::kMesh
                : e.kind == "wall" ? "stroke=\"black\" stroke-width=\"4\""
                                   : "stroke=\"black\" stroke-width=\"1\" stroke-dasharray=\"6,4\"";
      sample += "/>";
    }
    out += sample + "</g>\n";
    text_at(out, x + kLegendSample + 6.0, y + 4.5, "start", e.label);
  }
  out += "  </g>\n";
}

void svg_number(std::string& out, double v) {
  text::append_fixed(out, v, 2);
}

void svg_line(std::string& out, const char* attributes, double x1, double y1, double x2, double y2,
              const char* style) {
  out += "  <line ";
  out += attributes;
  svg_attribute(out, "x1", x1);
  svg_attribute(out, "y1", y1);
  svg_attribute(out, "x2", x2);
  svg_attribute(out, "y2", y2);
  out += ' ';
  out += style;
  out += "/>\n";
}

}  // namespace invasim
