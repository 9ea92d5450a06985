#pragma once
// What a picture of a frame needs: finite coordinates and radii (a NaN or infinite one would
// be written into the SVG as cx="nan" or r="inf"). The render command checks every frame it
// loads and refuses one that does not pass, naming the file, the particle and the value.
#include <cstddef>
#include <string>

#include "io/frame.hpp"

namespace invasim {

// Cells: finite positions, finite radii >= 0. `origin` names the file; `first_row_line`, if
// not 0, is the file line of cell 0 (XYZ rows; VTP points have none).
void require_drawable_cells(const CellFrame& cells, const std::string& origin,
                            std::size_t first_row_line = 0);

// Adipocyte meshes: finite vertex positions, finite vertex radii >= 0.
void require_drawable_meshes(const MeshFrame& meshes, const std::string& origin);

}  // namespace invasim
