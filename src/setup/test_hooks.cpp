#include "setup/test_hooks.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string_view>
#include <thread>

#include "core/stop_request.hpp"

namespace invasim {

void inject_nan_at_compression_step(System& sys, std::size_t step) {
  static const char* at = std::getenv("INVASIM_TEST_NAN_AT_COMPRESSION_STEP");
  if (at == nullptr || sys.n_sites() == 0) return;
  if (std::strtoull(at, nullptr, 10) != step) return;
  sys.sites().pos[0].x() = std::numeric_limits<double>::quiet_NaN();
}

namespace {
// Sleeps until SIGINT/SIGTERM is recorded, at most 120 s.
void wait_for_stop_signal() {
  for (int waited = 0; waited < 24000 && stop_requested() == 0; ++waited)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
}
}  // namespace

void pause_at_compression_step(std::size_t step) {
  static const char* at = std::getenv("INVASIM_TEST_PAUSE_AT_COMPRESSION_STEP");
  if (at != nullptr && std::strtoull(at, nullptr, 10) == step) wait_for_stop_signal();
}

void pause_in_stoppable_minimize() {
  static const char* on = std::getenv("INVASIM_TEST_PAUSE_IN_STOPPABLE_MINIMIZE");
  if (on != nullptr && std::string_view(on) == "1") wait_for_stop_signal();
}

void pause_in_rescale_fire(std::uint64_t iteration) {
  static const char* at = std::getenv("INVASIM_TEST_PAUSE_IN_RESCALE_FIRE");
  if (at == nullptr || std::strtoull(at, nullptr, 10) != iteration) return;
  std::fprintf(stderr, "test hook: paused in the rescale's FIRE before iteration %llu\n",
               static_cast<unsigned long long>(iteration));
  std::fflush(stderr);
  wait_for_stop_signal();
}

}  // namespace invasim
