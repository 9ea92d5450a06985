#pragma once
// The objects a protocol checkpoint holds (bind_checkpoint.cpp): the System, the Dynamics,
// the tethers, a correlator, the contacts, read from a keyword table {system =, dynamics =,
// tethers =, correlator =, contacts =} and written into one checkpoint. Shared by
// invasim.save_checkpoint and the checkpoint writer of a Simulation (bind_simulation.cpp).
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "checkpoint/protocol_checkpoint.hpp"
#include "lua/engine_types.hpp"
#include "measure/time_correlator.hpp"

namespace invasim::lua {

struct CheckpointParts {
  std::shared_ptr<SystemHandle> sim;
  std::shared_ptr<DynamicsHandle> dyn;
  std::shared_ptr<Tethers> tethers;
  std::shared_ptr<TimeCorrelator> correlator;
  std::shared_ptr<Contacts> contacts;
};

// Reads the keys system (required when need_system), dynamics (only with need_system),
// tethers, correlator and contacts of kw; with the system, checks them (check_checkpoint_parts).
CheckpointParts read_checkpoint_parts(Kwargs& kw, bool need_system = true);

// Refuses contacts that are not a force of the parts' System (a caller that sets the System
// itself, as sim:checkpoint does, calls it then).
void check_checkpoint_parts(const CheckpointParts& p);

// Writes the parts' sections, the protocol's `extra` string and the run's identity.
void write_checkpoint_parts(CheckpointWriter& w, const CheckpointParts& p, std::string_view extra,
                            const std::optional<std::string>& run_id,
                            const std::optional<std::string>& run_parameters);

// The correlator of a Correlator userdata at `index` (sharing its ownership), or nullptr
// (bind_correlator.cpp).
std::shared_ptr<TimeCorrelator> shared_correlator(lua_State* L, int index);

}  // namespace invasim::lua
