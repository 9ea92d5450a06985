-- Test: invasim.keywords, the engine's keyword checker for stages written in Lua. A stage
-- checks its table with it; errors name the stage, the key, the value and the allowed values,
-- at the line of the stage's caller.
local iv = require("invasim")
local checks = 0

local spec = {
  steps = { 100, range = "[0, inf)" },
  dt = { 0.05, range = "(0, inf)", unit = "tau", help = "time step" },
  phi = { type = "number", required = true, range = "(0, 1)" },
  bath = { "langevin", choices = { "langevin", "damped" } },
  label = "stage",                 -- a default value: the type follows it
  progress = true,
  on_sample = { type = "function" },      -- optional, no default
  columns = { type = "table" },
  P = { 1e-3, type = "number|Ramp", range = "[0, inf)" },
  group = { type = "Group" },
  anything = { type = "any" },
}

-- A stage as the protocol library writes one: it checks its keywords first (here in a tail
-- call, which removes the stage's frame: the location is still the stage's caller).
local function stage(opts)
  return iv.keywords("stage", opts, spec)
end

local function expect_error(pattern, line, opts)
  local ok, err = pcall(stage, opts)
  assert(not ok, "expected an error matching: " .. pattern)
  if not tostring(err):find(pattern) then
    error("error message\n  " .. tostring(err) .. "\ndoes not match\n  " .. pattern, 2)
  end
  -- The location is the stage's caller: pcall is a C function, so the caller here is the
  -- line of a wrapper (see below); with a Lua caller it is that caller's line.
  if line then
    local at = tostring(err):match("^keywords.lua:(%d+):")
    assert(at and tonumber(at) == line, "error at line " .. tostring(at) .. ", expected " .. line .. ": " .. err)
  end
  checks = checks + 1
end

-- Defaults fill the absent keys; given values pass through; optional keys stay nil.
local o = stage{ phi = 0.5, steps = 2e3, bath = "damped" }
assert(o.phi == 0.5 and o.steps == 2000 and o.dt == 0.05 and o.bath == "damped" and o.label == "stage")
assert(o.progress == true and o.on_sample == nil and o.columns == nil and o.P == 1e-3)
checks = checks + 1
local ramp = iv.ramp{ from = 0, to = 1e-3, steps = 10 }
o = stage{ phi = 0.1, P = ramp, on_sample = print, columns = { "step" }, anything = ramp }
assert(o.P == ramp and o.on_sample == print and o.columns[1] == "step")
checks = checks + 1

-- Errors, each at the line of the call that gave the bad table.
local function call(opts) local r = stage(opts); return r end  -- not a tail call: keeps its frame
local function expect_at(pattern, opts)
  local line = debug.getinfo(2, "l").currentline
  expect_error(pattern, nil, opts)
  local ok, err = pcall(function() call(opts) end)
  assert(not ok)
  local at = tostring(err):match("^keywords.lua:(%d+):")
  -- `call` is the stage's caller: its line is the one of `return stage(opts)` above.
  assert(at and tonumber(at) == debug.getinfo(call, "S").linedefined, "location " .. tostring(err))
  return line
end
expect_at("stage: unknown key 'stpes' %(did you mean 'steps'%?%); valid keys: P, anything, bath, columns, dt, group, label, on_sample, phi, progress, steps",
          { phi = 0.5, stpes = 10 })
expect_at("stage: key 'dt' must be a number, got string", { phi = 0.5, dt = "small" })
expect_at("stage: key 'dt' = 0 is out of range %(must be > 0%)", { phi = 0.5, dt = 0 })
expect_at("stage: key 'steps' must be an integer, got 2.5", { phi = 0.5, steps = 2.5 })
expect_at("stage: key 'steps' = %-1 is out of range %(must be >= 0%)", { phi = 0.5, steps = -1 })
expect_at("stage: missing required key 'phi' %(a number%)", {})
expect_at("stage: missing required key 'phi' %(a number%); unknown key 'ph' %(did you mean 'phi'%?%)", { ph = 0.5 })
expect_at("stage: key 'phi' = 1 is out of range %(must be in %(0, 1%)%)", { phi = 1 })
expect_at("stage: key 'bath' must be one of: damped, langevin; got 'hot'", { phi = 0.5, bath = "hot" })
expect_at("stage: key 'bath' must be one of: damped, langevin; got 'dampd' %(did you mean 'damped'%?%)", { phi = 0.5, bath = "dampd" })
expect_at("stage: key 'progress' must be a boolean", { phi = 0.5, progress = 1 })
expect_at("stage: key 'on_sample' must be a function, got table", { phi = 0.5, on_sample = {} })
expect_at("stage: key 'P' must be a number or an invasim.ramp{}, got string", { phi = 0.5, P = "high" })
expect_at("stage: key 'P' = %-1 is out of range %(must be >= 0%)", { phi = 0.5, P = -1 })
expect_at("stage: key 'group' must be a Group, got Ramp", { phi = 0.5, group = ramp })
expect_at("stage: unexpected positional value %[1%]", { 0.5, phi = 0.5 })
expect_at("stage: expected a keyword table, as in stage{key = value, ...}; got number", 5)

-- The level argument names a caller further up (a stage wrapped by another function).
local function wrapped(opts) local o = iv.keywords("wrapped", opts, { x = 1 }, 2); return o end
local function outer(opts) local o = wrapped(opts); return o end
local ok, err = pcall(function()
  outer{ y = 1 }  -- this line
end)
local this_line = debug.getinfo(1, "l").currentline - 2
assert(not ok and err:find("^keywords.lua:" .. this_line .. ": wrapped: unknown key 'y'"), err)
checks = checks + 1

-- Mistakes in the spec itself are the stage author's: reported at the stage's own line.
ok, err = pcall(iv.keywords, "bad", {}, { x = { type = "nubmer" } })
assert(not ok and err:find("keywords: bad: key 'x': unknown type 'nubmer' (did you mean 'number'?)", 1, true), err)
ok, err = pcall(iv.keywords, "bad", {}, { x = { 1, type = "number", required = true } })
assert(not ok and err:find("either required or has a default", 1, true), err)
ok, err = pcall(iv.keywords, "bad", {}, { x = { type = "number", rnage = "[0, 1]" } })
assert(not ok and err:find("unknown key 'rnage' (did you mean 'range'?)", 1, true), err)
ok, err = pcall(iv.keywords, "bad", {}, { x = { type = "number", range = "0..1" } })
assert(not ok and err:find("not in interval notation", 1, true), err)
checks = checks + 4

-- The declaration form is iv.params': the first entry is the default, the type follows it
-- unless `type` names it, and a plain default must lie inside its range and choices.
local function spec_error(pattern, entry)
  local ok, err = pcall(iv.keywords, "bad", {}, { x = entry })
  assert(not ok and err:find(pattern, 1, true), "expected '" .. pattern .. "', got " .. tostring(err))
  checks = checks + 1
end
spec_error("keywords: bad: key 'x' must be in (0, inf); its default is 0", { 0.0, range = "(0, inf)" })
spec_error("keywords: bad: key 'x' must be one of a, b; its default is 'c'", { "c", choices = { "a", "b" } })
spec_error("keywords: bad: key 'x' is declared an integer but its default 2.5 is not", { 2.5, type = "integer" })
spec_error("keywords: bad: key 'x' is declared an integer but its default 1e+30 is not", { 1e30, type = "integer" })
spec_error("keywords: bad: key 'x' is declared type = 'string' but its default is a number", { 2.5, type = "string" })
spec_error("keywords: bad: key 'x' is declared type = 'Ramp' but its default is a table", { {}, type = "Ramp" })
spec_error("keywords: bad: key 'x' has neither a type nor a default", { help = "no type" })
spec_error("keywords: bad: key 'x' is a boolean: a range applies to number and integer keys only", { true, range = "[0, 1]" })
spec_error("keywords: bad: key 'x' is a number: choices apply to string keys only", { type = "number", choices = { "a" } })
spec_error("keywords: bad: key 'x': key 'choices' must be a list of strings", { "a", choices = "a" })
-- A table default (not plain) is returned as it is; an integer default makes an integer key.
-- An integer default is kept exactly, beyond 2^53 too (the reader iv.params shares).
assert(iv.keywords("t", {}, { n = { 9007199254740993 } }).n == 9007199254740993)
assert(iv.params{ big = { 9007199254740993, help = "2^53 + 1" } }.big == 9007199254740993)
checks = checks + 2
local list = { 0.9, 1.1 }
o = iv.keywords("t", { n = 3.0 }, { d = { list }, n = 1, s = { "x", choices = { "x", "y" } } })
assert(o.d == list and o.n == 3.0 and o.s == "x")
ok, err = pcall(iv.keywords, "t", { n = 1.5 }, { n = 1 })
assert(not ok and err:find("t: key 'n' must be an integer, got 1.5", 1, true), err)
ok, err = pcall(iv.keywords, "t", { d = 5 }, { d = { list } })
assert(not ok and err:find("t: key 'd' must be a table, got number", 1, true), err)
checks = checks + 3

-- Every plain value is checked by the engine's one checker (Kwargs::declared): a range closed
-- at inf takes math.huge, an open one refuses it; a required key names what it wants.
local function kw_error(pattern, given, decl)
  local ok, err = pcall(iv.keywords, "t", given, { x = decl })
  assert(not ok and err:find(pattern, 1, true), "expected '" .. pattern .. "', got " .. tostring(err))
  checks = checks + 1
end
assert(iv.keywords("t", { x = math.huge }, { x = { 1.0, range = "[0, inf]" } }).x == math.huge)
checks = checks + 1
kw_error("t: key 'x' must be a finite number, got inf", { x = math.huge }, { 1.0, range = "[0, inf)" })
kw_error("t: key 'x' must be a finite number, got -inf", { x = -math.huge }, { 1.0, range = "[0, inf]" })
kw_error("t: missing required key 'x' (true or false)", {}, { type = "boolean", required = true })
kw_error("t: missing required key 'x' (an integer >= 1)", {}, { type = "integer", required = true, range = "[1, inf)" })
kw_error("t: missing required key 'x' (one of: a, b)", {}, { type = "string", required = true, choices = { "a", "b" } })
kw_error("t: key 'x' must be a boolean (true or false), got 5", { x = 5 }, { type = "boolean", required = true })
kw_error("t: key 'x' must be one of: a, b; got 'c'", { x = "c" }, { "a", choices = { "a", "b" } })
kw_error("t: key 'x' must be a number or an invasim.ramp{}, got string", { x = "1" }, { 1.0, type = "number|Ramp" })

print(string.format("keywords: all %d checks passed", checks))
