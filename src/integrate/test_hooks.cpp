#include "integrate/test_hooks.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace invasim {

namespace {
std::atomic<std::uint64_t> team_steps{0};

void print_team_steps() {
  std::fprintf(stderr, "test hook: %llu steps ran in parallel teams\n",
               static_cast<unsigned long long>(team_steps.load()));
}
}  // namespace

bool team_steps_forced() {
  static const bool forced = [] {
    const char* on = std::getenv("INVASIM_TEST_TEAM_STEPS");
    if (on == nullptr || std::string_view(on) != "1") return false;
    std::atexit(print_team_steps);
    return true;
  }();
  return forced;
}

void count_team_steps(std::uint64_t n) {
  if (team_steps_forced()) team_steps += n;
}

}  // namespace invasim
