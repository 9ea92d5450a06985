-- Test: a bound C++ object carries its type in its userdata, checked on every
-- access, so a script that swaps metatables with debug.setmetatable cannot make a method run
-- on the wrong C++ type. For every pair (A, B) of bound types, an A object is given B's
-- metatable and every method of B is called on it (self = A, and with a B as self and the A as
-- each argument): each call must be a Lua error naming the function, the argument position,
-- the expected and the given type, or succeed on a valid B. Nothing may crash. Also: a FILE*
-- dressed as a bound object, a bound object refused a metatable without invasim's __gc, and
-- collection of swapped objects (each __gc destroys by its own tag).
local iv = require("invasim")

-- One scratch directory for every Snapshots object made here, removed at the end.
local snapshot_dir = os.tmpname()
os.remove(snapshot_dir)

local function make_all()
  local sys = iv.System{ box = { 8, 8, 8 }, periodic = { true, true, true }, seed = 2 }
  sys:place{ cells = { n = 4, x = { 0, 8 } } }
  local contacts = iv.Contacts{}
  sys:add(contacts)
  local cells = sys:group("cancer")
  local dyn = iv.Dynamics{ dt = 0.01 }
  local method = iv.Langevin{ group = cells, gamma = 0.5, kT = 0.1 }
  dyn:add(method)
  return {
    System = sys,
    Group = cells,
    Contacts = contacts,
    Walls = iv.Walls{ eps = 1, left = true, right = true },
    Shape = iv.Shape{ eps_v = 1e3, eps_a = 1 },
    Tethers = iv.Tethers{ K = 1e-2 },
    Method = method,
    Dynamics = dyn,
    Fire = iv.Fire{ max_steps = 3 },
    Ramp = iv.ramp{ from = 0, to = 1, steps = 10 },
    Progress = iv.Progress{ total = 10, live = false, every_seconds = 1e9 },
    Simulation = iv.Simulation{ system = sys, dynamics = dyn },
    Correlator = iv.Correlator{ group = cells, interval = 0.01, lags = 4, origin_every = 1 },
    Snapshots = iv.Snapshots{ dir = snapshot_dir },
  }
end

-- The methods of a bound object: upvalue 1 of its metatable's __index (binding.cpp).
local function methods_of(object)
  local mt = debug.getmetatable(object)
  local _, table_of_methods = debug.getupvalue(mt.__index, 1)
  local names = {}
  for name in pairs(table_of_methods) do names[#names + 1] = name end
  table.sort(names)
  return names
end

local objects = make_all()
local type_names = {}
for name in pairs(objects) do type_names[#type_names + 1] = name end
table.sort(type_names)
assert(#type_names == 14, "bound types: " .. #type_names)

local calls, errors = 0, 0
for _, a in ipairs(type_names) do
  for _, b in ipairs(type_names) do
    if a ~= b then
      local victim = make_all()[a]  -- fresh objects: a call that succeeds changes nothing shared
      local other = make_all()[b]
      local b_meta = debug.getmetatable(other)
      local a_meta = debug.getmetatable(victim)
      debug.setmetatable(victim, b_meta)
      for _, m in ipairs(methods_of(other)) do
        -- self of the wrong type, called as a method
        local ok, err = pcall(function() return victim[m](victim, other) end)
        calls = calls + 1
        assert(not ok, a .. " dressed as " .. b .. ": " .. m .. " ran")
        local want = "bad self for '" .. m .. "' %(" .. b .. " expected, got " .. a .. "%)"
        assert(type(err) == "string" and err:find("^type_tags%.lua:%d+: ") and err:find(want),
               a .. " as " .. b .. ":" .. m .. ": " .. tostring(err))
        errors = errors + 1
        -- the A object as a later argument of a valid B method: an error or a valid call
        for position = 1, 2 do
          local args = { other, other, other }
          args[position + 1] = victim
          local ok2, err2 = pcall(function() return b_meta.__index(other, m)(table.unpack(args)) end)
          calls = calls + 1
          if not ok2 then
            assert(type(err2) == "string" and err2:find("^type_tags%.lua:%d+: "), tostring(err2))
            errors = errors + 1
          end
        end
      end
      -- tostring through the wrong metatable names the real type
      local text = b_meta.__tostring(victim)
      assert(text:find("^" .. a .. " %(with the metatable of"), text)
      debug.setmetatable(victim, a_meta)
    end
  end
end

-- A bound object swapped and collected under another type's metatable: its own __gc runs.
for i = 1, 50 do
  local fresh = make_all()
  debug.setmetatable(fresh.Ramp, debug.getmetatable(fresh.System))
  debug.setmetatable(fresh.System, debug.getmetatable(fresh.Progress))
end
collectgarbage()
collectgarbage()

-- A FILE* given an invasim metatable, and a bound object given the FILE* metatable.
local file_meta = debug.getmetatable(io.stdout)
local f = io.tmpfile()
local progress = iv.Progress{ total = 1, live = false }
debug.setmetatable(f, debug.getmetatable(progress))
local ok, err = pcall(function() return f:update(1) end)
assert(not ok and err:find("bad self for 'update' %(Progress expected, got userdata%)"), tostring(err))
-- A bound object may not lose invasim's __gc (the FILE* metatable, a plain table, nil): its
-- C++ object would never be freed (LeakSanitizer found that leak). The refusal names the type.
local ramp = iv.ramp{ from = 0, to = 1, steps = 10 }
local ramp_meta = debug.getmetatable(ramp)
-- Lua reads __gc raw when it collects, so a metatable that finds invasim's __gc only through
-- its own __index is refused too.
local inherits_gc = setmetatable({}, { __index = { __gc = ramp_meta.__gc } })
assert(inherits_gc.__gc == ramp_meta.__gc and rawget(inherits_gc, "__gc") == nil)
for _, foreign in ipairs({ file_meta, {}, { __gc = function() end }, inherits_gc }) do
  ok, err = pcall(function() debug.setmetatable(ramp, foreign) end)
  assert(not ok and err:find("^type_tags%.lua:%d+: debug%.setmetatable: a bound Ramp must keep an invasim metatable"),
         tostring(err))
  assert(debug.getmetatable(ramp) == ramp_meta, "the refused swap changed the metatable")
end
ok, err = pcall(function() debug.setmetatable(ramp, nil) end)
assert(not ok and err:find("a bound Ramp must keep an invasim metatable"), tostring(err))
assert(ramp:value(5) == 0.5, "the ramp still works after the refused swaps")
-- Other values are untouched by the guard.
local plain = {}
assert(debug.setmetatable(plain, { __index = { answer = 42 } }) == plain and plain.answer == 42)
assert(debug.setmetatable(io.tmpfile(), file_meta))
f, ramp = nil, nil
collectgarbage()

-- The SIGSEGV this guards against: a ramp dressed as a Group given to a method, then run.
local all = make_all()
local disguised = iv.ramp{ from = 0, to = 1, steps = 10 }
debug.setmetatable(disguised, debug.getmetatable(all.Group))
ok, err = pcall(iv.Langevin, { group = disguised, gamma = 1, kT = 0 })
assert(not ok and err:find("Langevin: key 'group' must be a Group .* got Ramp"), tostring(err))
ok, err = pcall(function() return disguised:size() end)
assert(not ok and err:find("bad self for 'size' %(Group expected, got Ramp%)"), tostring(err))
-- Contacts dressed as a System
debug.setmetatable(all.Contacts, debug.getmetatable(all.System))
ok, err = pcall(function() return all.Contacts:positions() end)
assert(not ok and err:find("bad self for 'positions' %(System expected, got Contacts%)"), tostring(err))

-- A Ramp used where a Group is expected, a Contacts where a Walls is.
ok, err = pcall(iv.Langevin, { group = all.Ramp, gamma = 1, kT = 0 })
assert(not ok and err:find("must be a Group .* got Ramp"), tostring(err))
ok, err = pcall(all.Dynamics.pressure_wall, all.Dynamics, { P = 1, walls = all.Contacts })
assert(not ok and err:find("must be a Walls force, got Contacts"), tostring(err))

-- A Simulation finalised (its __gc called through the debug library) by its own observer while
-- it runs: the run holds its own reference, ends its steps, and the object then reads as gone.
do
  local gsys = iv.System{ box = { 6, 6, 6 }, periodic = { true, true, true }, seed = 3 }
  gsys:place{ cells = { n = 8, x = { 0.5, 5.5 } } }
  gsys:add(iv.Contacts{})
  local gdyn = iv.Dynamics{ dt = 0.01 }
  gdyn:add(iv.Langevin{ group = gsys:group("cancer"), gamma = 0.2, kT = 1e-3 })
  local sim = iv.Simulation{ system = gsys, dynamics = gdyn }
  local calls = 0
  sim:observe(function()
    calls = calls + 1
    if calls == 1 then
      debug.getmetatable(sim).__gc(sim)
      gsys, gdyn = nil, nil
      collectgarbage()
      collectgarbage()
    end
  end, { every = 10 })
  local steps = sim:run(100)
  assert(steps == 100 and calls == 10, "a run whose Simulation was finalised: " .. tostring(steps) .. " steps, " .. calls .. " calls")
  ok, err = pcall(function() return sim:run(1) end)
  assert(not ok and err:find("Simulation object is no longer valid"), tostring(err))
end

print(string.format("type_tags: %d types, %d calls on a swapped metatable or a wrong argument, %d errors, no crash",
                    #type_names, calls, errors))
assert(os.execute("rm -rf '" .. snapshot_dir .. "'"))
