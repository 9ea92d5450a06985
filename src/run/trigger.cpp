#include "run/trigger.hpp"

#include <algorithm>

#include "core/errors.hpp"

namespace invasim {

Trigger Trigger::every(std::uint64_t period, std::uint64_t phase) {
  if (period == 0) throw InputError("trigger: every = 0 steps; the period must be >= 1");
  if (phase >= period)
    throw InputError("trigger: phase = " + std::to_string(phase) + " must be in [0, " +
                     std::to_string(period) + ") for every = " + std::to_string(period));
  Trigger t;
  t.period_ = period;
  t.phase_ = phase;
  return t;
}

Trigger Trigger::at(std::vector<std::uint64_t> steps) {
  Trigger t;
  std::sort(steps.begin(), steps.end());
  steps.erase(std::unique(steps.begin(), steps.end()), steps.end());
  t.steps_ = std::move(steps);
  return t;
}

Trigger Trigger::at_end() {
  Trigger t;
  t.at_end_ = true;
  return t;
}

Trigger Trigger::on_stop() {
  Trigger t;
  t.on_stop_ = true;
  return t;
}

Trigger& Trigger::operator|=(const Trigger& other) {
  if (other.period_ != 0) {
    if (period_ != 0 && (period_ != other.period_ || phase_ != other.phase_))
      throw InputError("trigger: two different periods cannot be combined");
    period_ = other.period_;
    phase_ = other.phase_;
  }
  std::vector<std::uint64_t> steps = steps_;
  steps.insert(steps.end(), other.steps_.begin(), other.steps_.end());
  steps_ = at(std::move(steps)).steps_;
  at_end_ = at_end_ || other.at_end_;
  on_stop_ = on_stop_ || other.on_stop_;
  return *this;
}

bool Trigger::due(std::uint64_t step) const {
  if (period_ != 0 && step % period_ == phase_) return true;
  return std::binary_search(steps_.begin(), steps_.end(), step);
}

std::optional<std::uint64_t> Trigger::next_after(std::uint64_t step) const {
  std::optional<std::uint64_t> next;
  if (period_ != 0) {
    // The smallest s > step with s % period == phase.
    const std::uint64_t base = step - step % period_ + phase_;
    next = base > step ? base : base + period_;
  }
  const auto it = std::upper_bound(steps_.begin(), steps_.end(), step);
  if (it != steps_.end() && (!next || *it < *next)) next = *it;
  return next;
}

std::string Trigger::describe() const {
  std::vector<std::string> parts;
  if (period_ != 0)
    parts.push_back("every " + std::to_string(period_) + " steps" +
                    (phase_ ? " (phase " + std::to_string(phase_) + ")" : ""));
  if (!steps_.empty()) {
    std::string s = steps_.size() == 1 ? "at step " : "at steps ";
    for (std::size_t k = 0; k < steps_.size(); ++k)
      s += (k ? ", " : "") + std::to_string(steps_[k]);
    parts.push_back(s);
  }
  if (at_end_) parts.push_back("at the end");
  if (on_stop_) parts.push_back("on stop");
  if (parts.empty()) return "never";
  std::string text = parts[0];
  for (std::size_t k = 1; k < parts.size(); ++k) text += " or " + parts[k];
  return text;
}

}  // namespace invasim
