-- A path holding a NUL byte is refused by every function that takes one, naming the problem:
-- the system call would stop at the NUL, at another path (remove_path("victim\0/x") would
-- delete victim). Prints "nul_paths: passed" when every one refused and victim survived.
local iv = require("invasim")
local victim = iv.out_dir .. "/victim"
iv.make_dirs(victim)
iv.write_file(victim .. "/kept.txt", "kept\n")
local bad = victim .. "\0/not/this"
local sys = iv.System{ box = { 10, 10, 10 } }
sys:place{ cells = { n = 4, x = { 1, 5 } } }
local dyn = iv.Dynamics{ dt = 0.01 }
local sim = iv.Simulation{ system = sys, dynamics = dyn }
local calls = {
  remove_path = function() return iv.remove_path(bad) end,
  write_file = function() return iv.write_file(bad, "x") end,
  make_dirs = function() return iv.make_dirs(bad) end,
  exists = function() return iv.exists(bad) end,
  resolve_path = function() return iv.resolve_path(bad) end,
  hash_file = function() return iv.hash_file(bad) end,
  lock_run_dir = function() return iv.lock_run_dir(bad) end,
  record_run_lock = function() return iv.record_run_lock(bad) end,
  remove_temporaries = function() return iv.remove_temporaries(bad) end,
  save_checkpoint = function() return iv.save_checkpoint(bad, { system = sys }) end,
  load_checkpoint = function() return iv.load_checkpoint(bad, { system = sys }) end,
  read_json = function() return iv.read_json(bad) end,
  Snapshots = function() return iv.Snapshots{ dir = bad } end,
  checkpoint = function() return sim:checkpoint{ path = bad, every = 1 } end,
}
local names = {}
for name in pairs(calls) do names[#names + 1] = name end
table.sort(names)
for _, name in ipairs(names) do
  local ok, err = pcall(calls[name])
  assert(not ok, name .. " accepted a path with a NUL byte")
  assert(tostring(err):find("NUL byte", 1, true), name .. ": refused for another reason: " .. tostring(err))
  assert(iv.exists(victim .. "/kept.txt"), name .. " removed the victim")
end
print("nul_paths: " .. #names .. " functions refused; passed")
