#pragma once
// Dilute random placement without overlaps (docs/model.md, protocol step 1): cancer cells and
// adipocytes at random positions inside given x ranges (all of y and z), each body treated
// as a ball (a cell: its diameter; an adipocyte: mesh radius + vertex radius) that must not
// overlap any ball already placed. With walls in x the balls stay between the walls; in a box
// periodic in x the centres' range may span the whole box (overlaps use the minimum image). Random
// numbers come from the system seed (stream kPlacement), so a placement is reproducible.
#include <vector>

#include "core/range.hpp"
#include "state/system.hpp"

namespace invasim {

struct SpherePlacement {
  int n = 0;
  std::vector<double> diameters{0.9, 1.1};  // assigned in turn: i-th cell gets d[i % size]
  Range x{0.0, 0.0};                        // range of the centres' x
  double max_attempts_per_cell = 10000;
  // Given centres instead of random ones (a start taken from another program, as LAMMPS's
  // read_data): n = positions.size(), inside the walls, wrapped on periodic axes; overlaps
  // are the caller's (they are not checked, and `x` is unused).
  std::vector<Vec3> positions;
};

struct MeshPlacement {
  int n = 0;
  double diameter = 6.0;  // outer diameter, vertex radii included
  // Adipocytes of many sizes (beyond the paper's one size; docs/model.md, "Bodies"), at most
  // one of: `diameters`, the k-th adipocyte gets diameters[k % size]; `spread` > 0, the
  // diameters are log-normal with mean `diameter`: d = diameter exp(spread z - spread^2/2),
  // z a standard normal keyed by the seed and the body's index (stream kPlacement).
  std::vector<double> diameters;
  double spread = 0.0;
  double vertex_diameter = 2.0;  // contact diameter of each vertex
  double shape_param = 1.1;      // reference shape parameter A_0
  int subdivisions = 1;          // icosphere(1): 42 vertices
  bool random_rotation = true;
  Range x{0.0, 0.0};          // range of the centres' x
  double volume_grid = 0.05;  // grid spacing for the union volume V_i
  double max_attempts_per_body = 10000;
};

// Memory per site assumed by the placement's memory check (core/memory_budget.hpp): the
// System's per-site arrays (~130 bytes), a neighbour list of ~50 entries, the forces' and
// measurements' per-site buffers; an upper estimate, so the check errs on the safe side.
inline constexpr double kBytesPerSite = 1024;

// Places meshes first, then spheres, avoiding every existing site. Returns the new site
// indices of the spheres (the cancer-cell group). Throws InputError when a region cannot
// hold the requested bodies (names the region and how many fitted); the System is then left
// as it was.
struct PlacementResult {
  std::vector<int> cells;
  std::vector<int> bodies;
};
PlacementResult place_random(System& sys, const MeshPlacement& meshes,
                             const SpherePlacement& spheres);

}  // namespace invasim
