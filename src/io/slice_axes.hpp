#pragma once
// The frame around a slice picture (docs/output_formats.md, "Slice pictures"): the pixel
// layout, the axes with ticks in sigma, the caption with the time in tau and the legend.
// render_slice.cpp draws the shapes inside the plot area.
#include <string>
#include <vector>

#include "io/slice.hpp"

namespace invasim {

// Maps simulation coordinates (u, w) to SVG pixels (w upwards) and holds the page layout:
// the plot area (the box) with room for the caption above, the vertical axis to the left and
// the horizontal axis and the legend below.
struct SliceCanvas {
  double lo_u, hi_u, lo_w, hi_w, scale;
  double left = 72.0, right = 24.0, top = 44.0, below = 52.0;  // margins around the box
  double legend_height = 0.0;
  double x(double u) const { return left + (u - lo_u) * scale; }
  double y(double w) const { return top + (hi_w - w) * scale; }
  double width() const { return left + right + (hi_u - lo_u) * scale; }
  double height() const { return top + below + legend_height + (hi_w - lo_w) * scale; }
};

// Appends an SVG number with 2 decimals (the pictures' coordinate format).
void svg_number(std::string& out, double v);
// Appends `  <line ATTRIBUTES x1=".." y1=".." x2=".." y2=".." STYLE/>` and a newline (ticks,
// box edges).
void svg_line(std::string& out, const char* attributes, double x1, double y1, double x2, double y2,
              const char* style);

// One legend entry: a sample drawn by `kind` ("cell-active", "cell-passive", "cell",
// "adipocyte", "mesh", "wall", "periodic") and its label.
struct LegendEntry {
  std::string kind, label;
};

// The canvas of a slice whose longer box side spans `size_px` pixels, with room for `legend`.
SliceCanvas slice_canvas(const Slice& s, double size_px, const std::vector<LegendEntry>& legend);

// SVG text: caption ("z = 10.05 sigma, step 500, t = 25 tau"), axes with tick marks and
// labels in sigma, the axis titles (the wall normal named), and the legend.
std::string slice_caption(const Slice& s);
void append_axes(std::string& out, const SliceCanvas& cv, const Slice& s);
void append_legend(std::string& out, const SliceCanvas& cv, const std::vector<LegendEntry>& legend);

// Styles shared by the shapes and their legend samples.
namespace slice_style {
inline constexpr const char* kCellActive =
    "fill=\"#e3221c\" stroke=\"#5c0000\" stroke-width=\"0.6\"";
inline constexpr const char* kCellPassive =
    "fill=\"#fd9a4b\" stroke=\"#6b2c00\" stroke-width=\"0.6\"";
inline constexpr const char* kAdipocyteFill = "fill=\"#9ee9f2\" stroke=\"none\"";
inline constexpr const char* kAdipocyteOutline =
    "fill=\"none\" stroke=\"#00424a\" stroke-width=\"1.8\" stroke-linejoin=\"round\"";
inline constexpr const char* kMesh =
    "fill=\"none\" stroke=\"#00424a\" stroke-width=\"0.6\" stroke-opacity=\"0.45\"";
}  // namespace slice_style

}  // namespace invasim
