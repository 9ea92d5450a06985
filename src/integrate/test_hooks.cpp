#include "integrate/test_hooks.hpp"

#include <cstdlib>
#include <string_view>

namespace invasim {

bool team_steps_forced() {
  static const bool forced = [] {
    const char* on = std::getenv("INVASIM_TEST_TEAM_STEPS");
    return on != nullptr && std::string_view(on) == "1";
  }();
  return forced;
}

}  // namespace invasim
