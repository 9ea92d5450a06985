#include "core/idle_tasks.hpp"

#include <omp.h>

#include <algorithm>

namespace invasim {

void IdleTasks::post(std::size_t n, std::function<void(std::size_t)> run) {
  finish();
  if (n == 0) return;
  run_ = std::move(run);
  next_.store(0, std::memory_order_relaxed);
  done_.store(0, std::memory_order_relaxed);
  total_.store(n, std::memory_order_release);
}

bool IdleTasks::run_one() {
  const std::size_t n = total_.load(std::memory_order_acquire);
  if (n == 0 || next_.load(std::memory_order_relaxed) >= n) return false;
  const std::size_t i = next_.fetch_add(1, std::memory_order_acq_rel);
  if (i >= n) return false;
  run_(i);
  done_.fetch_add(1, std::memory_order_acq_rel);
  return true;
}

void IdleTasks::finish() {
  const std::size_t n = total_.load(std::memory_order_acquire);
  if (n == 0) return;
  const std::size_t left = n - std::min(n, next_.load(std::memory_order_relaxed));
  // Many tasks left (the step ran on one thread): all threads take them, as the owner's own
  // loop would have.
#pragma omp parallel if (left >= 8 && omp_get_max_threads() > 1 && !omp_in_parallel())
  while (run_one()) {
  }
  while (done_.load(std::memory_order_acquire) < n) {  // (tasks still running elsewhere)
  }
  total_.store(0, std::memory_order_release);
  run_ = nullptr;
}

IdleTasks& idle_tasks() {
  static IdleTasks tasks;
  return tasks;
}

}  // namespace invasim
