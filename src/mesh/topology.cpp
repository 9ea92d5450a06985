#include "mesh/topology.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/errors.hpp"

namespace invasim {

MeshTopology::MeshTopology(int n_vertices, std::vector<Face> faces)
    : n_vertices_(n_vertices), faces_(std::move(faces)) {
  if (n_vertices < 4) fail_input("mesh: ", n_vertices, " vertices; a closed mesh needs >= 4");
  if (faces_.size() < 4) fail_input("mesh: ", faces_.size(), " faces; a closed mesh needs >= 4");
  // Directed edge -> face that uses it; a closed oriented manifold uses each directed edge
  // once and its reverse once.
  std::map<std::pair<int, int>, int> directed;
  std::vector<int> uses(n_vertices, 0);
  for (std::size_t f = 0; f < faces_.size(); ++f) {
    const Face& t = faces_[f];
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= n_vertices)
        fail_input("mesh: face ", f, " has vertex index ", t[k], " outside [0, ", n_vertices, ")");
      ++uses[t[k]];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
      fail_input("mesh: face ", f, " repeats a vertex (", t[0], ", ", t[1], ", ", t[2], ")");
    for (int k = 0; k < 3; ++k) {
      const std::pair<int, int> e{t[k], t[(k + 1) % 3]};
      if (!directed.emplace(e, int(f)).second)
        fail_input("mesh: edge (", e.first, ", ", e.second, ") is used twice in the same direction",
                   " (faces ", directed[e], " and ", f, "): not a consistently oriented manifold");
    }
  }
  for (const auto& [e, f] : directed) {
    if (!directed.count({e.second, e.first}))
      fail_input("mesh: edge (", e.first, ", ", e.second, ") of face ", f,
                 " has no opposite face: the mesh is not closed");
    if (e.first < e.second) edges_.push_back(e);
  }
  for (int v = 0; v < n_vertices; ++v)
    if (uses[v] == 0) fail_input("mesh: vertex ", v, " is not used by any face");
  const int euler = n_vertices - n_edges() + n_faces();
  if (euler != 2)
    fail_input("mesh: Euler characteristic V - E + F = ", euler, "; a closed genus-0 mesh has 2");
  corner_offsets_.assign(n_vertices + 1, 0);
  for (int v = 0; v < n_vertices; ++v) corner_offsets_[v + 1] = corner_offsets_[v] + uses[v];
  corners_.resize(std::size_t(corner_offsets_[n_vertices]));
  for (int m = 0; m < 3; ++m)
    for (const Face& f : faces_) face_corner_[m].push_back(f[m]);
  std::vector<int> next(corner_offsets_.begin(), corner_offsets_.end() - 1);
  for (std::size_t f = 0; f < faces_.size(); ++f)
    for (int k = 0; k < 3; ++k) corners_[std::size_t(next[faces_[f][k]]++)] = {int(f), k};
}

MeshShape icosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 6)
    fail_input("icosphere: subdivisions = ", subdivisions, " must be in [0, 6]");
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Vec3> v = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<MeshTopology::Face> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<int, int>, int> midpoint;
    auto split = [&](int a, int b) {
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return midpoint[key] = int(v.size()) - 1;
    };
    std::vector<MeshTopology::Face> next;
    for (const auto& tri : f) {
      const int ab = split(tri[0], tri[1]), bc = split(tri[1], tri[2]), ca = split(tri[2], tri[0]);
      next.push_back({tri[0], ab, ca});
      next.push_back({tri[1], bc, ab});
      next.push_back({tri[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  const int n = int(v.size());
  return {std::make_shared<const MeshTopology>(n, std::move(f)), std::move(v)};
}

}  // namespace invasim
