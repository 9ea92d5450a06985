#pragma once
// Flat walls normal to x at the box's lower and upper x bounds (docs/model.md, "Forces"). A site at
// distance d from a wall feels F = (eps/s)(1 - d/s) into the box for d <= s, where s is the
// site's own diameter. The reaction force on each wall is kept for the barostat and the
// pressure measurement.
#include "forces/force.hpp"

namespace invasim {

class WallForce : public TeamForce {
 public:
  explicit WallForce(double eps = 1.0, bool left = true, bool right = true);
  std::string name() const override { return "wall"; }
  void prepare_team(System& sys, const ForceFlags& flags) override;
  ForceResult add_forces_team(System& sys, const ForceFlags& flags) override;
  // x component of the force the sites exert on the left / right wall (last evaluation).
  double left_wall_force() const { return left_force_; }
  double right_wall_force() const { return right_force_; }
  double eps() const { return eps_; }
  bool left() const { return left_; }
  bool right() const { return right_; }

 private:
  double eps_;
  bool left_, right_;
  double left_force_ = 0.0, right_force_ = 0.0;
  struct PerSite {
    double left = 0, right = 0, energy = 0, virial = 0;
    PerSite& operator+=(const PerSite& o) {
      left += o.left;
      right += o.right;
      energy += o.energy;
      virial += o.virial;
      return *this;
    }
  };
  std::vector<PerSite> partial_;  // block sums (team_deterministic_sum)
};

}  // namespace invasim
