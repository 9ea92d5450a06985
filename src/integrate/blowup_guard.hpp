#pragma once
// Blow-up guard: stops a run that has become meaningless (a numerical instability, a too
// large time step) with a SimulationError that says where, instead of letting NaNs spread
// into the output. A site has blown up when its position or velocity is not finite, or when
// it has left the box through a wall by more than its diameter (x < lo.x - d or x > hi.x + d
// on every non-periodic axis). Dynamics::run checks every `every()` steps (at steps that are
// multiples of it, so chunked and continuous runs check at the same steps) and at the end of
// each run.
#include <cstdint>

#include "state/system.hpp"

namespace invasim {

// Throws SimulationError naming the step, the first offending site (lowest index, so the
// result does not depend on the thread count), its kind and the offending value, e.g.
// "blow-up at step 1234: site 17 (cancer cell) has a non-finite position (nan, 1.2, 3.4)".
// One serial pass over the sites. A NaN spreads to neighbouring sites through the forces
// within a step, so the site named is the lowest-index one affected, not necessarily the
// first to go wrong.
void check_blowup(const System& sys);

// How often a run checks: every `every` steps (default 100, at least 1).
class BlowupGuard {
 public:
  static constexpr std::uint64_t kDefaultEvery = 100;
  std::uint64_t every() const { return every_; }
  // Throws InputError unless every >= 1.
  void set_every(std::uint64_t every);
  // True when a check is due after completing step `step`.
  bool due(std::uint64_t step) const { return step % every_ == 0; }

 private:
  std::uint64_t every_ = kDefaultEvery;
};

}  // namespace invasim
