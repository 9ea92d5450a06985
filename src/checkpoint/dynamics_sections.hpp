#pragma once
// Checkpoint sections of the integrator (docs/output_formats.md, "Checkpoint sections"), one
// function pair per object in the manner of LAMMPS's write_restart / read_restart per style:
// each object writes its state under its own name prefix, and reads it back by name.
//   <p>.from, <p>.to, <p>.steps [, <p>.start]   a Ramp (absent: no ramp)
//   <p>.gamma, .kT, .f0, .tau_p, .sites, .kT_ramp.*, .f0_ramp.*   a Method
//   <p>.dt, <p>.methods, <p>.method1.* ... , <p>.pressure_wall.*  a Dynamics
// Readers restore into objects built the same way (same methods on groups of the same size,
// a pressure wall if and only if the checkpoint has one) and name the mismatch otherwise.
#include <optional>
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/ramp.hpp"

namespace invasim {

void write_ramp(CheckpointWriter& out, const std::optional<Ramp>& ramp, const std::string& prefix);
std::optional<Ramp> read_ramp(const CheckpointReader& in, const std::string& prefix);

void write_method(CheckpointWriter& out, const Method& method, const std::string& prefix);
void read_method(const CheckpointReader& in, Method& method, const std::string& prefix);

void write_dynamics(CheckpointWriter& out, const Dynamics& dynamics,
                    const std::string& prefix = "dynamics");
// Checks that the sections fit `dynamics` (as many methods, on groups of the same size, and a
// pressure wall if and only if the checkpoint has one), naming the mismatch; changes nothing.
void check_dynamics(const CheckpointReader& in, const Dynamics& dynamics,
                    const std::string& prefix = "dynamics");
// Restores dt, every method and the pressure wall (its WallForce link is left as it is),
// after check_dynamics.
void read_dynamics(const CheckpointReader& in, Dynamics& dynamics,
                   const std::string& prefix = "dynamics");

}  // namespace invasim
