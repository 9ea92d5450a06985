#pragma once
// VTK XML snapshots for ParaView (docs/output_formats.md, "VTK"): ASCII PolyData (.vtp) of the
// adipocyte meshes (triangles with per-triangle body id and shape parameter) and of the cancer
// cells (vertices with radius, velocity, orientation), a ParaView collection (.pvd) indexing
// a time series, and readers for exactly these files (used by the renderer and the tests).
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "io/frame.hpp"

namespace invasim {

// The .vtp text of all adipocyte meshes of a frame: Points (each body whole, centroid in the
// box), Polys (connectivity, offsets), PointData "radius" (vertex contact radius), CellData
// "adipocyte" (Int32) and "shape_parameter" (Float64), FieldData with the box, the time and
// the step.
std::string adipocytes_vtp_text(const Frame& frame);
// The .vtp text of the cancer cells: Points (wrapped), Verts (one per cell), PointData
// "radius", "velocity" (3), "orientation" (3), FieldData as above.
std::string spheres_vtp_text(const Frame& frame);

// One data set of a .pvd collection: its time and its file (relative to the .pvd).
struct PvdEntry {
  double time = 0.0;
  std::string file;
};
// The .pvd text of a time series.
std::string pvd_text(const std::vector<PvdEntry>& entries);
// The entries of a .pvd file in file order. Throws IoError if it is not a VTK Collection.
std::vector<PvdEntry> read_pvd(const std::filesystem::path& path);
// The same for text; `origin` names it in messages.
std::vector<PvdEntry> parse_pvd(std::string_view text, const std::string& origin);

// The contents of one of our .vtp files.
struct VtpData {
  struct Array {
    std::string type;  // VTK type name: Float64, Int32, Int64, UInt64
    int components = 1;
    std::vector<double> values;
  };
  std::vector<Vec3> points;
  std::vector<std::int64_t> poly_connectivity, poly_offsets;
  std::vector<std::int64_t> vert_connectivity, vert_offsets;
  std::map<std::string, Array> point_data, cell_data, field_data;
};
VtpData parse_vtp(std::string_view text, const std::string& origin);
VtpData read_vtp(const std::filesystem::path& path);

// The frame stored in an adipocytes .vtp (box, time, step and meshes; no cells). Every poly
// must be a triangle; vertex radii are 0 if the file has no PointData "radius". `origin` names the
// source in error messages.
Frame mesh_frame_from_vtp(const VtpData& vtp, const std::string& origin);
// The frame stored in a spheres .vtp (box, time, step and cells; no meshes).
Frame cell_frame_from_vtp(const VtpData& vtp, const std::string& origin);

}  // namespace invasim
