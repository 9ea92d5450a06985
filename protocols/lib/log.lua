-- Plain stage messages on stdout, prefixed by the stage name and flushed at once (so that
-- logs interleave correctly with the progress lines on stderr).
local M = {}
local tee_file = nil

-- Also append every message to `path` (the run's log.txt), flushed line by line.
function M.tee(path)
  if tee_file then tee_file:close() end
  tee_file = assert(io.open(path, "a"))
end

function M.say(stage, fmt, ...)
  local line = stage .. ": " .. string.format(fmt, ...) .. "\n"
  io.stdout:write(line)
  io.stdout:flush()
  if tee_file then
    tee_file:write(line)
    tee_file:flush()
  end
end

-- A message for log.txt only (e.g. each checkpoint written: on stdout it would break the
-- progress line of a terminal).
function M.note(stage, fmt, ...)
  if tee_file then
    tee_file:write(stage .. ": " .. string.format(fmt, ...) .. "\n")
    tee_file:flush()
  end
end

-- "70 x 70 x 70" from a {Lx, Ly, Lz} list.
function M.box(lengths)
  return string.format("%.4g x %.4g x %.4g", lengths[1], lengths[2], lengths[3])
end

return M
