#pragma once
// Immutable connectivity of a closed, outward-oriented triangle mesh, shared by every
// adipocyte that uses it (Mirheo-style: topology apart from positions). Construction
// validates it: indices in range, every edge in exactly two faces with opposite
// orientations, every vertex used, genus 0. A malformed mesh throws InputError.
#include <array>
#include <memory>
#include <utility>
#include <vector>

#include "core/vec3.hpp"

namespace invasim {

class MeshTopology {
 public:
  using Face = std::array<int, 3>;
  MeshTopology(int n_vertices, std::vector<Face> faces);

  int n_vertices() const { return n_vertices_; }
  int n_faces() const { return int(faces_.size()); }
  int n_edges() const { return int(edges_.size()); }
  const std::vector<Face>& faces() const { return faces_; }
  const std::vector<std::pair<int, int>>& edges() const { return edges_; }
  // The faces around each vertex, in increasing face order, as (face, corner) pairs:
  // vertex v's are corners()[corner_offsets()[v] .. corner_offsets()[v + 1]). Lets a
  // per-face computation be summed per vertex in the order a loop over the faces would add it.
  const std::vector<int>& corner_offsets() const { return corner_offsets_; }
  const std::vector<std::pair<int, int>>& corners() const { return corners_; }
  // Corner m (0, 1, 2) of every face as one array: face_corner(m)[k] == faces()[k][m], for
  // loops over the faces that gather from plain arrays.
  const std::vector<int>& face_corner(int m) const { return face_corner_[m]; }

 private:
  int n_vertices_;
  std::vector<Face> faces_;
  std::vector<std::pair<int, int>> edges_;    // (a < b), each once
  std::vector<int> corner_offsets_;           // n_vertices + 1 offsets into corners_
  std::vector<std::pair<int, int>> corners_;  // (face, corner), grouped by vertex
  std::vector<int> face_corner_[3];
};

// A mesh shape: its topology and vertex positions on the unit sphere (or any reference shape).
struct MeshShape {
  std::shared_ptr<const MeshTopology> topology;
  std::vector<Vec3> vertices;
};

// Icosahedron with each edge split `subdivisions` times by midpoints projected onto the unit
// sphere. subdivisions = 1 gives the adipocyte mesh: 42 vertices, 80 faces, 120 edges.
MeshShape icosphere(int subdivisions);

}  // namespace invasim
