#pragma once
// A protocol's checkpoint (docs/output_formats.md, "Checkpoint sections"): the System, and
// where the protocol has them the Dynamics, the tethers and a correlator, with the protocol's
// own string ("extra") and the identity of the run that wrote it ("run.id",
// "run.parameters", which --resume compares with the run it continues). invasim's Lua
// functions save_checkpoint and load_checkpoint and the checkpoints a Simulation writes are
// this one composition.
#include <optional>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "forces/contact_force.hpp"
#include "forces/tether_force.hpp"
#include "integrate/dynamics.hpp"
#include "measure/time_correlator.hpp"
#include "state/system.hpp"

namespace invasim {

// The objects of one checkpoint; every one but the System may be absent. The contacts are
// the run's own where a protocol changes their parameters while it runs (a continued run
// takes the checkpoint's); a start taken from another run (--from) leaves them out, so that
// its own parameters hold.
struct ProtocolObjects {
  System* system = nullptr;
  Dynamics* dynamics = nullptr;
  TetherForce* tethers = nullptr;
  TimeCorrelator* correlator = nullptr;
  ContactForce* contacts = nullptr;
};

// The run that writes a checkpoint, and the protocol's own string.
struct ProtocolRecord {
  std::string extra;
  std::optional<std::string> run_id, run_parameters;
};

// Writes every present object's sections and the record.
void write_protocol_checkpoint(CheckpointWriter& out, const ProtocolObjects& objects,
                               const ProtocolRecord& record);

// Restores every present object from the checkpoint read from `path` and returns its
// `extra`. The System must have been built the same way (the same numbers of sites and
// bodies: groups, methods and forces index its sites), else an InputError naming both; a
// given seed replaces the stored one. Caches of the System's forces and the Dynamics'
// preparation are the caller's (the Dynamics reads its sections only).
std::string read_protocol_checkpoint(const CheckpointReader& in, const std::string& path,
                                     const ProtocolObjects& objects,
                                     std::optional<std::uint64_t> seed);

// The run that wrote a checkpoint: its "run.id" and "run.parameters" where stored.
ProtocolRecord checkpoint_run(const CheckpointReader& in);

}  // namespace invasim
