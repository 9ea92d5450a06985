#include "io/test_hooks.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace invasim {

namespace {

// The value of an environment variable as a positive count, or 0.
long env_count(const char* name) {
  const char* text = std::getenv(name);
  return text ? std::strtol(text, nullptr, 10) : 0;
}

std::atomic<long> checkpoint_writes{0};

}  // namespace

WriteFault checkpoint_write_fault(const std::filesystem::path& path) {
  if (path.extension() != ".ckpt") return WriteFault::kNone;
  const long pause_at = env_count("INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE");
  const long fail_at = env_count("INVASIM_TEST_FAIL_CHECKPOINT_WRITE");
  if (pause_at <= 0 && fail_at <= 0) return WriteFault::kNone;
  const long n = ++checkpoint_writes;
  if (n == pause_at) return WriteFault::kPause;
  if (n == fail_at) return WriteFault::kNoSpace;
  return WriteFault::kNone;
}

void pause_inside_write(const std::filesystem::path& path) {
  std::fprintf(stderr, "test hook: paused inside the write of %s\n", path.c_str());
  std::fflush(stderr);
  for (int i = 0; i < 3600; ++i) ::sleep(1);
}

}  // namespace invasim
