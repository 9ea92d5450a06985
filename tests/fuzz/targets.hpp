#pragma once
// The four fuzz targets: the checkpoint reader (with the System, tethers,
// correlator and protocol-state sections it holds), the VTK snapshot readers (.vtp, .pvd),
// the --set value parser and the Lua keyword layer. Each runs one input in-process; an
// exception of the project's error types (InputError and its IoError, SimulationError, a Lua
// error raised from them) is the expected answer to bad input, anything else is a finding.
#include <functional>
#include <string>
#include <vector>

namespace invasim::fuzz {

struct Target {
  std::string name;
  // Seed inputs, written by the project's own writers from a small real System (and, for the
  // keyword layer, from the engine's field tables).
  std::vector<std::string> seeds;
  // Tokens of the format, inserted by the mutator.
  std::vector<std::string> dictionary;
  // Repairs a mutated input so that it gets past the outer checks (the checkpoint's length
  // field and CRC) most of the time; may be empty.
  std::function<void(std::string&)> fixup;
  // Runs one input; returns normally or throws a project error for well-handled input.
  std::function<void(const std::string&)> run;
};

// The target called `name` (checkpoint, vtk, set, keywords); throws std::invalid_argument.
Target make_target(const std::string& name);

}  // namespace invasim::fuzz
