-- Restarting a protocol from its run directory (invasim run --resume DIR). The protocol runs
-- again from the top with the same parameters; while a resume is pending, the stages only
-- build their objects (init places, tether connects, quench makes the Dynamics) and skip
-- their work (compression, minimisation, steps), then the production stage loads
-- DIR/checkpoint/state.ckpt into those objects and continues from the saved step, bit for
-- bit. A run stopped by a signal during its compression saved the partly compressed tissue
-- (compressing_path); lib.compress then continues the compression from it. A run stopped
-- after its compression and before its first production checkpoint (in its quench, its
-- rescale) starts again from its compressed tissue (compressed_path: lib.compress loads it
-- instead of compressing), or from the same --from tissue, which resume.txt records. Every
-- checkpoint must be this run's: its identity (lib.run_identity) is compared with the run's
-- before anything runs.
local iv = require("invasim")
local run_identity = require("lib.run_identity")

local M = {}
-- The checkpoint a --resume continues from, until the stage that loads it says it is done:
-- "state" (production), "compressed" or "compressing" (lib.compress); nil: none.
local waiting = nil
local identity = nil  -- this run's identity, set by lib.run_dir

function M.checkpoint_path(out) return out .. "/checkpoint/state.ckpt" end
-- The compressed tissue a run saves for others (invasim run --from DIR).
function M.compressed_path(out) return out .. "/checkpoint/compressed.ckpt" end
-- The partly compressed tissue a run stopped by a signal during compression saves (deleted
-- once the compression is complete).
function M.compressing_path(out) return out .. "/checkpoint/compressing.ckpt" end

local run_dir = nil   -- this run's directory, set with the identity

-- This run's identity (lib.run_identity.of) and directory, set by lib.run_dir.
function M.set_identity(id, dir) identity, run_dir = id, dir end
function M.run_dir() return run_dir end

-- The command that continues this run after a stop: the sweep's own command when the run is
-- a point of a sweep (invasim.continue_command, set by `invasim sweep job`), else
-- `invasim run --resume DIR`.
function M.continue_command(dir)
  return iv.continue_command or ("invasim run --resume " .. (dir or run_dir or "DIR"))
end

-- Where a --resume of this run starts when the run has no production checkpoint yet: from
-- its compressed tissue (its own, or that of --from), else from the beginning.
function M.restart_point()
  local own = run_dir and M.compressed_path(run_dir)
  if own and iv.exists(own) then return "from its compressed tissue (" .. own .. ")" end
  if iv.from then return "from the compressed tissue of " .. iv.from end
  return "from the beginning"
end

-- What a stop before production's first checkpoint tells the user to do: the command that
-- continues the run and where it starts again, or (no run directory) to run it again.
function M.restart_advice()
  if not run_dir then return "run the protocol again from the start" end
  return M.continue_command(run_dir) .. " starts the run again " .. M.restart_point()
end

-- Adds this run's identity to a save_checkpoint keyword table (nothing outside a run
-- directory); returns the table.
function M.stamp(t)
  if identity then t.run_id, t.run_parameters = identity.id, identity.text end
  return t
end

-- Refuses (an error naming both runs and what differs) a checkpoint that this run did not
-- write.
function M.check(out, path)
  local id, text = iv.checkpoint_run(path)
  if id == identity.id then return end
  local restart = string.format("to run %s again from the beginning, delete %s and resume, or " ..
                                "start it anew with --overwrite", out, path)
  if not id then
    error(string.format("--resume %s: refusing the checkpoint %s: it records no run identity " ..
                        "(it was not written by a protocol run), so it cannot be told to belong " ..
                        "to run %s; %s", out, path, identity.id, restart), 0)
  end
  local diff = run_identity.differences(text, identity.text, "the checkpoint", "this run")
  error(string.format("--resume %s: refusing the checkpoint %s: it was written by run %s, not " ..
                      "by the run %s/resume.txt describes (run %s), so continuing it would " ..
                      "simulate other parameters than this run records; %s; %s", out, path, id,
                      out, identity.id, #diff > 0 and "what differs: " .. table.concat(diff, "; ")
                      or "the parameters cannot be told apart", restart), 0)
end

-- Called by lib.run_dir: a resume is pending if --resume was given and a checkpoint of this
-- run exists (a checkpoint of another run is an error): the production checkpoint; else the
-- compressed tissue (lib.compress loads it; a run killed between saving it and deleting
-- compressing_path has both, and the complete one wins); else the checkpoint of a compression
-- stopped by a signal (lib.compress continues it). Returns whether any is pending.
function M.start(out)
  if not iv.resume then return false end
  for _, kind in ipairs({ { "state", M.checkpoint_path }, { "compressed", M.compressed_path },
                          { "compressing", M.compressing_path } }) do
    local path = kind[2](out)
    if iv.exists(path) then
      M.check(out, path)
      waiting = kind[1]
      return true
    end
  end
  return false
end

-- Whether the compression stage should continue from compressing_path (then it calls
-- compression_done once it has loaded it).
function M.compression_pending() return waiting == "compressing" end
function M.compression_done() waiting = nil end

-- Whether the compression stage should load this run's compressed tissue (compressed_path)
-- instead of compressing (then it calls compressed_done once it has loaded it).
function M.compressed_pending() return waiting == "compressed" end
function M.compressed_done() waiting = nil end

-- Whether stages should skip their work (the checkpoint will replace their result).
function M.pending() return waiting == "state" end

-- Called by the production stage once the checkpoint is loaded.
function M.done() waiting = nil end

-- The order of a table's keys in a checkpoint: numbers (ascending) before strings
-- (byte order) before booleans (false first), so that equal data always gives the same bytes
-- (pairs() order depends on the table's history and on string hashing).
local rank = { number = 1, string = 2, boolean = 3 }
local function key_order(a, b)
  local ta, tb = type(a), type(b)
  if ta ~= tb then return (rank[ta] or 4) < (rank[tb] or 4) end
  if ta == "boolean" then return (not a) and b end
  if ta == "number" or ta == "string" then return a < b end
  return false
end

-- Text that serialize writes as it is (see growing_list).
local raw_text = {}

-- serialize for a list that only grows (the production's rows, saved at every checkpoint):
-- returns a function giving, as of the call, text that serialize writes exactly as it would
-- write the list, each element serialized once, when first seen (not at every checkpoint,
-- which made a long run's checkpoints cost O(rows) each). Elements must not change after that.
function M.growing_list(list)
  local parts = {}
  return function()
    for i = #parts + 1, #list do parts[i] = "[" .. M.serialize(i) .. "]=" .. M.serialize(list[i]) end
    return setmetatable({ text = "{" .. table.concat(parts, ",") .. "}" }, raw_text)
  end
end

-- Serialises plain Lua data (tables, numbers, strings, booleans) to a chunk that load()
-- turns back into equal data; floats in hexadecimal, so they come back bit for bit. Keys are
-- written in a fixed order (key_order): equal data gives identical text.
function M.serialize(v)
  local t = type(v)
  if t == "number" then
    if math.type(v) == "integer" then return tostring(v) end
    if v ~= v then return "0/0" elseif v == math.huge then return "math.huge"
    elseif v == -math.huge then return "-math.huge" end
    return string.format("%a", v)
  elseif t == "string" then return string.format("%q", v)
  elseif t == "boolean" or t == "nil" then return tostring(v)
  elseif t == "table" then
    if getmetatable(v) == raw_text then return v.text end
    local keys = {}
    for k, x in pairs(v) do
      if type(x) ~= "function" and type(x) ~= "userdata" then keys[#keys + 1] = k end
    end
    table.sort(keys, key_order)
    local parts = {}
    for i, k in ipairs(keys) do parts[i] = "[" .. M.serialize(k) .. "]=" .. M.serialize(v[k]) end
    return "{" .. table.concat(parts, ",") .. "}"
  end
  error("resume: cannot save a " .. t)
end

-- The data back from serialize's text: parsed as data by invasim.decode_state, never run as
-- code (a crafted checkpoint must not be able to loop or allocate without bound). `origin`
-- names the checkpoint in messages.
function M.deserialize(text, origin)
  return iv.decode_state(text, origin and ("checkpoint " .. origin .. ": section 'extra'") or nil)
end

return M
