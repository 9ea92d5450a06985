#pragma once
// Fault injection for the reliability tests (docs/reliability.md), off unless its
// environment variable is set: INVASIM_TEST_NAN_AT_COMPRESSION_STEP=K makes site 0's position
// NaN right after the box is scaled for compression step K, so that a test can see the
// blow-up guard stop the compression's FIRE. INVASIM_TEST_PAUSE_AT_COMPRESSION_STEP=K makes
// the process wait at the same point of step K until SIGINT/SIGTERM arrives (at most 120 s),
// so that a test stops a compression in progress however fast the compression is; the
// numbers are not touched. INVASIM_TEST_PAUSE_IN_STOPPABLE_MINIMIZE=1 waits likewise at the start
// of every fire:minimize{stop_on_signal = true} (the protocol's final FIRE of the compression).
// INVASIM_TEST_PAUSE_IN_RESCALE_FIRE=K makes invasim.rescale print
// "test hook: paused in the rescale's FIRE before iteration K" to stderr and wait likewise
// before its FIRE's iteration K, so that a test signals a FIRE known to be running.
#include <cstddef>
#include <cstdint>

#include "state/system.hpp"

namespace invasim {

void inject_nan_at_compression_step(System& sys, std::size_t step);
void pause_at_compression_step(std::size_t step);
void pause_in_stoppable_minimize();
// `iteration`: the number of FIRE iterations done (the stop function is polled before each).
void pause_in_rescale_fire(std::uint64_t iteration);

}  // namespace invasim
