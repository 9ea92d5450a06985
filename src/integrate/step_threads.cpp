#include "integrate/step_threads.hpp"

#include <omp.h>

#include <algorithm>

namespace invasim {

void StepThreads::set_mode(Mode mode) {
  mode_ = mode;
  max_threads_ = 0;  // measure afresh
}

void StepThreads::start_measuring() {
  phase_ = Phase::kSerialWindow;
  serial_time_ = team_time_ = 0.0;
  serial_n_ = team_n_ = 0;
}

int StepThreads::begin_step() {
  const int max = omp_get_max_threads();
  if (max != max_threads_) {  // first step, or the thread count changed: start again
    max_threads_ = max;
    decided_ = false;
    hold_windows_ = kMinHold;
    start_measuring();
  }
  if (max_threads_ == 1 || mode_ == Mode::kAll)
    team_now_ = max_threads_ > 1;
  else
    team_now_ = phase_ == Phase::kTeamWindow || (phase_ == Phase::kHold && team_chosen_);
  return team_now_ ? max_threads_ : 1;
}

void StepThreads::choose(bool team) {
  if (decided_ && team == team_chosen_)
    hold_windows_ = std::min(2 * hold_windows_, kMaxHold);
  else
    hold_windows_ = kMinHold;
  team_chosen_ = team;
  decided_ = true;
  phase_ = Phase::kHold;
  hold_left_ = hold_windows_ * window_;
  hold_time_ = 0.0;
  hold_n_ = 0;
}

void StepThreads::end_step(double seconds) {
  ++(team_now_ ? team_steps_ : serial_steps_);
  if (max_threads_ == 1 || mode_ == Mode::kAll) return;
  switch (phase_) {
    case Phase::kSerialWindow:
      serial_time_ += seconds;
      if (++serial_n_ >= kMinWindowSteps && serial_time_ >= kWindowSeconds) {
        window_ = serial_n_;
        if (serial_time_ / double(serial_n_) < kMinTeamStepSeconds)
          choose(false);  // too light for a team
        else
          phase_ = Phase::kTeamWindow;
      }
      break;
    case Phase::kTeamWindow:
      team_time_ += seconds;
      ++team_n_;
      if (team_time_ > serial_time_)  // slower than the whole 1-thread window already
        choose(false);
      else if (team_n_ >= window_)
        choose(team_time_ < kTeamGain * serial_time_);
      break;
    case Phase::kHold:
      // With the team: a window clearly slower than the last 1-thread window (the machine got
      // busier) measures again at once.
      hold_time_ += seconds;
      if (++hold_n_ == window_) {
        if (team_chosen_ &&
            hold_time_ > kRecheckFactor * serial_time_ / double(serial_n_) * double(window_)) {
          start_measuring();
          break;
        }
        hold_time_ = 0.0;
        hold_n_ = 0;
      }
      if (--hold_left_ == 0) start_measuring();
      break;
  }
}

ThreadCountScope::ThreadCountScope(int threads) : saved_(omp_get_max_threads()) {
  if (threads != saved_) omp_set_num_threads(threads);
}

ThreadCountScope::~ThreadCountScope() {
  if (omp_get_max_threads() != saved_) omp_set_num_threads(saved_);
}

MeasuredStep::MeasuredStep(StepThreads& threads)
    : threads_(threads), scope_(threads.begin_step()), start_(std::chrono::steady_clock::now()) {}

MeasuredStep::~MeasuredStep() {
  threads_.end_step(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

}  // namespace invasim
