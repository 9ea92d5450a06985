#pragma once
// Extended XYZ snapshots of the cancer cells (docs/output_formats.md, "Cells: extended XYZ"),
// in the form OVITO reads without any column mapping:
//   N
//   Lattice="Lx 0 0 0 Ly 0 0 0 Lz" Origin="x0 y0 z0"
//   Properties=species:S:1:pos:R:3:radius:R:1:velo:R:3:orient:R:3 pbc="F T T" Time=t Step=n C x y z
//   r vx vy vz nx ny nz
// and a reader for such files (our own, and any extended XYZ with an orthorhombic Lattice and
// a pos column), used by the slice renderer and the tests.
#include <filesystem>
#include <map>
#include <string>
#include <string_view>

#include "io/frame.hpp"

namespace invasim {

// The Properties value written for every cell frame.
inline constexpr std::string_view kXyzProperties =
    "species:S:1:pos:R:3:radius:R:1:velo:R:3:orient:R:3";

// The text of one extended XYZ frame of the frame's cells (species "C", positions as stored:
// wrapped on periodic axes).
std::string xyz_frame_text(const Frame& frame);

// The key=value pairs of an extended XYZ comment line (quotes removed).
std::map<std::string, std::string> parse_xyz_comment(std::string_view line);

// Frame `index` (0 = first) of an extended XYZ text: box (Lattice must be diagonal; Origin
// defaults to 0, pbc to "T T T"), Step and Time (0 if absent) and the cells; radius, velo and
// orient default to 0.5, 0 and 0 when absent. `origin` names the source in error messages.
Frame parse_xyz(std::string_view text, const std::string& origin, std::size_t index = 0);
// Same, from a file.
Frame read_xyz(const std::filesystem::path& path, std::size_t index = 0);

}  // namespace invasim
