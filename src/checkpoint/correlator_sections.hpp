#pragma once
// Checkpoint sections of a TimeCorrelator's accumulators (dynamics_sections.hpp explains the
// scheme): <p>.samples, .last_time, .velocity, .orientation, .position, .origins, .sums.
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "measure/time_correlator.hpp"

namespace invasim {

void write_correlator(CheckpointWriter& out, const TimeCorrelator& correlator,
                      const std::string& prefix = "correlator");
// The accumulators as stored (read_protocol_checkpoint reads every part before it restores any).
CorrelatorState read_correlator_state(const CheckpointReader& in,
                                      const std::string& prefix = "correlator");
// Restores the accumulators (InputError if their sizes do not fit this correlator).
void read_correlator(const CheckpointReader& in, TimeCorrelator& correlator,
                     const std::string& prefix = "correlator");

}  // namespace invasim
