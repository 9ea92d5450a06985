// Tests of the field tables (lua/fields.hpp): each bound type's declared keys are exactly the
// keys its constructor reads, their defaults are the engine structs' own, and the same table
// drives params(), describe and set{}; and of the one "did you mean" (core/names).
#include <catch2/catch.hpp>
#include <iomanip>
#include <sstream>
#include <string>

#include "core/names.hpp"
#include "core/progress.hpp"
#include "forces/contact_force.hpp"
#include "forces/wall_force.hpp"
#include "integrate/dynamics.hpp"
#include "integrate/fire.hpp"
#include "io/snapshot_writer.hpp"
#include "lua/lua_state.hpp"
#include "measure/time_correlator.hpp"
#include "setup/compression.hpp"

using namespace invasim;
using namespace invasim::lua;

namespace {

// A Lua number literal that reads back as exactly x.
std::string lua_number(double x) {
  std::ostringstream out;
  out << std::setprecision(17) << x;
  return out.str();
}

// `assert(<table>.<key> == <value>, ...)` for one default.
std::string same(const std::string& table, const std::string& key, const std::string& value) {
  return "assert(" + table + "." + key + " == " + value + ", '" + table + "." + key +
         " = ' .. tostring(" + table + "." + key + ") .. ', the engine says " + value + "')\n";
}
std::string same(const std::string& table, const std::string& key, double value) {
  return same(table, key, lua_number(value));
}
std::string same(const std::string& table, const std::string& key, bool value) {
  return same(table, key, std::string(value ? "true" : "false"));
}

}  // namespace

TEST_CASE("did_you_mean: typos and transpositions, not other words", "[lua][names]") {
  const std::vector<std::string> keys = {"box",         "periodic", "seed",
                                         "mean_degree", "drift",    "vertex_gamma"};
  CHECK(did_you_mean("bxo", keys) == " (did you mean 'box'?)");   // a transposition: 1 edit
  CHECK(did_you_mean("sed", keys) == " (did you mean 'seed'?)");  // short: 1 edit allowed
  CHECK(did_you_mean("drfit", keys) == " (did you mean 'drift'?)");
  CHECK(did_you_mean("mean_dgree", keys) == " (did you mean 'mean_degree'?)");
  // Long names allow a third of their length: three edits in a 12-character name.
  CHECK(did_you_mean("vertx_gama_", keys) == " (did you mean 'vertex_gamma'?)");
  CHECK(did_you_mean("xyz", keys).empty());
  CHECK(did_you_mean("temperature", keys).empty());
  CHECK(did_you_mean("seed", {}).empty());
}

TEST_CASE("invasim.X.defaults are the engine structs' own defaults", "[lua][fields]") {
  const ContactParams contact;
  const FireParams fire;
  const MethodParams method;
  const PressureWall wall;
  const TimeCorrelatorParams corr;
  const SnapshotOptions snap;
  const ProgressOptions progress;
  const CompressionParams compression;
  const WallForce walls;
  std::string code = "local iv = require('invasim')\n";
  code += same("iv.Contacts.defaults", "alpha", contact.alpha);
  code += same("iv.Contacts.defaults", "beta", contact.beta);
  code += same("iv.Contacts.defaults", "eps_cc", contact.eps_cc);
  code += same("iv.Contacts.defaults", "eps_cv", contact.eps_cv);
  code += same("iv.Contacts.defaults", "eps_vv", contact.eps_vv);
  code += same("iv.Contacts.defaults", "skin", contact.skin);
  code += same("iv.Walls.defaults", "eps", walls.eps());
  code += same("iv.Walls.defaults", "left", walls.left());
  code += same("iv.Walls.defaults", "right", walls.right());
  for (const char* t : {"iv.Fire.defaults", "iv.compress.defaults", "iv.rescale.defaults"}) {
    code += same(t, "ftol", fire.ftol);
    code += same(t, "dt", fire.dt);
    code += same(t, "dt_max", fire.dt_max);
    code += same(t, "max_steps", static_cast<double>(fire.max_steps));
  }
  code += same("iv.compress.defaults", "step", compression.step);
  code +=
      same("iv.compress.defaults", "max_compressions", static_cast<double>(compression.max_steps));
  for (const char* t : {"iv.Damped.defaults", "iv.Langevin.defaults", "iv.Active.defaults"})
    code += same(t, "gamma", method.gamma);
  code += same("iv.Active.defaults", "kT", method.kT);
  code += same("iv.Dynamics.pressure_wall.defaults", "mass", wall.mass);
  code += same("iv.Dynamics.pressure_wall.defaults", "gamma", wall.gamma);
  code += same("iv.Dynamics.pressure_wall.defaults", "kT", wall.kT);
  code += same("iv.Correlator.defaults", "lags", static_cast<double>(corr.lags));
  code += same("iv.Correlator.defaults", "origin_every", static_cast<double>(corr.origin_every));
  code += same("iv.Correlator.defaults", "k", corr.k);
  code += same("iv.Correlator.defaults", "velocity", corr.velocity);
  code += same("iv.Correlator.defaults", "orientation", corr.orientation);
  code += same("iv.Correlator.defaults", "position", corr.position);
  code += same("iv.Correlator.defaults", "fs_average", std::string("\"isotropic\""));
  code += same("iv.Snapshots.defaults", "cells_xyz", snap.cells_xyz);
  code += same("iv.Snapshots.defaults", "spheres_vtp", snap.spheres_vtp);
  code += same("iv.Snapshots.defaults", "adipocytes_vtp", snap.adipocytes_vtp);
  code += same("iv.Progress.defaults", "total", static_cast<double>(progress.total));
  code += same("iv.Progress.defaults", "start", static_cast<double>(progress.start_step));
  code += same("iv.Progress.defaults", "every_seconds", progress.every_seconds);
  code += same("iv.Progress.defaults", "label", std::string("\"\""));
  // Keys without a default (required) have none in the table.
  code += R"lua(
    assert(iv.Shape.defaults.eps_v == nil and iv.Tethers.defaults.K == nil)
    assert(iv.Langevin.defaults.kT == nil and iv.Active.defaults.f0 == nil)
    assert(iv.compress.defaults.to_phi == nil and iv.Correlator.defaults.interval == nil)
  )lua";
  LuaState state;
  REQUIRE_NOTHROW(state.run_string(code));
}

TEST_CASE("invasim.X.defaults is read-only and X stays a constructor", "[lua][fields]") {
  LuaState state;
  REQUIRE_NOTHROW(state.run_string(R"lua(
    local iv = require("invasim")
    local ok, err = pcall(function() iv.Contacts.defaults.beta = 1 end)
    assert(not ok and err:find("invasim.Contacts.defaults is read-only", 1, true), err)
    ok, err = pcall(function() iv.Contacts.defaults.new_key = 1 end)
    assert(not ok and err:find("read-only", 1, true), err)
    assert(iv.Contacts.defaults.beta == 0)
    -- pairs() walks the defaults
    local n = 0
    for k, v in pairs(iv.Contacts.defaults) do n = n + 1 end
    assert(n == 8, n)  -- alpha, beta, alpha_cv, beta_cv, eps_cc, eps_cv, eps_vv, skin
    -- the constructor is still called as before, and errors keep their form
    assert(tostring(iv.Contacts{ beta = 0.01 }):find("^Contacts%(alpha=0.2, beta=0.01,"))
    ok, err = pcall(iv.Contacts, { bta = 1 })
    assert(not ok and err:find("Contacts: unknown key 'bta' (did you mean 'beta'?)", 1, true), err)
    -- fields: name, type, default, range, unit, help
    local f = iv.Contacts.fields[2]
    assert(f.name == "beta" and f.type == "number" and f.default == 0 and f.range == "[0, inf)")
    assert(f.unit == "1" and f.help:find("cohesion depth") and f.required == false)
    local tau_p = iv.Active.fields[5]
    assert(tau_p.name == "tau_p" and tau_p.required and tau_p.default == nil)
    local fs = iv.Correlator.fields[6]
    assert(fs.name == "fs_average" and fs.choices[1] == "isotropic" and fs.choices[2] == "yz")
  )lua"));
}

TEST_CASE("every key a constructor reads is declared in its field table", "[lua][fields]") {
  LuaState state;
  REQUIRE_NOTHROW(state.run_string(R"lua(
    local iv = require("invasim")
    local sys = iv.System{ box = {20, 14, 14}, seed = 5 }
    sys:place{ cells = { n = 4, diameters = {1.0}, x = {1, 4} } }
    local cells = sys:group("cancer")
    local tethers = sys:add(iv.Tethers{ K = 1 })
    -- The keys the error lists as valid are the keys the reader asked for.
    local function read_keys(fn, ...)
      local ok, err = pcall(fn, ...)
      assert(not ok, "expected an unknown-key error")
      local keys = err:match("valid keys: (.*)$")
      assert(keys, err)
      return keys
    end
    local function declared(fields, extras)
      local names = {}
      for _, f in ipairs(fields) do names[#names + 1] = f.name end
      for _, e in ipairs(extras or {}) do names[#names + 1] = e end
      table.sort(names)
      return table.concat(names, ", ")
    end
    local cases = {
      { iv.Contacts, {} }, { iv.Walls, {} }, { iv.Shape, { eps_v = 1, eps_a = 1 } },
      { iv.Tethers, { K = 1 } }, { iv.Damped, { group = cells } },
      { iv.Langevin, { group = cells, kT = 0 } },
      { iv.Active, { group = cells, f0 = 0, tau_p = 1, randomize = false } },
      { iv.Dynamics, {} }, { iv.Fire, {} }, { iv.Correlator, { group = cells, interval = 1 } },
      { iv.Snapshots, { dir = "unused" } }, { iv.Progress, {} },
      { iv.System, { box = {1, 1, 1} } }, { iv.ramp, { from = 0, to = 1, steps = 1 } },
    }
    for i, c in ipairs(cases) do
      local keys = c[2]
      keys.zz_unknown = 1
      local got = read_keys(c[1], keys)
      assert(got == declared(c[1].fields, c[3]), i .. ": reads " .. got .. "; declares " .. declared(c[1].fields, c[3]))
    end
    local got = read_keys(iv.compress, sys, { to_phi = 0.5, zz = 1 })
    assert(got == declared(iv.compress.fields), got)
    got = read_keys(iv.rescale, sys, { phi_a = 0.5, zz = 1 })
    assert(got == declared(iv.rescale.fields), got)
    local dyn = iv.Dynamics{}
    got = read_keys(dyn.pressure_wall, dyn, { P = 0, zz = 1 })
    assert(got == declared(iv.Dynamics.pressure_wall.fields), got)
    got = read_keys(tethers.connect, tethers, { zz = 1 })
    assert(got == declared(iv.Tethers.connect.fields), got)
  )lua"));
}

TEST_CASE("params(), describe and set{} come from the same table", "[lua][fields]") {
  LuaState state;
  REQUIRE_NOTHROW(state.run_string(R"lua(
    local iv = require("invasim")
    local function state_names(fields)
      local n = {}
      for _, f in ipairs(fields) do if f.state then n[#n + 1] = f.name end end
      table.sort(n)
      return table.concat(n, ",")
    end
    local function keys(t)
      local n = {}
      for k in pairs(t) do n[#n + 1] = k end
      table.sort(n)
      return table.concat(n, ",")
    end
    local sys = iv.System{ box = {20, 14, 14}, seed = 5 }
    sys:place{ cells = { n = 4, diameters = {1.0}, x = {1, 4} } }
    local cells = sys:group("cancer")
    local objects = {
      { iv.Contacts{}, iv.Contacts }, { iv.Walls{ left = false }, iv.Walls },
      { iv.Shape{ eps_v = 2, eps_a = 3 }, iv.Shape }, { iv.Fire{ ftol = 1e-3 }, iv.Fire },
      { iv.Active{ group = cells, f0 = 1, tau_p = math.huge, randomize = false }, iv.Active },
      { iv.Correlator{ group = cells, interval = 0.5, fs_average = "yz" }, iv.Correlator },
    }
    for i, o in ipairs(objects) do
      local p = o[1]:params()
      assert(keys(p) == state_names(o[2].fields), i .. ": params " .. keys(p))
    end
    assert(iv.Walls{ left = false }:params().left == false)
    assert(iv.Correlator{ group = cells, interval = 0.5, fs_average = "yz" }:params().fs_average == "yz")
    assert(iv.Active{ group = cells, f0 = 1, tau_p = math.huge, randomize = false }:params().tau_p == math.huge)
    assert(tostring(iv.Walls{ left = false }) == "Walls(eps=1, left=false, right=true)")
    assert(tostring(iv.Fire{ ftol = 1e-3 }) == "Fire(ftol=0.001, dt=0.05, dt_max=0.5, max_steps=1000000)")
    local c = iv.Contacts{}
    c:set{ beta = 0.01 }
    assert(c:params().beta == 0.01 and c:params().alpha == 0.2)
    local ok, err = pcall(c.set, c, { bta = 1 })
    assert(not ok and err:find("Contacts:set: unknown key 'bta' (did you mean 'beta'?)", 1, true), err)
    local d = iv.Damped{ group = cells }
    ok, err = pcall(d.set, d, { kT = 1 })
    assert(not ok and err:find("Damped:set: unknown key 'kT'", 1, true), err)
  )lua"));
}
