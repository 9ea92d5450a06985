-- Test: protocol parameters declared by reference (lib/declare.lua). A parameter that sets an
-- engine field or a stage keyword has that field's range, type and help, with only the
-- protocol's default (and a note) of its own; invasim.Contacts.check applies the contact
-- law's rules (beta < alpha) without building anything, as lib/parameters.lua does before any
-- work.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local declare = require("lib.declare")
local production = require("lib.production")
local parameters = require("lib.parameters")
local checks = 0
local function check(ok, what) assert(ok, what); checks = checks + 1 end

local function field(type_name, key)
  for _, f in ipairs(iv[type_name].fields) do if f.name == key then return f end end
end

-- The common parameters take the engine's declaration; only the defaults differ.
local d = parameters.declarations()
local beta = field("Contacts", "beta")
check(d.beta[1] == 1e-2 and beta.default == 0, "beta: the paper's default over the engine's 0")
check(d.beta.range == beta.range and d.beta.range == "[0, inf)", "beta: the engine's range")
check(d.beta.help:sub(1, #beta.help) == beta.help, "beta: the engine's help")
check(d.alpha[1] == field("Contacts", "alpha").default, "alpha: the engine's default")
check(d.tau_p.range == "[0, inf]" and d.tau_p.range == field("Active", "tau_p").range,
      "tau_p: the engine's range, math.huge included")
check(d.dt[1] == iv.Dynamics.defaults.dt and d.dt.unit == "tau", "dt: the engine's default and unit")
check(d.vertex_gamma.help:find("of the adipocyte vertices", 1, true), "vertex_gamma: the protocol's note")
-- Stage keywords: production's declaration, with the protocols' default.
local ck = production.keys.checkpoint_every
check(d.checkpoint_every[1] == 10000 and ck[1] == 0, "checkpoint_every: 10000 over the stage's 0")
check(d.checkpoint_every.type == "integer" and d.checkpoint_every.help == ck.help and
      d.checkpoint_every.range == ck.range, "checkpoint_every: the stage's type, range and help")
check(d.every[1] == production.keys.every[1] and d.every.range == "[1, inf)", "every: the stage's")

-- declare names what it cannot find.
local function fails(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  check(not ok and tostring(err):find(pattern), "expected an error matching " .. pattern .. ", got " .. tostring(err))
end
fails("invasim.Contacts has no key 'gama'", declare.engine, "Contacts", "gama")
fails("invasim.Nothing is not an engine type with fields", declare.engine, "Nothing", "x")
fails("invasim.Active's key 'f0' has no default; give the protocol's", declare.engine, "Active", "f0")
fails("the stage declares no key 'stpes' with its help", declare.keyword, production.keys, "stpes")

-- The contact law's rules, once (ContactParams::validate), reachable before any work.
check(iv.Contacts.check{ alpha = 0.2, beta = 0.01 } == nil, "valid contact keys")
check(iv.Contacts.check{ alpha = 0.2, beta = 0.3 }:find("^cohesion: beta = 0.3 must be smaller than alpha = 0.2"),
      "beta >= alpha")
check(iv.Contacts.check{ alpha_cv = 0.1, beta_cv = 0.1 }:find("^adhesion: beta_cv = 0.1 must be smaller than alpha_cv = 0.1"),
      "beta_cv >= alpha_cv")
check(iv.Contacts.check{ alpha = -1 }:find("key 'alpha' = %-1 is out of range"), "a range")
check(iv.Contacts.check{ alpah = 1 }:find("unknown key 'alpah'"), "an unknown key")
local decl = parameters.declarations()
decl.beta[1] = 0.3
local ok, err = pcall(parameters.validate, iv.params(decl))
check(not ok and err:find("^cohesion: beta = 0.3 must be smaller than alpha = 0.2 .*%-%-set alpha, beta"),
      "parameters.validate reports the engine's rule with the --set hint: " .. tostring(err))
print("declarations: all " .. checks .. " checks passed")
