#pragma once
// ECM tethers (docs/model.md, "Forces" and protocol step 4): linear springs between adipocyte
// centres of mass, U = K/2 (R_ij - l_ij0)^2 (sigma = 1). A tether joins body a to the periodic
// image of body b that was nearest when it was made (the minimum image then) and keeps that
// image for its whole life: re-choosing the nearest image at every step would flip the
// spring's force when a component of R_ij passes half the box, as it does in small boxes where
// l_ij0 approaches L/2. The force on a centre is shared equally by the body's vertices.
#include "forces/force.hpp"

namespace invasim {

struct Tether {
  int a, b;            // body indices
  double rest_length;  // l_ij0
  // Box lengths taken off the unwrapped centre difference R_a - R_b along y and z (0 along
  // x): R_ij = Box::minus_periods(R_a - R_b, periods), the image chosen when the tether was made.
  Vec3i periods = Vec3i::Zero();
};

class TetherForce : public TeamForce {
 public:
  explicit TetherForce(double stiffness);
  std::string name() const override { return "tether"; }
  void prepare_team(System& sys, const ForceFlags& flags) override;
  ForceResult add_forces_team(System& sys, const ForceFlags& flags) override;

  double stiffness() const { return stiffness_; }
  void set_stiffness(double k);
  const std::vector<Tether>& tethers() const { return tethers_; }
  // Removes every tether (before restoring them from a checkpoint).
  void clear() { tethers_.clear(); }
  // Adds one tether to the nearest image of b as the bodies stand now; rest length must be
  // >= 0, bodies distinct and valid.
  void add(const System& sys, int a, int b, double rest_length);
  // The same with the image given (a checkpoint restores it as it was).
  void add(const System& sys, int a, int b, double rest_length, const Vec3i& periods);
  // Tethers every pair of bodies whose centres are closer than a cutoff d_c chosen so that
  // the mean number of tethers per body is `mean_degree` (the M = mean_degree N_a / 2
  // shortest pairs; d_c is midway between the M-th and (M+1)-th distances); rest lengths are
  // the current separations. Returns d_c.
  double connect_by_mean_degree(const System& sys, double mean_degree);
  // Heterogeneity lambda: tethers whose midpoint lies in the lower half of the box in z get
  // l0 = (1 - lambda) R, the others (1 + lambda) R, with R the current separation.
  void apply_heterogeneity(const System& sys, double lambda);
  // Current centre of each body (unwrapped vertex centroid).
  static std::vector<Vec3> body_centres(const System& sys);
  // The tether's vector R_a - R_b (through its image) from the centres of body_centres.
  static Vec3 separation(const Box& box, const std::vector<Vec3>& centres, const Tether& t) {
    return box.minus_periods(centres[t.a] - centres[t.b], t.periods);
  }

 private:
  // Force on body a's centre from tether t (minus it on body b's), and its stretch.
  Vec3 tether_force(const Box& box, const Tether& t, double* stretch) const;
  double stiffness_;
  std::vector<Tether> tethers_;
  // Team scratch: body centres, and each body's tethers in tether order (CSR; index + 1 for
  // end a, -(index + 1) for end b), so that every body sums its forces in the serial order.
  std::vector<Vec3> centres_;
  std::vector<int> body_start_, body_tethers_;
};

}  // namespace invasim
