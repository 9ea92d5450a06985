#pragma once
// Pictures of a slice (docs/output_formats.md, "Slice pictures"): an SVG like the paper's
// Fig. 1(c-d), with cancer cells as red discs (active red, passive orange when both are
// present), each adipocyte as the section of its contact envelope (mesh plus vertex spheres)
// filled in cyan with its own dark closed outline (io/slice_outline.hpp) and its mesh section
// as a thin line, walls as thick black lines and periodic edges as dashed lines; shapes that
// cross a periodic edge are drawn again at their periodic image (clipped to the box). Axes
// with ticks in sigma, the time in tau and a legend frame it (io/slice_axes.hpp). Entry point
// of `invasim render`.
#include <filesystem>
#include <string>

#include "io/slice.hpp"

namespace invasim {

// What a picture shows: cells cut by the plane, adipocyte cross-sections (closed polygons),
// and open chains (only for meshes that are not closed). Periodic copies are not counted.
struct RenderCounts {
  int discs = 0;
  int polygons = 0;
  int open_chains = 0;
  int vertex_discs = 0;  // sections of adipocyte vertex spheres
};
RenderCounts count_shapes(const Slice& slice);

// The SVG text of a slice; the longer box side spans `size_px` pixels (axes, caption and
// legend around it).
std::string slice_svg(const Slice& slice, double size_px = 800.0);

// The frame a snapshot file belongs to. Given any of cells_<step>.xyz, spheres_<step>.vtp or
// adipocytes_<step>.vtp, it loads the cells (from the file given if it holds cells, else from
// cells_<step>.xyz, else from spheres_<step>.vtp) and the meshes (adipocytes_<step>.vtp)
// found next to it; a missing companion file just leaves that part empty. A file not named that way
// is loaded alone (.xyz: cells; .vtp: meshes if it has polygons, else cells). A file with a
// non-finite coordinate or radius is refused (io/frame_check.hpp).
Frame load_snapshot_frame(const std::filesystem::path& snapshot);

// load_snapshot_frame, cut_frame, and the SVG (slice_svg) written atomically to `out`.
RenderCounts render_snapshot(const std::filesystem::path& snapshot, const SlicePlane& plane,
                             const std::filesystem::path& out);

}  // namespace invasim
