-- Errors whose object is not a string or whose message holds a NUL, failing at_error functions,
-- os.exit, at the top level and in engine callbacks (tests/lua/CMakeLists.txt: one case per --set
-- case=...). Each ends the script with status 1 and a message naming this file and line.
local iv = require("invasim")
local p = iv.params{ case = { "table", help = "which error to raise" } }

local function in_callback(raise)
  local sys = iv.System{ box = { 8, 8, 8 }, periodic = { true, true, true }, seed = 1 }
  sys:place{ cells = { n = 4, x = { 0, 8 } } }
  sys:add(iv.Contacts{})
  local dyn = iv.Dynamics{ dt = 0.01 }
  dyn:add(iv.Langevin{ group = sys:group("cancer"), gamma = 0.5, kT = 0.1 })
  local sim = iv.Simulation{ system = sys, dynamics = dyn }
  sim:observe(raise, { every = 2 })
  sim:run(10)
  print("error_objects: the run went on after its callback failed")
end

local cases = {
  table = function() error({}) end,
  ["nil"] = function() error(nil) end,
  number = function() error(42) end,
  tostring = function()
    error(setmetatable({}, { __tostring = function() return "a custom error object" end }))
  end,
  callback_table = function() in_callback(function() error({ code = 3 }) end) end,
  exit = function() os.exit(0) end,
  exit_in_callback = function() in_callback(function() os.exit(0) end) end,
  nul = function() error("before\0after") end,
  nul_in_callback = function() in_callback(function() error("in\0callback") end) end,
  failing_at_error = function()
    iv.at_error(function() error("the handler failed") end)
    iv.at_error(function(message) print("second handler saw: " .. message) end)
    error("the script failed")
  end,
}
local raise = cases[p.case] or error("unknown case " .. tostring(p.case))
raise()
print("error_objects: the script ended normally")
