-- Restarting a protocol from its run directory (invasim run --resume DIR). The protocol runs
-- again from the top with the same parameters; while a resume is pending, the stages only
-- build their objects (init places, tether connects, quench makes the Dynamics) and skip
-- their work (compression, minimisation, steps), then the production stage loads
-- DIR/checkpoint/state.ckpt into those objects and continues from the saved step, bit for
-- bit. A run killed before its first checkpoint starts again from the beginning.
local iv = require("invasim")

local M = {}
local pending = false

function M.checkpoint_path(out) return out .. "/checkpoint/state.ckpt" end
-- The compressed tissue a run saves for others (invasim run --from DIR).
function M.compressed_path(out) return out .. "/checkpoint/compressed.ckpt" end

-- Called by lib.run_dir: a resume is pending if --resume was given and a checkpoint exists.
function M.start(out)
  if not iv.resume then return false end
  local f = io.open(M.checkpoint_path(out), "rb")
  if f then f:close(); pending = true end
  return pending
end

-- Whether stages should skip their work (the checkpoint will replace their result).
function M.pending() return pending end

-- Called by the production stage once the checkpoint is loaded.
function M.done() pending = false end

-- Serialises plain Lua data (tables, numbers, strings, booleans) to a chunk that load()
-- turns back into equal data; floats in hexadecimal, so they come back bit for bit.
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
    local parts = {}
    for k, x in pairs(v) do
      if type(x) ~= "function" and type(x) ~= "userdata" then
        parts[#parts + 1] = "[" .. M.serialize(k) .. "]=" .. M.serialize(x)
      end
    end
    return "{" .. table.concat(parts, ",") .. "}"
  end
  error("resume: cannot save a " .. t)
end

function M.deserialize(text)
  local chunk = assert(load("return " .. text, "checkpoint", "t", { math = math }))
  return chunk()
end

return M
