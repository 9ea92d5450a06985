#pragma once
// The operations a Simulation schedules (run/operation.hpp): samplers and writers of the
// engine's own, and a function operation through which the Lua layer adds observers written
// in Lua (the engine knows no Lua).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "integrate/lipolysis.hpp"
#include "integrate/proliferation.hpp"
#include "io/snapshot_writer.hpp"
#include "measure/time_correlator.hpp"
#include "run/operation.hpp"

namespace invasim {

// Samples a TimeCorrelator (its interval must be the trigger's period times dt).
class CorrelatorSampler : public Operation {
 public:
  explicit CorrelatorSampler(std::shared_ptr<TimeCorrelator> correlator);
  std::string name() const override { return "correlator sampler"; }
  const TimeCorrelator& correlator() const { return *correlator_; }
  void apply(Simulation& sim) override;
  // The correlator's group follows its cells; dead ones leave it (TimeCorrelator::sites_changed).
  void sites_changed(Simulation& sim, const std::vector<int>& new_index) override;

 private:
  std::shared_ptr<TimeCorrelator> correlator_;
};

// Writes a snapshot frame of the System.
class SnapshotOperation : public Operation {
 public:
  explicit SnapshotOperation(std::shared_ptr<SnapshotWriter> writer);
  std::string name() const override { return "snapshot writer"; }
  void apply(Simulation& sim) override;

 private:
  std::shared_ptr<SnapshotWriter> writer_;
};

// Writes a checkpoint file atomically: `compose` fills the sections (each object writes its
// own, checkpoint/), then `written(step)` is told (optional, e.g. to log it).
class CheckpointOperation : public Operation {
 public:
  using ComposeFn = std::function<void(CheckpointWriter&)>;
  using WrittenFn = std::function<void(std::uint64_t step)>;
  CheckpointOperation(std::filesystem::path path, ComposeFn compose, WrittenFn written = {});
  std::string name() const override { return "checkpoint writer"; }
  void apply(Simulation& sim) override;

 private:
  std::filesystem::path path_;
  ComposeFn compose_;
  WrittenFn written_;
};

// An operation that applies a T (Lipolysis, Proliferation) at the System steps that are
// multiples of `every` (schedule it with Trigger::every(every)), each time for the time
// elapsed since the previous multiple or since step `since`, whichever is later: a run whose
// part with T starts between two multiples (a production after a quench of another length)
// credits the first application with its own steps only, and a run resumed from a checkpoint
// continues bit for bit when given the same `since`. Refuses a missing T and every = 0,
// naming `what`.
template <typename T>
class EveryOperation : public Operation {
 public:
  EveryOperation(std::shared_ptr<const T> object, std::uint64_t every, std::uint64_t since,
                 const char* what)
      : object_(std::move(object)), every_(every), since_(since), what_(what) {
    if (!object_) throw InputError(std::string(what) + ": no " + what + " given");
    if (every_ < 1) throw InputError(std::string(what) + ": every = 0 steps (must be >= 1)");
  }
  std::string name() const override { return what_; }

 protected:
  double elapsed(Simulation& sim) const;  // min(every, step - since) x dt
  std::shared_ptr<const T> object_;
  std::uint64_t every_, since_;
  const char* what_;
};

// Applies lipolysis to the System every `every` steps (EveryOperation's elapsed time). Like a
// parameter change between two steps, the new reference volumes act from the next force
// evaluation: the step's first half-kick uses the forces already computed, as a run restored
// from a checkpoint written at this step (which stores them) does, so both continue bit for
// bit.
class LipolysisOperation : public EveryOperation<Lipolysis> {
 public:
  LipolysisOperation(std::shared_ptr<const Lipolysis> lipolysis, std::uint64_t every,
                     std::uint64_t since)
      : EveryOperation(std::move(lipolysis), every, since, "lipolysis") {}
  void apply(Simulation& sim) override;
};

// Applies a Proliferation every `every` steps (EveryOperation's elapsed time of divisions and
// deaths), then makes the run follow the new set of sites: the methods' groups
// (Dynamics::sites_changed), the other operations (Operation::sites_changed: a correlator's group),
// the force terms' caches, and the forces of the new state (Dynamics::prepare), so that a
// checkpoint written at this step holds them and a run restored from it continues bit for bit.
class ProliferationOperation : public EveryOperation<Proliferation> {
 public:
  ProliferationOperation(std::shared_ptr<const Proliferation> proliferation, std::uint64_t every,
                         std::uint64_t since)
      : EveryOperation(std::move(proliferation), every, since, "proliferation") {}
  void apply(Simulation& sim) override;
  // Cells born and dead since the operation was made.
  std::uint64_t births() const { return births_; }
  std::uint64_t deaths() const { return deaths_; }

 private:
  std::uint64_t births_ = 0, deaths_ = 0;
};

}  // namespace invasim
