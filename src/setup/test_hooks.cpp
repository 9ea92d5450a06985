#include "setup/test_hooks.hpp"

#include <cstdlib>
#include <limits>

namespace invasim {

void inject_nan_at_compression_step(System& sys, std::size_t step) {
  static const char* at = std::getenv("INVASIM_TEST_NAN_AT_COMPRESSION_STEP");
  if (at == nullptr || sys.n_sites() == 0) return;
  if (std::strtoull(at, nullptr, 10) != step) return;
  sys.sites().pos[0].x() = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace invasim
