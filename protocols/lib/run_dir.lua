-- The run directory: created at the start of a protocol, it receives params.json
-- (every resolved parameter, the seed, the run's identity, the program version and git
-- revision), resume.txt (what --resume needs), log.txt (a copy of the stage messages), the
-- observers' series.csv, summary.json, correlations.csv, shapes.csv, snapshots/ and
-- checkpoint/. A new run refuses a directory that holds another run unless --overwrite is
-- given, which deletes that run's files first: no stale file of an earlier run can
-- be picked up.
local iv = require("invasim")
local files = require("lib.files")
local log = require("lib.log")
local resume = require("lib.resume")
local run_identity = require("lib.run_identity")

local M = {}

-- The files and directories a run writes (what --overwrite deletes), and those that show
-- that a directory holds a run.
M.RUN_FILES = { "params.json", "resume.txt", "log.txt", "series.csv", "summary.json",
                "correlations.csv", "shapes.csv", "checkpoint", "snapshots", "plots" }
local MARKS = { "params.json", "resume.txt", "checkpoint/state.ckpt", "checkpoint/compressed.ckpt",
                "checkpoint/compressing.ckpt" }

-- The run id recorded in dir/resume.txt, or nil.
local function recorded_id(dir)
  local f = io.open(dir .. "/resume.txt", "r")
  if not f then return nil end
  local text = f:read("a")
  f:close()
  return text:match("\n# run_id=(%x+)")
end

-- A new run in dir: refused if dir holds a run, unless --overwrite (then its files go).
-- Returns the list of files removed.
local function claim(dir, identity)
  local found = {}
  for _, f in ipairs(MARKS) do
    if iv.exists(dir .. "/" .. f) then found[#found + 1] = f end
  end
  if #found == 0 then return {} end
  if not iv.overwrite then
    local old = recorded_id(dir)
    error(string.format("--out %s already holds a run%s (%s): refusing to start another run " ..
                        "(run %s) there, whose files would mix with that run's. Continue that " ..
                        "run with: invasim run --resume %s; or choose another --out; or add " ..
                        "--overwrite to delete its files and start anew", dir,
                        old and " (run " .. old .. ")" or "", table.concat(found, ", "),
                        identity.id, dir), 0)
  end
  if identity.from and identity.from == iv.resolve_path(dir) then
    error(string.format("--from %s and --out %s are the same directory: --overwrite would " ..
                        "delete the compressed tissue this run starts from", iv.from, dir), 0)
  end
  local removed = {}
  for _, f in ipairs(M.RUN_FILES) do
    if iv.exists(dir .. "/" .. f) then
      iv.remove_path(dir .. "/" .. f)
      removed[#removed + 1] = f
    end
  end
  return removed
end

-- Creates the directory and writes params.json; returns the directory path.
function M.open(p, dir)
  dir = dir or iv.out_dir
  local identity = run_identity.of(p)
  resume.set_identity(identity, dir)
  local removed = {}
  if not iv.resume then removed = claim(dir, identity) end
  files.mkdir(dir)
  files.mkdir(dir .. "/checkpoint")
  if resume.start(dir) then
    log.tee(dir .. "/log.txt")
    log.say("run", "resuming the run in %s (run %s) from its checkpoint", dir, identity.id)
    return dir
  end
  -- resume.txt: what `invasim run --resume DIR` needs to start the same protocol again (the
  -- protocol path, the run id for the reader, --from, then one key=value line per parameter,
  -- in --set syntax).
  local lines = { iv.script, "# run_id=" .. identity.id }
  if identity.from then lines[#lines + 1] = "--from=" .. identity.from end
  for _, line in ipairs(identity.lines) do lines[#lines + 1] = line end
  files.write(dir .. "/resume.txt", table.concat(lines, "\n") .. "\n")
  local params = {}
  for k, v in pairs(p) do params[k] = v end
  files.write(dir .. "/params.json", iv.json_encode{
    protocol = iv.script, parameters = params, run_id = identity.id, from = identity.from,
    invasim_version = iv.version, git_revision = iv.git_revision, threads = iv.threads(),
  })
  log.tee(dir .. "/log.txt")
  if #removed > 0 then
    log.say("run", "--overwrite: deleted the previous run's %s in %s", table.concat(removed, ", "), dir)
  end
  log.say("run", "invasim %s (%s), %d threads; run %s; output in %s", iv.version,
          iv.git_revision, iv.threads(), identity.id, dir)
  return dir
end

return M
