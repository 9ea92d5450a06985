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
  files.mkdir(dir .. "/checkpoint")
  if require("lib.resume").start(dir) then
    log.tee(dir .. "/log.txt")
    log.say("run", "resuming the run in %s from its checkpoint", dir)
    return dir
  end
  local params = {}
  for k, v in pairs(p) do params[k] = v end
  -- resume.txt: what `invasim run --resume DIR` needs to start the same protocol again (the
  -- protocol path, then one key=value line per parameter, in --set syntax).
  local lines = { iv.script }
  local names = {}
  for k in pairs(params) do names[#names + 1] = k end
  table.sort(names)
  for _, k in ipairs(names) do
    local v = params[k]
    if math.type(v) == "float" then v = string.format("%.17g", v) end
    lines[#lines + 1] = k .. "=" .. tostring(v)
  end
  files.write(dir .. "/resume.txt", table.concat(lines, "\n") .. "\n")
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
