-- The run directory: created at the start of a protocol, it receives params.json
-- (every resolved parameter, the seed, the run's identity, the program version and git
-- revision), resume.txt (what --resume needs), log.txt (a copy of the stage messages), the
-- observers' series.csv, summary.json, correlations.csv, shapes.csv, snapshots/ and
-- checkpoint/. A new run refuses a directory that holds another run unless --overwrite is
-- given, which deletes that run's files first: no stale file of an earlier run can
-- be picked up. A run that stopped before saving anything (refused by a stage's checks,
-- killed before its first checkpoint) is taken over without --overwrite, saying so. The
-- directory is locked (DIR/.lock, invasim.lock_run_dir) before any of its
-- files is written or deleted, for the whole life of the run: a second run into it, new or
-- --resume, is refused while the first runs. A --resume first checks the directory's files
-- against resume.txt (lib.resume_checks). Temporary files of atomic writes that a killed run
-- left behind are removed once the lock is held (no other process writes there then).
local iv = require("invasim")
local files = require("lib.files")
local log = require("lib.log")
local resume = require("lib.resume")
local resume_checks = require("lib.resume_checks")
local run_identity = require("lib.run_identity")

local M = {}

-- The files and directories a run writes (what --overwrite deletes), and those that show
-- that a directory holds a run.
M.RUN_FILES = { "params.json", "resume.txt", "log.txt", "series.csv", "summary.json",
                "correlations.csv", "shapes.csv", "checkpoint", "snapshots", "plots" }
local MARKS = { "params.json", "resume.txt", "checkpoint/state.ckpt", "checkpoint/compressed.ckpt",
                "checkpoint/compressing.ckpt" }

-- What open() writes before the stages run: all that a run which stopped before saving
-- anything leaves (no checkpoint, no results).
local WRITTEN_AT_START = { ["params.json"] = true, ["resume.txt"] = true, ["log.txt"] = true,
                           checkpoint = true }

-- The run id recorded in dir/resume.txt, or nil.
local function recorded_id(dir) return resume_checks.records(dir).run_id end

-- Whether the run in dir saved nothing: no checkpoint and no file beyond WRITTEN_AT_START.
local function saved_nothing(dir)
  for _, f in ipairs(M.RUN_FILES) do
    if not WRITTEN_AT_START[f] and iv.exists(dir .. "/" .. f) then return false end
  end
  for _, f in ipairs(MARKS) do
    if f:find("^checkpoint/") and iv.exists(dir .. "/" .. f) then return false end
  end
  return true
end

-- A new run in dir: refused if dir holds a run that saved something, unless --overwrite
-- (then its files go). Returns the list of files removed and, for a run that saved nothing,
-- its id ("unknown" if resume.txt records none).
local function claim(dir, identity)
  local found = {}
  for _, f in ipairs(MARKS) do
    if iv.exists(dir .. "/" .. f) then found[#found + 1] = f end
  end
  if #found == 0 then return {} end
  local unsaved = not iv.overwrite and saved_nothing(dir) and (recorded_id(dir) or "unknown")
  if not iv.overwrite and not unsaved then
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
  return removed, unsaved
end

-- Takes the lock of dir for the rest of the run, or refuses the run naming its holder.
local function lock(dir)
  local ok, holder = iv.lock_run_dir(dir)
  if ok then return end
  local option = iv.resume and "--resume" or "--out"
  error(string.format("%s %s: the run directory is in use by another invasim run (%s; lock " ..
                      "file %s/.lock): refusing to %s while it runs (the two runs' files would " ..
                      "mix). Wait for that run to end, or stop it (its lock goes with its " ..
                      "process, even after kill -9)%s", option, dir, holder, dir,
                      iv.resume and "continue it" or
                      (iv.overwrite and "delete its files" or "start another run there"),
                      iv.resume and "" or ", or choose another --out"), 0)
end

-- A new run with --from S: S's compressed tissue must be the one of the run S/resume.txt
-- describes (a compressed.ckpt copied from another run would be taken for S's).
local function check_source(identity)
  if not identity.from then return end
  local path = run_identity.source_path(identity.from)
  if not identity.from_checkpoint then
    error(string.format("--from %s: %s does not exist (the directory holds no run that finished " ..
                        "its compression)", iv.from, path), 0)
  end
  local described = recorded_id(identity.from)
  if not described then return end  -- not a protocol's run directory: the hash still holds it
  local id = iv.checkpoint_run(path)
  if id ~= described then
    error(string.format("--from %s: refusing %s: it was written by %s, but %s/resume.txt " ..
                        "describes run %s, so the tissue is not that run's (a compressed.ckpt " ..
                        "copied from another run?); restore it, or run %s again", iv.from, path,
                        id and "run " .. id or "no protocol run", identity.from, described,
                        identity.from), 0)
  end
end

-- Logs the temporary files removed and the warnings of a resume (also on stderr).
local function report(dir, temporaries, warnings)
  if #temporaries > 0 then
    log.say("run", "removed %d temporary file(s) of writes interrupted by a killed run in %s: %s",
            #temporaries, dir, table.concat(temporaries, ", "))
  end
  for _, w in ipairs(warnings) do
    log.say("run", "warning: %s", w)
    io.stderr:write("invasim: warning: ", w, "\n")
  end
end

-- Creates and locks the directory, checks it (a new run: that it holds no other run; a
-- resume: lib.resume_checks) and writes params.json and resume.txt; returns the directory
-- path.
function M.open(p, dir)
  dir = dir or iv.out_dir
  local identity = run_identity.of(p)
  resume.set_identity(identity, dir)
  if not iv.resume then check_source(identity) end
  files.mkdir(dir .. "/checkpoint")  -- an unwritable --out is refused here, naming it
  lock(dir)
  local removed, warnings, records, unsaved = {}, {}, nil, nil
  if iv.resume then
    records = resume_checks.records(dir)
    resume_checks.verify_sources(dir, identity, records)
  else
    removed, unsaved = claim(dir, identity)
  end
  iv.record_run_lock(dir)
  local temporaries = iv.remove_temporaries(dir)
  files.mkdir(dir .. "/checkpoint")
  local continuing = resume.start(dir)  -- refuses a checkpoint of another run
  if iv.resume then warnings = resume_checks.verify_records(dir, identity, p, records) end
  if iv.resume and iv.exists(dir .. "/summary.json") then  -- written last, by a finished run
    log.say("run", "%s holds a finished run (its summary.json is written): nothing to resume", dir)
    iv.stop()
  end
  if continuing then
    log.tee(dir .. "/log.txt")
    log.say("run", "resuming the run in %s (run %s) from its checkpoint; invasim %s (%s), %d threads",
            dir, identity.id, iv.version, iv.git_revision, iv.threads())
    report(dir, temporaries, warnings)
    return dir
  end
  -- params.json, then resume.txt (what `invasim run --resume DIR` needs to start the same
  -- protocol again: the protocol path, the run's records for the checks of lib.resume_checks,
  -- --from, then one key=value line per parameter, in --set syntax). A run killed between the
  -- two writes has no resume.txt and cannot be resumed (it has not started its work).
  local protocol_hash = iv.hash_file(iv.script)
  local params = {}
  for k, v in pairs(p) do params[k] = run_identity.json_value(v) end
  files.write(dir .. "/params.json", iv.json_encode{
    protocol = identity.protocol, protocol_hash = protocol_hash, parameters = params,
    run_id = identity.id, from = identity.from, from_checkpoint = identity.from_checkpoint,
    invasim_version = iv.version, git_revision = iv.git_revision, threads = iv.threads(),
  })
  local lines = { identity.protocol, "# run_id=" .. identity.id, "# protocol_hash=" .. protocol_hash }
  for _, m in ipairs(run_identity.module_hashes()) do
    lines[#lines + 1] = "# module " .. m.name .. "=" .. m.hash
  end
  if identity.from then
    lines[#lines + 1] = "# from_checkpoint=" .. identity.from_checkpoint
    lines[#lines + 1] = "--from=" .. identity.from
  end
  for _, line in ipairs(identity.lines) do lines[#lines + 1] = line end
  files.write(dir .. "/resume.txt", table.concat(lines, "\n") .. "\n")
  log.tee(dir .. "/log.txt")
  if unsaved then
    log.say("run", "replaced run %s in %s, which stopped before saving anything (no checkpoint, " ..
            "no results): deleted its %s", unsaved, dir, table.concat(removed, ", "))
  elseif #removed > 0 then
    log.say("run", "--overwrite: deleted the previous run's %s in %s", table.concat(removed, ", "), dir)
  end
  log.say("run", "invasim %s (%s), %d threads; run %s; output in %s", iv.version,
          iv.git_revision, iv.threads(), identity.id, dir)
  if iv.resume then  -- stopped before its first checkpoint (or killed): nothing to continue from
    log.say("run", "no checkpoint of this run in %s: --resume starts it again %s", dir, resume.restart_point())
  end
  report(dir, temporaries, warnings)
  return dir
end

return M
