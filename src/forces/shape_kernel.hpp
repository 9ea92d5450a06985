#pragma once
// The shape energy of one adipocyte and its gradient (docs/model.md, "Bodies") with the faces
// in vector lanes: a first pass over the faces gathers their corners into arrays and sums the
// volume, a second computes each corner's gradient (volume and area parts together), then
// each vertex sums its corners through the topology's corner lists (MeshTopology::corners), in
// face order. The order of every sum is fixed by the topology, so results do not depend on
// the thread count (bodies are evaluated one per thread).
// Tests: "shape kernel" (against a plain one-face-at-a-time sum) and the finite-difference
// and Hessian tests of tests/unit/test_forces.cpp.
#include <vector>

#include "state/system.hpp"

namespace invasim {

class ShapeKernel {
 public:
  // Energy of `body` with vertices x (unwrapped, body order); grad (n_vertices entries) is
  // overwritten with the energy's gradient.
  double evaluate(const MeshBody& body, const Vec3* x, double eps_v, double eps_a, Vec3* grad);
  // The vertex centroid of the last evaluate's body (vertex_centroid of its x).
  const Vec3& centroid() const { return centroid_; }

 private:
  // Per-face arrays, structure of arrays, n_faces each (see evaluate).
  std::vector<double> buffer_;
  // The vertices' coordinates as three arrays, so that the face loop gathers from plain arrays.
  std::vector<double> vx_, vy_, vz_;
  Vec3 centroid_ = Vec3::Zero();
};

}  // namespace invasim
