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
#include "io/snapshot_writer.hpp"
#include "measure/time_correlator.hpp"
#include "run/operation.hpp"

namespace invasim {

// Samples a TimeCorrelator (its interval must be the trigger's period times dt).
class CorrelatorSampler : public Operation {
 public:
  explicit CorrelatorSampler(std::shared_ptr<TimeCorrelator> correlator);
  std::string name() const override { return "correlator sampler"; }
  void apply(Simulation& sim) override;

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
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  ComposeFn compose_;
  WrittenFn written_;
};

// Applies lipolysis to the System every `every` steps (elapsed time every x dt: schedule it
// with Trigger::every(every)). Like a parameter change between two steps, the new reference
// volumes act from the next force evaluation: the step's first half-kick uses the forces
// already computed, as a run restored from a checkpoint written at this step (which stores
// them) does, so both continue bit for bit.
class LipolysisOperation : public Operation {
 public:
  LipolysisOperation(std::shared_ptr<const Lipolysis> lipolysis, std::uint64_t every);
  std::string name() const override { return "lipolysis"; }
  void apply(Simulation& sim) override;

 private:
  std::shared_ptr<const Lipolysis> lipolysis_;
  std::uint64_t every_;
};

// Calls a function (an observer); returning false ends the run at this step boundary.
class FunctionOperation : public Operation {
 public:
  using Fn = std::function<bool(Simulation&)>;
  FunctionOperation(std::string name, Fn fn);
  std::string name() const override { return name_; }
  void apply(Simulation& sim) override;

 private:
  std::string name_;
  Fn fn_;
};

}  // namespace invasim
