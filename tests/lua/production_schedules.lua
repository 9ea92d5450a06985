-- Test: the production stage's samplers each run on their own schedule (an iv.Simulation,
-- src/run/): with every = 300, snapshot_every = 700 and checkpoint_every = 500 (none a
-- multiple of another), series rows, snapshot frames and checkpoints come at exactly the
-- steps of the System that are multiples of their own period.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local protocol = require("lib.protocol")
local p = iv.params(protocol.merge{})
local out = require("lib.run_dir").open(p)
protocol.validate(p)
local tissue = protocol.prepare(p)
local first = tissue.sys:step()
local result = protocol.produce(tissue, p, out)
local last = tissue.sys:step()
assert(last == first + p.steps, "production ran " .. (last - first) .. " steps")

local function multiples(period, lo, hi)   -- steps s in (lo, hi] with s % period == 0
  local t = {}
  for s = lo + 1, hi do if s % period == 0 then t[#t + 1] = s end end
  return t
end
local function same(a, b, what)
  assert(#a == #b, string.format("%s: %d entries, expected %d", what, #a, #b))
  for i = 1, #a do
    assert(a[i] == b[i], string.format("%s: entry %d is step %s, expected %s", what, i, a[i], b[i]))
  end
  return #a
end

local rows = {}
for i, row in ipairs(result.series.rows) do rows[i] = row.step end
local n_rows = same(rows, multiples(p.every, first, last), "series rows")

local frames = {}
for line in assert(io.open(out .. "/snapshots/adipocytes.pvd")):lines() do
  local step = line:match('file="adipocytes_(%d+)%.vtp"')
  if step then frames[#frames + 1] = tonumber(step) end
end
local expected_frames = multiples(p.snapshot_every, first, last)
table.insert(expected_frames, 1, first)  -- the frame of the start (lib.protocol.produce)
local n_frames = same(frames, expected_frames, "snapshot frames")

local checkpoints = {}
for line in assert(io.open(out .. "/log.txt")):lines() do
  local step = line:match("^production: checkpoint of step (%d+) written")
  if step then checkpoints[#checkpoints + 1] = tonumber(step) end
end
local n_checkpoints = same(checkpoints, multiples(p.checkpoint_every, first, last), "checkpoints")
assert(n_checkpoints > 0 and n_frames > 1 and n_rows > 0, "the schedules must fire")
print(string.format("production_schedules: ok (%d rows, %d frames, %d checkpoints at their own steps)",
                    n_rows, n_frames, n_checkpoints))
