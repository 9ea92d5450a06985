#pragma once
// What a Dynamics steps: a System with its ForceField, and a revision count. Every change made
// outside a run of a Dynamics (the state, the forces, their parameters) bumps the revision;
// a Dynamics re-prepares (re-evaluates the forces and the drive) before its next step when the
// Model, or its revision, is not the one of its last run (RunRecord). The Lua System object is
// a Model (run/objects.hpp).
#include <cstdint>
#include <memory>

#include "forces/force.hpp"
#include "integrate/dynamics.hpp"
#include "state/system.hpp"

namespace invasim {

struct Model {
  Model(const Box& box, std::uint64_t seed) : system(box, seed) {}
  System system;
  ForceField forces;
  std::uint64_t revision = 0;
  void changed() { ++revision; }
};

// The Model a Dynamics last ran on (or was loaded for), and that Model's revision then.
class RunRecord {
 public:
  // Invalidates `dynamics` unless it last ran on `model` at model's current revision.
  void check(Dynamics& dynamics, const std::shared_ptr<Model>& model) const {
    if (last_.lock() != model || revision_ != model->revision) dynamics.invalidate();
  }
  // After a run of the Dynamics on `model` (or a checkpoint loaded into both).
  void ran_on(const std::shared_ptr<Model>& model) {
    last_ = model;
    revision_ = model->revision;
  }

 private:
  std::weak_ptr<Model> last_;
  std::uint64_t revision_ = 0;
};

}  // namespace invasim
