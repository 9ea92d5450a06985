#include "core/wait_policy.hpp"

#include <unistd.h>

#include <cstdlib>

namespace invasim {

void use_passive_wait_policy_by_default(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv("OMP_WAIT_POLICY");  // exec failed: keep running with the runtime's default
}

}  // namespace invasim
