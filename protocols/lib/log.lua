-- Plain stage messages on stdout, prefixed by the stage name and flushed at once (so that
-- logs interleave correctly with the progress lines on stderr).
-- A failed write to log.txt (a full disk) is an error that stops the run: a log cut
-- mid-line would not say that it is incomplete.
local iv = require("invasim")
local files = require("lib.files")

local M = {}
local tee_file, tee_path = nil, nil

-- Appends a line to log.txt; a failed write or flush raises an error naming the file (and
-- stops the tee, so that reporting that error does not write to it again).
local function append(line)
  if not tee_file then return end
  local ok, err = files.write_flushed(tee_file, line)
  if not ok then
    local path = tee_path
    tee_file:close()
    tee_file, tee_path = nil, nil
    error(string.format("cannot write the run's log %s: %s; the run stops (its log would be " ..
                        "incomplete)", path, err), 0)
  end
end

-- Also append every message to `path` (the run's log.txt), flushed line by line.
function M.tee(path)
  if tee_file then tee_file:close() end
  local f, err = io.open(path, "a")
  if not f then error(string.format("cannot open the run's log %s: %s", path, err), 0) end
  tee_file, tee_path = f, path
end

-- The message that ends a run (an error, a stop by a signal) goes to its log too (nowhere
-- before a tee).
iv.at_error(function(message) append("end: " .. message .. "\n") end)

function M.say(stage, fmt, ...)
  local line = stage .. ": " .. string.format(fmt, ...) .. "\n"
  io.stdout:write(line)
  io.stdout:flush()
  append(line)
end

-- A message for log.txt only (e.g. each checkpoint written: on stdout it would break the
-- progress line of a terminal).
function M.note(stage, fmt, ...)
  if tee_file then append(stage .. ": " .. string.format(fmt, ...) .. "\n") end
end

-- "70 x 70 x 70" from a {Lx, Ly, Lz} list.
function M.box(lengths)
  return string.format("%.4g x %.4g x %.4g", lengths[1], lengths[2], lengths[3])
end

return M
