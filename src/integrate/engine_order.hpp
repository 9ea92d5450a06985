#pragma once
// The engine order of the sites (docs/performance.md, "Sites in cell order"): the order in
// which Dynamics stores them during its steps (System::to_engine). Sites are sorted by kind (as
// the neighbour list bins them), then by cell of a grid of cells one largest diameter of the
// kind wide, with the axis along which the contact kernel cuts its thread slabs (slab_axis)
// varying slowest, so that a slab is a contiguous range of slots; ties by permanent index. The
// order is a function of the state alone (positions, kinds, diameters, box), never of the
// storage layout, the history or the thread count.
#include <vector>

#include "state/system.hpp"

namespace invasim {

// The permanent indices of the sites in engine order (a permutation of [0, n_sites)).
std::vector<int> spatial_order(const System& sys);

// Puts the System in the engine layout for the scope's lifetime (choosing the engine order
// first if the sites have none) and back in the user layout at its end, also when an exception
// leaves the scope; does nothing if the System already is in the engine layout.
class EngineLayoutScope {
 public:
  explicit EngineLayoutScope(System& sys);
  ~EngineLayoutScope();
  EngineLayoutScope(const EngineLayoutScope&) = delete;
  EngineLayoutScope& operator=(const EngineLayoutScope&) = delete;

 private:
  System& sys_;
  bool entered_ = false;
};

}  // namespace invasim
