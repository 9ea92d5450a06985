#include "run/simulation.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/stop_request.hpp"

namespace invasim {

Simulation::Simulation(std::shared_ptr<System> system, std::shared_ptr<ForceField> forces,
                       std::shared_ptr<Dynamics> dynamics)
    : system_(std::move(system)),
      forces_(std::move(forces)),
      dynamics_(std::move(dynamics)),
      stop_check_(&stop_requested) {
  if (!system_ || !forces_ || !dynamics_)
    throw InputError("Simulation: needs a System, a ForceField and a Dynamics");
}

void Simulation::add(std::shared_ptr<Operation> operation, Trigger trigger) {
  if (!operation) throw InputError("Simulation: no operation given");
  if (running_)
    throw InputError("Simulation: the " + operation->name() +
                     " cannot be added while the Simulation runs (from one of its operations); "
                     "add it before the run, or after the run returns");
  for (const auto& s : operations_)
    if (s.operation == operation)
      throw InputError("Simulation: the " + operation->name() + " is already scheduled");
  operations_.push_back({std::move(operation), std::move(trigger)});
}

void Simulation::set_max_chunk(std::uint64_t steps) {
  if (steps == 0) throw InputError("Simulation: max_chunk = 0; it must be >= 1 step");
  max_chunk_ = steps;
}

RunResult Simulation::run(std::uint64_t n) {
  RunResult result;
  stop_requested_ = false;
  const std::uint64_t end = system_->step + n;
  const std::vector<Scheduled>& ops = operations_;  // fixed during the run (add() refuses)
  running_ = true;
  struct NotRunning {
    bool& flag;
    ~NotRunning() { flag = false; }
  } not_running{running_};
  std::vector<char> ran(ops.size());
  while (system_->step < end) {
    const std::uint64_t now = system_->step;
    std::uint64_t next = std::min(end, now + max_chunk_);
    for (const auto& s : ops)
      if (const auto t = s.trigger.next_after(now)) next = std::min(next, *t);
    dynamics_->run(*system_, *forces_, next - now);
    result.steps += next - now;
    const bool last = next == end;
    for (std::size_t k = 0; k < ops.size(); ++k) {
      ran[k] = ops[k].trigger.due(next) || (last && ops[k].trigger.fires_at_end());
      if (ran[k]) ops[k].operation->apply(*this);
    }
    if (progress_) progress_(result.steps, system_->time);
    const int signal = stop_check_ ? stop_check_() : 0;
    if (signal || stop_requested_) {
      result.stopped = !last;
      result.stop_signal = signal;
      if (signal)
        for (std::size_t k = 0; k < ops.size(); ++k)
          if (!ran[k] && ops[k].trigger.fires_on_stop()) ops[k].operation->apply(*this);
      break;
    }
  }
  if (n == 0)  // nothing to step: the at_end operations still see the (unchanged) state
    for (const auto& s : ops)
      if (s.trigger.fires_at_end()) s.operation->apply(*this);
  return result;
}

}  // namespace invasim
