#pragma once
// Deformable-polyhedron shape energy of every adipocyte (docs/model.md, "Bodies"):
//   U_i = eps_v/2 (1 - v_i/v_i0)^2 + eps_a/2 sum_k (1 - a_ik/a_ik0)^2
// with the analytic gradient. Bodies are independent, so they are processed in parallel and
// each writes only its own vertices.
#include "forces/force.hpp"

namespace invasim {

class ShapeForce : public TeamForce {
 public:
  ShapeForce(double eps_v, double eps_a);
  std::string name() const override { return "shape"; }
  void prepare_team(System& sys, const ForceFlags& flags) override;
  ForceResult add_forces_team(System& sys, const ForceFlags& flags) override;
  double eps_v() const { return eps_v_; }
  double eps_a() const { return eps_a_; }

 private:
  double eps_v_, eps_a_;
  std::vector<ForceResult> per_body_;
};

// Shape energy of one body; adds its gradient with respect to the vertices to grad (which may
// be null). ShapeKernel's arithmetic, for callers outside the force loop.
double body_shape_energy(const MeshBody& body, const Vec3* x, double eps_v, double eps_a,
                         Vec3* grad);

}  // namespace invasim
