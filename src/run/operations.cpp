#include "run/operations.hpp"

#include <algorithm>

#include "core/errors.hpp"
#include "core/stop_request.hpp"
#include "run/simulation.hpp"

namespace invasim {

CorrelatorSampler::CorrelatorSampler(std::shared_ptr<TimeCorrelator> correlator)
    : correlator_(std::move(correlator)) {
  if (!correlator_) throw InputError("correlator sampler: no correlator given");
}

void CorrelatorSampler::apply(Simulation& sim) {
  correlator_->sample(sim.system());
}

void CorrelatorSampler::sites_changed(Simulation& sim, const std::vector<int>& new_index) {
  correlator_->sites_changed(new_index, sim.system().site_epoch());
}

template <typename T>
double EveryOperation<T>::elapsed(Simulation& sim) const {
  const std::uint64_t step = sim.system().step;
  const std::uint64_t steps = step > since_ ? std::min(every_, step - since_) : 0;
  return double(steps) * sim.dynamics().dt();
}
template class EveryOperation<Lipolysis>;
template class EveryOperation<Proliferation>;

void LipolysisOperation::apply(Simulation& sim) {
  object_->apply(sim.system(), elapsed(sim));
}

void ProliferationOperation::apply(Simulation& sim) {
  const SiteChange change = object_->apply(sim.system(), elapsed(sim));
  births_ += change.born.size();
  deaths_ += std::uint64_t(change.deaths);
  if (change.empty()) return;
  sim.dynamics().sites_changed(change);
  for (const auto& scheduled : sim.operations())
    scheduled.operation->sites_changed(sim, change.new_index);
  for (const auto& term : sim.forces().terms()) term->invalidate_caches();
  sim.dynamics().prepare(sim.system(), sim.forces());
}

SnapshotOperation::SnapshotOperation(std::shared_ptr<SnapshotWriter> writer)
    : writer_(std::move(writer)) {
  if (!writer_) throw InputError("snapshot writer: no SnapshotWriter given");
}

void SnapshotOperation::apply(Simulation& sim) {
  writer_->write(sim.system());
}

CheckpointOperation::CheckpointOperation(std::filesystem::path path, ComposeFn compose,
                                         WrittenFn written)
    : path_(std::move(path)), compose_(std::move(compose)), written_(std::move(written)) {
  if (path_.empty()) throw InputError("checkpoint writer: empty path");
  if (!compose_) throw InputError("checkpoint writer: nothing to write");
}

void CheckpointOperation::apply(Simulation& sim) {
  const StopPathWork writing;  // a stop request meanwhile waits for this checkpoint
  CheckpointWriter w;
  compose_(w);
  w.write(path_);
  if (written_) written_(sim.system().step);
}

}  // namespace invasim
