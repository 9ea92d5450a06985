#pragma once
// A sweep specification: a Lua file (protocols/sweeps/*.lua) that returns a table
//   { protocol = "../invasion.lua",              -- relative to the spec file
//     set = { key = value, ... },                -- fixed parameters
//     product = { key = { v1, v2, ... }, ... },  -- every combination of these lists
//     zip = { { key1 = {...}, key2 = {...} } },  -- lists that move together (equal lengths)
//     seeds = { 1, 2, 3 },                       -- replicates (the parameter `seed`)
//     prep = { set = { ... } },                  -- optional shared preparation run
//     tiny = { set = { ... }, take = 2 } }       -- the CI size (`sweep init --tiny`)
// checked against the parameters the protocol declares (its invasim.params{...} table, read
// the way `invasim params` reads it): an unknown key, an undeclared parameter, a value of the
// wrong type or outside its range is an InputError naming "spec.lua:LINE: key", before
// anything is written. docs/sweeps.md describes the format.
#include <string>
#include <utility>
#include <vector>

#include "core/params.hpp"
#include "sweep/python_json.hpp"

namespace invasim::sweep {

// One axis: a parameter and its values.
using Axis = std::pair<std::string, std::vector<Json>>;

struct SweepSpec {
  std::string path;             // the spec file
  std::string protocol;         // absolute path of the protocol
  std::vector<Param> declared;  // the protocol's parameters
  Json fixed = Json::object();  // set = {...}
  std::vector<Axis> product;    // product = {...} (sorted by name), then seeds
  std::vector<std::vector<Axis>> zips;
  bool has_prep = false;
  Json prep_set = Json::object();  // the preparation's parameters: fixed, then prep.set
  Json prep_own = Json::object();  // prep.set alone (what an override of `set` leaves alone)
  bool has_tiny = false;           // tiny = { set = {...}, take = N }
  Json tiny_set = Json::object();  // the tiny size's parameters (checked like `set`)
  int tiny_take = 2;               // values kept per axis at the tiny size (seeds: 1)

  // The state points: fixed parameters plus one value of every axis (the product of the
  // product axes and zip groups), in a fixed order.
  std::vector<Json> points() const;
  // How many points() makes, counted without making them (the product of the axes' and zip
  // groups' lengths; SIZE_MAX if that overflows).
  std::size_t point_count() const;
  // The count as its factors, e.g. "kT: 100 x f0: 100 x seed: 3".
  std::string point_count_factors() const;
};

// Loads and checks SPEC.lua; InputError naming the file, line and key on any problem.
SweepSpec load_spec(const std::string& path);

// The declared parameter `name` of a protocol's declarations, or nullptr.
const Param* find_param(const std::vector<Param>& declared, const std::string& name);

// The protocol's parameters, read by running it in `invasim params` mode.
std::vector<Param> protocol_params(const std::string& protocol);

// A state-point value as `--set key=VALUE` text for the protocol (floats round-trip).
std::string set_text(const Json& value);

// A parameter's value as a state-point value (an integer stays an integer).
Json to_json(const ParamValue& value);

}  // namespace invasim::sweep
