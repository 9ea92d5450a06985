#pragma once
// The force interface: a force term reads the state and adds its forces into
// sites().force, and, when asked, returns its potential energy and virial. Integrators and
// the minimiser see forces only through a ForceField (a list of terms), so adding a term
// touches no integrator.
#include <memory>
#include <string>
#include <vector>

#include "state/system.hpp"

namespace invasim {

struct ForceFlags {
  bool energy = false;
  bool virial = false;
};

// Energy and the diagonal of the virial W_aa = sum over interactions of r_a F_a (so that
// W_aa = -dU/d(ln L_a) under an affine stretch of axis a).
struct ForceResult {
  double energy = 0.0;
  Vec3 virial = Vec3::Zero();
};

class Force {
 public:
  virtual ~Force() = default;
  virtual std::string name() const = 0;
  // Adds this term's forces into sys.sites().force.
  virtual ForceResult add_forces(System& sys, const ForceFlags& flags) = 0;
  // Drops cached state derived from positions (neighbour lists), e.g. after the System was
  // replaced by a checkpoint.
  virtual void invalidate_caches() {}
};

// An ordered list of force terms, evaluated together.
class ForceField {
 public:
  void add(std::shared_ptr<Force> force) { terms_.push_back(std::move(force)); }
  const std::vector<std::shared_ptr<Force>>& terms() const { return terms_; }
  // Zeroes all site forces, then adds every term; result per term in `per_term` if given.
  ForceResult compute(System& sys, const ForceFlags& flags = {},
                      std::vector<ForceResult>* per_term = nullptr);
  // Total potential energy (forces are recomputed as a side effect).
  double energy(System& sys) { return compute(sys, {true, false}).energy; }

 private:
  std::vector<std::shared_ptr<Force>> terms_;
};

}  // namespace invasim
