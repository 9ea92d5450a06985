#pragma once
// An operation a Simulation calls between steps (run/simulation.hpp): a sampler, a writer or
// an observer. The Simulation decides when (its Trigger); the operation only acts on the
// state it is given. Operations may read the System freely; one that changes the state or the
// forces must call Simulation::state_changed() so that the Dynamics re-evaluates its forces.
#include <string>
#include <vector>

namespace invasim {

class Simulation;

class Operation {
 public:
  virtual ~Operation() = default;
  // A short name for listings and error messages ("correlator sampler", "snapshot writer").
  virtual std::string name() const = 0;
  // Acts on the Simulation at its current step.
  virtual void apply(Simulation& sim) = 0;
  // Cells divided or died (ProliferationOperation): new_index is the new index of every old
  // site (-1: died). An operation that holds site indices follows them (default: none held).
  virtual void sites_changed(Simulation& /*sim*/, const std::vector<int>& /*new_index*/) {}
};

}  // namespace invasim
