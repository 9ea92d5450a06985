#pragma once
// A parameter that changes linearly with the time step (HOOMD-blue's ramp variant):
// value(step) = from + (to - from) * clamp((step - start) / steps, 0, 1). The ramp starts at
// the first step it is applied to (anchored then, so a run split into chunks or restarted
// from a checkpoint that saved `start` follows the same schedule) unless `start` is given.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

#include "core/errors.hpp"

namespace invasim {

struct Ramp {
  double from = 0.0;
  double to = 0.0;
  std::uint64_t steps = 1;             // length of the ramp in time steps (>= 1)
  std::optional<std::uint64_t> start;  // first step of the ramp; set on first use if empty

  void validate(const char* what) const {
    if (steps == 0) fail_input(what, ": a ramp needs steps >= 1");
    if (!std::isfinite(to - from))  // value() would give inf or nan on the way
      fail_input(what, ": a ramp from ", from, " to ", to,
                 " spans more than the largest number (to - from overflows)");
  }
  // Value at `step`, anchoring the start at this step on first use.
  double value(std::uint64_t step) {
    if (!start) start = step;
    if (step <= *start) return from;
    const double f = std::min(1.0, double(step - *start) / double(steps));
    return from + (to - from) * f;
  }
};

}  // namespace invasim
