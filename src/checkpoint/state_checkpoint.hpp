#pragma once
// Checkpoint sections of the simulation state (docs/output_formats.md, "Checkpoint
// sections"): the whole System, exactly (every double bit-for-bit), and the state of the
// tether force and of the barostat wall. Each function writes or reads sections named
// "<prefix>.<field>", so a full checkpoint is composed of several of them (system, forces,
// integrator, observers) in one CheckpointWriter. It sits above integrate, forces and io
// (it needs the tether force and the pressure wall), so that io includes neither.
#include <string>

#include "checkpoint/checkpoint_file.hpp"
#include "forces/tether_force.hpp"
#include "integrate/dynamics.hpp"
#include "state/system.hpp"

namespace invasim {

// Box (corners, periodicity, version), seed, step, time, every Sites array, the distinct mesh
// topologies and every body (topology index, first site, reference areas and volume, outer
// volume).
void write_system(CheckpointWriter& out, const System& sys, const std::string& prefix = "system");

// Rebuilds the System written by write_system: equal to it in every stored field, bit for bit,
// box version included; bodies with identical topologies share one MeshTopology. Sections
// missing or inconsistent with each other are an IoError naming the checkpoint and section.
// Neighbour lists and integrators built for another System must be invalidated by the caller
// (a fresh VerletList / Dynamics rebuilds on first use anyway).
System read_system(const CheckpointReader& in, const std::string& prefix = "system");

// Tether stiffness and every tether (bodies, rest length and image), in order.
void write_tethers(CheckpointWriter& out, const TetherForce& tethers,
                   const std::string& prefix = "tethers");
// Restores stiffness and tethers into `tethers`, which must hold no tether yet; the tethers
// are validated against sys (body indices).
void read_tethers(const CheckpointReader& in, const System& sys, TetherForce& tethers,
                  const std::string& prefix = "tethers");

// The barostat wall's scalars: pressure, mass, gamma, velocity and last force.
void write_pressure_wall(CheckpointWriter& out, const PressureWall& wall,
                         const std::string& prefix = "pressure_wall");
// Restores those scalars; wall.walls (the WallForce link) is left as it is.
void read_pressure_wall(const CheckpointReader& in, PressureWall& wall,
                        const std::string& prefix = "pressure_wall");

}  // namespace invasim
