#pragma once
// Fault-injection hooks for the reliability tests (docs/reliability.md), off unless
// their environment variable is set. They act on checkpoint writes (files ending in ".ckpt"),
// counted in this process from 1:
//   INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE=N  the N-th write stops halfway through its
//       temporary file, prints "test hook: paused inside the write of <path>" to stderr and
//       sleeps (a test SIGKILLs the process there), then finishes normally;
//   INVASIM_TEST_FAIL_CHECKPOINT_WRITE=N      the N-th write fails halfway with ENOSPC, as on
//       a full disk.
#include <filesystem>

namespace invasim {

enum class WriteFault { kNone, kPause, kNoSpace };

// The fault to inject into this write of `path` (counts the checkpoint writes).
WriteFault checkpoint_write_fault(const std::filesystem::path& path);

// Announces the pause on stderr and sleeps up to an hour.
void pause_inside_write(const std::filesystem::path& path);

}  // namespace invasim
