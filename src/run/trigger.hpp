#pragma once
// When a scheduled operation of a Simulation runs (run/simulation.hpp), in the manner of
// HOOMD-blue's triggers: every N steps of the System's step counter (optionally shifted by a
// phase), at given steps, at the end of a run, when a stop request ends a run, or any
// combination of these. Triggers are checked after a step, at the step count it reached:
// the state a run starts from is never sampled.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace invasim {

class Trigger {
 public:
  // Due at the steps s with s % period == phase (period >= 1, phase < period).
  static Trigger every(std::uint64_t period, std::uint64_t phase = 0);
  // Due at each of the given steps (any order, duplicates allowed).
  static Trigger at(std::vector<std::uint64_t> steps);
  // Due after the last step of a run that was not stopped early.
  static Trigger at_end();
  // Due when a stop request (SIGINT / SIGTERM) ends a run, at the step where it stopped.
  static Trigger on_stop();

  // The union with another trigger's conditions.
  Trigger& operator|=(const Trigger& other);
  friend Trigger operator|(Trigger a, const Trigger& b) { return a |= b; }

  // Whether the periodic or step conditions hold at `step`.
  bool due(std::uint64_t step) const;
  // The first step after `step` at which due() holds (nullopt if none).
  std::optional<std::uint64_t> next_after(std::uint64_t step) const;
  // The period of the periodic condition (0: none), and whether it is the only condition.
  std::uint64_t period() const { return period_; }
  bool only_periodic() const { return period_ > 0 && steps_.empty() && !at_end_ && !on_stop_; }
  bool fires_at_end() const { return at_end_; }
  bool fires_on_stop() const { return on_stop_; }
  // "every 300 steps", "at steps 5, 9", "at the end", "on stop", joined with " or ".
  std::string describe() const;

 private:
  std::uint64_t period_ = 0, phase_ = 0;  // period 0: no periodic condition
  std::vector<std::uint64_t> steps_;      // sorted, unique
  bool at_end_ = false, on_stop_ = false;
};

}  // namespace invasim
