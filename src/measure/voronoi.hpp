#pragma once
// Voronoi measurements (docs/measurements.md, "Voronoi tessellation"): the tessellation of all
// sites (cancer-cell centres and adipocyte vertices) in the box with walls in x and periodic y, z;
// from it the interfacial area A_t, the adipocyte surfaces S_i, A_t^max, the Voronoi cell volumes
// and the local adipocyte packing fraction. Definitions and decisions: docs/measurements.md.
//
// Method (docs/measurements.md, "Method"): CGAL's 3D Delaunay triangulation of the sites, their
// periodic images in y, z within a margin around the box and eight far dummy points beyond the
// walls; each real cell is clipped to the slab between the walls. Every vertex of a clipped
// real cell is verified against the infinite periodic point set (no image nearer than the
// site; missing images found there are inserted), so every real cell is exact. Only
// voronoi.cpp includes CGAL.
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct VoronoiOptions {
  // Width in y and z of the layer of periodic images inserted around the box at the start
  // (0: automatic, 1.5 mean site spacings). The verification inserts whatever further images a
  // real cell needs.
  double margin = 0.0;
  // Radical (power) tessellation with weights (diameter/2)^2: invasim's variant, not the
  // paper's (the paper uses the plain Voronoi tessellation, the default).
  bool radical = false;
  // measure_voronoi only: skip the faces between two cancer cells, which none of its
  // results but the tessellation's cancer-cell volumes (then NaN) and face list need
  // (docs/measurements.md; the main job's observer sets it: a third of the call's time).
  bool interface_only = false;
};

// Neighbour codes of a face lying on a wall.
inline constexpr int kLeftWall = -1;
inline constexpr int kRightWall = -2;

// One face of the tessellation, listed once: between the cells of sites a and b (a <= b),
// or between the cell of a and a wall (b = kLeftWall / kRightWall). A site may share several
// faces with another site (different periodic images) or with itself (small boxes).
struct VoronoiFace {
  int a = 0;
  int b = 0;
  double area = 0.0;
  // From site a to the image of b across the face (for a wall face: to a's mirror image
  // across the wall, 2 (wall - x_a) along x); the face's outward normal seen from a is
  // offset / |offset|.
  Vec3 offset = Vec3::Zero();
};

struct VoronoiTessellation {
  std::vector<VoronoiFace> faces;  // every face of positive area once
  std::vector<double> volume;      // per site; 0 for a site without a cell (see docs)
  double margin = 0.0;             // image margin in y and z
  int refinements = 0;             // verification passes that had to insert images
  std::size_t n_points = 0;        // points triangulated (sites, images, dummy points)
  std::size_t n_added = 0;         // images inserted by the verification (beyond the margin)
};

// Tessellation of `points` in `box` (walls in x, periodic y and z; positions need not be
// wrapped). With opt.radical, `weights` (one per point) give the power diagram. Faces
// between two points flagged in `skip_faces_between` (empty, or one flag per point) are
// neither computed nor listed, and the flagged points' volumes are NaN. Throws InputError if
// the box is not walled in x and periodic in y, z or the weights or flags are missing,
// SimulationError if the cells could not be verified (a site not finite, or no convergence).
VoronoiTessellation tessellate(const Box& box, const std::vector<Vec3>& points,
                               const VoronoiOptions& opt = {},
                               const std::vector<double>& weights = {},
                               const std::vector<char>& skip_faces_between = {});

// The Voronoi measurements of one configuration (docs/measurements.md, "Voronoi tessellation").
struct VoronoiMeasurement {
  double interface_area = 0.0;         // A_t = cancer_adipocyte_area + cancer_wall_area
  double cancer_adipocyte_area = 0.0;  // faces between cancer-cell and vertex cells
  double cancer_wall_area = 0.0;       // faces of cancer-cell cells on either wall
  double max_interface_area = 0.0;     // A_t^max = 2 L_y L_z + sum_i S_i
  double interface_ratio = 0.0;        // A_t / A_t^max
  // S_i: the faces of the union of i's vertex cells that are not on a wall (the 2 L_y L_z of
  // A_t^max already counts both walls as fully covered by cancer cells).
  std::vector<double> adipocyte_surface;
  // The faces of the union of i's vertex cells on either wall: the union's whole surface is
  // adipocyte_surface[i] + adipocyte_wall_area[i].
  std::vector<double> adipocyte_wall_area;
  double adipocyte_wall_total = 0.0;     // sum_i adipocyte_wall_area[i]
  std::vector<double> adipocyte_volume;  // volume of the union of i's vertex cells
  // phi_a,i = V_i / adipocyte_volume[i], V_i = MeshBody::outer_volume; NaN where V_i is
  // unknown (outer_volume == 0). Mean and population standard deviation (Delta phi_a) over
  // the bodies with known V_i (NaN if none).
  std::vector<double> local_phi_a;
  double mean_local_phi_a = 0.0;
  double std_local_phi_a = 0.0;
  VoronoiTessellation tessellation;  // per-site volumes, faces, margin
};

VoronoiMeasurement measure_voronoi(const System& sys, const VoronoiOptions& opt = {});

}  // namespace invasim
