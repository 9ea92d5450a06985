#pragma once
// Fault injection for the reliability tests (issue 14, docs/reliability.md), off unless its
// environment variable is set: INVASIM_TEST_NAN_AT_COMPRESSION_STEP=K makes site 0's position
// NaN right after the box is scaled for compression step K, so that a test can see the
// blow-up guard stop the compression's FIRE.
#include <cstddef>

#include "state/system.hpp"

namespace invasim {

void inject_nan_at_compression_step(System& sys, std::size_t step);

}  // namespace invasim
