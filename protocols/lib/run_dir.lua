-- The run directory (issue 5): created at the start of a protocol, it receives params.json
-- (every resolved parameter, the seed, the program version and git revision), log.txt (a
-- copy of the stage messages), the observers' series.csv, summary.json, correlations.csv,
-- shapes.csv and snapshots/.
local iv = require("invasim")
local files = require("lib.files")
local json = require("lib.json")
local log = require("lib.log")

local M = {}

-- Creates the directory and writes params.json; returns the directory path.
function M.open(p, dir)
  dir = dir or iv.out_dir
  files.mkdir(dir)
  local params = {}
  for k, v in pairs(p) do params[k] = v end
  files.write(dir .. "/params.json", json.encode{
    protocol = iv.script, parameters = params, invasim_version = iv.version,
    git_revision = iv.git_revision, threads = iv.threads(),
  })
  log.tee(dir .. "/log.txt")
  log.say("run", "invasim %s (%s), %d threads; output in %s", iv.version, iv.git_revision,
          iv.threads(), dir)
  return dir
end

return M
