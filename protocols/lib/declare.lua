-- Protocol parameters declared by reference: a parameter that sets one engine field
-- (invasim.Contacts' beta) or one stage keyword (production's checkpoint_every) takes that
-- field's type, range, unit and help from its one declaration, and states only what the
-- protocol changes: its default (the paper's beta = 1e-2) and, where the protocol gives the
-- field a narrower meaning, a note added to the help. The result is an iv.params{} entry.
--
--   local declare = require("lib.declare")
--   iv.params{ beta = declare.engine("Contacts", "beta", 1e-2),
--              checkpoint_every = declare.keyword(production.keys, "checkpoint_every", 10000) }
local iv = require("invasim")

local M = {}

local function fail(fmt, ...) error(string.format(fmt, ...), 3) end

-- A declaration in the one form of iv.params{} and iv.keywords (docs/lua.md): the default
-- first, then type, range, unit, help and choices.
local function entry(default, type_name, range, unit, help, choices, note)
  local d = { default, type = type_name, range = range, choices = choices,
              help = note and (help .. " (" .. note .. ")") or help }
  if unit and unit ~= "" and unit ~= "1" then d.unit = unit end
  return d
end

-- Field `key` of invasim.<path> ("Active", or "Dynamics.pressure_wall" for a method's keys)
-- and its default (`default`, else the engine's); `who` names the caller in errors.
local function engine_field(who, path, key, default)
  local t = iv
  for part in tostring(path):gmatch("[^.]+") do t = type(t) == "table" and rawget(t, part) or nil end
  if type(t) ~= "table" or not rawget(t, "fields") then
    fail("%s: invasim.%s is not an engine type with fields", who, tostring(path))
  end
  for _, f in ipairs(t.fields) do
    if f.name == key then
      if default == nil then default = f.default end
      if default == nil then
        fail("%s: invasim.%s's key '%s' has no default; give the protocol's", who, path, key)
      end
      return f, default
    end
  end
  fail("%s: invasim.%s has no key '%s'", who, path, tostring(key))
end

-- The parameter that sets field `key` of the engine type invasim.<path> (its `fields` list):
-- `default` replaces the engine's default (nil: the engine's), `note` says what the field is
-- in this protocol ("of the cancer cells"). A field that also takes a Ramp is a number here.
function M.engine(path, key, default, note)
  local f, d = engine_field("declare.engine", path, key, default)
  local t = f.type == "number or Ramp" and "number" or f.type
  return entry(d, t, f.range, f.unit, f.help, f.choices, note)
end

-- The same field as a stage keyword, for a stage that passes it on to the engine; `type_name`
-- narrows the engine's type ("number" where the engine also takes a Ramp but the stage does
-- not).
function M.engine_keyword(path, key, default, type_name)
  local f, d = engine_field("declare.engine_keyword", path, key, default)
  local t = type_name or (f.type == "number or Ramp" and "number|Ramp" or f.type)
  return entry(d, t, f.range, f.unit, f.help, f.choices)
end

-- The parameter that sets keyword `key` of a stage, from the stage's keyword spec; `default`
-- replaces the stage's default (nil: the stage's).
function M.keyword(spec, key, default, note)
  local s = spec[key]
  if type(s) ~= "table" or not s.help then
    fail("declare.keyword: the stage declares no key '%s' with its help", tostring(key))
  end
  local t = s.type or math.type(s[1]) or type(s[1])  -- the stage's type, named or of its default
  if default == nil then default = s[1] end
  return entry(default, t, s.range, s.unit, s.help, s.choices, note)
end

return M
