#pragma once
// Lipolysis (docs/model.md, Bodies, "Lipolysis"): an adipocyte touched by cancer cells releases
// lipid and shrinks. While at least one cancer cell touches a body, its reference volume v_0
// falls at `rate` x v_0(initial) per unit time, down to `floor` x v_0(initial)
// (MeshBody::ref_volume_initial); its reference face areas scale with v_0^(2/3), so its
// reference shape parameter A_0 stays what it was, and its V_i (MeshBody::outer_volume, the
// packing fractions' volume) scales as the union volume of its current shape brought to the
// old and the new v_0.
//
// Touching is contact: a cancer cell closer than (d_cell + d_vertex)/2 to one of the body's
// vertices, the distance at which the contact force acts. Contact is what a cell exerts on an
// adipocyte at each step, is found from positions alone at any step, and is exact in time;
// a shared Voronoi face would also count cells across a gap of up to a cell diameter and is
// measured only every `every` steps at ~100 steps' cost. Contact is sampled at the steps
// where lipolysis is applied (Simulation's LipolysisOperation, every N steps, elapsed = N dt).
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct LipolysisParams {
  double rate = 0.0;      // fraction of v_0(initial) lost per unit time while touched (1/tau)
  double floor = 0.5;     // smallest v_0, as a fraction of v_0(initial), in (0, 1]
  void validate() const;  // throws InputError naming the bad value
};

class Lipolysis {
 public:
  explicit Lipolysis(const LipolysisParams& params);
  const LipolysisParams& params() const { return params_; }
  // For every body, whether a cancer cell touches it now (user layout, any box).
  std::vector<char> touched(const System& sys) const;
  // Shrinks every touched body's reference state by `elapsed` time of lipolysis; returns the
  // number of bodies touched. Deterministic and independent of threads (serial).
  int apply(System& sys, double elapsed) const;

 private:
  LipolysisParams params_;
};

// Sets body b's reference volume to v, scaling its reference face areas by (v / v_0)^(2/3)
// (the reference shape parameter is kept). v must be > 0.
void set_reference_volume(MeshBody& body, double v);

}  // namespace invasim
