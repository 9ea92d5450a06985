-- Files of a run directory: whole files written atomically (temp file + rename, through the
-- engine's invasim.write_file) so that a killed run never leaves a half-written file, and
-- appended ones (log.txt, series.csv) whose failed writes are reported.
local iv = require("invasim")

local M = {}

function M.write(path, text) iv.write_file(path, text) end

function M.mkdir(path) iv.make_dirs(path) end

-- Writes the parts to an open file and flushes it (the appended logs and tables of a run:
-- log.txt, series.csv); returns true, or nil and the error of the write or the flush (a full
-- disk), for the caller to name its file.
function M.write_flushed(file, ...)
  local ok, err = file:write(...)
  if ok then ok, err = file:flush() end
  return ok, err
end

return M
