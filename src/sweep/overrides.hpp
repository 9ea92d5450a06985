#pragma once
// Command-line changes of a loaded sweep spec, for `sweep init` (docs/sweeps.md, "Tiny runs"):
//   --set key=value   fixes a parameter: replaces its `set` value or its axis (product, seeds,
//                     zip list), or adds one the spec leaves at its default; parsed and checked
//                     like `invasim run --set`; the preparation takes it too unless prep.set
//                     gives the key itself
//   --take N          keeps the first N values of every product axis and zip group, 1 seed
//   --tiny            the spec's own `tiny = { set = {...}, take = N }`, then the above
// An undeclared key, a bad value, or a spec without `tiny` is an
// InputError naming the option, the value and what is allowed.
#include <optional>
#include <string>
#include <vector>

#include "core/params.hpp"
#include "sweep/spec.hpp"

namespace invasim::sweep {

struct SpecOverrides {
  bool tiny = false;
  std::vector<Override> set;  // --set key=value, in order
  std::optional<int> take;    // --take N
};

// Applies `o` to `spec` (in place): tiny first, then --set, then --take.
void apply_spec_overrides(SweepSpec& spec, const SpecOverrides& o);

}  // namespace invasim::sweep
