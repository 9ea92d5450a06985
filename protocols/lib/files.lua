-- Files of a run directory, written atomically (temp file + rename, through the engine's
-- invasim.write_file) so that a killed run never leaves a half-written file.
local iv = require("invasim")

local M = {}

function M.write(path, text) iv.write_file(path, text) end

function M.mkdir(path) iv.make_dirs(path) end

return M
