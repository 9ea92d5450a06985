-- What `invasim run --resume DIR` trusts, and what it checks before it continues a run
-- (docs/reliability.md, "Run directories: locks, sources and what a resume trusts").
-- DIR/resume.txt is the run's description: the resumed run follows its protocol, --from and
-- parameters. Everything else must agree with it, or the resume is refused with what differs:
--   - the --from source: its compressed.ckpt must have the content hash recorded at the start;
--   - the protocol script: its content hash must be the one recorded at the start;
--   - params.json: its parameters, run_id, from, protocol and recorded hashes;
--   - resume.txt's own "# run_id=" line: the identity its lines give;
--   - the checkpoint: its identity (lib.resume.check, after these checks).
-- A different invasim version or git revision than params.json records is a warning (in
-- log.txt and on stderr), not a refusal: the checkpoint format is versioned and checked on
-- load, and continuing a long run with a corrected binary must stay possible.
local iv = require("invasim")
local run_identity = require("lib.run_identity")

local M = {}

-- The "# key=value" records of DIR/resume.txt (run_id, protocol_hash, from_checkpoint), and
-- its "# module NAME=HASH" records as t.modules (NAME -> HASH).
function M.records(dir)
  local t = { modules = {} }
  local f = io.open(dir .. "/resume.txt", "r")
  if not f then return t end
  for line in f:lines() do
    local key, value = line:match("^# ([%w_]+)=(.*)$")
    if key then t[key] = value end
    local name, hash = line:match("^# module ([^=]+)=(%x+)$")
    if name then t.modules[name] = hash end
  end
  f:close()
  return t
end

-- Whether two values read from different files are the same (numbers by value, so that an
-- integral float read back from JSON as an integer is equal; tables entry by entry).
local function same(a, b)
  if type(a) == "number" and type(b) == "number" then return a == b or (a ~= a and b ~= b) end
  if type(a) == "table" and type(b) == "table" then
    for k, v in pairs(a) do if not same(v, b[k]) then return false end end
    for k in pairs(b) do if a[k] == nil then return false end end
    return true
  end
  return a == b
end

local function shown(v)
  if v == nil then return "(not set)" end
  if type(v) == "table" then return (iv.json_encode(v, { indent = 0 }):gsub("\n$", "")) end
  return run_identity.format_value(v)
end

-- What differs between params.json (`recorded`) and what resume.txt gives (identity, p, its
-- records), as "P = 5 in params.json, 0.0013 in resume.txt" entries.
local function params_json_differences(recorded, identity, p, records)
  local out = {}
  local function compare(name, in_json, in_resume)
    if not same(in_json, in_resume) then
      out[#out + 1] = string.format("%s = %s in params.json, %s in resume.txt", name, shown(in_json),
                                    shown(in_resume))
    end
  end
  compare("protocol", recorded.protocol, iv.script)
  compare("run_id", recorded.run_id, identity.id)
  compare("from", recorded.from, identity.from)
  compare("from_checkpoint", recorded.from_checkpoint, records.from_checkpoint)
  compare("protocol_hash", recorded.protocol_hash, records.protocol_hash)
  local parameters = type(recorded.parameters) == "table" and recorded.parameters or {}
  local names, seen = {}, {}
  for k in pairs(parameters) do if not seen[k] then seen[k] = true; names[#names + 1] = k end end
  for k in pairs(p) do if not seen[k] then seen[k] = true; names[#names + 1] = k end end
  table.sort(names)
  for _, k in ipairs(names) do compare(k, parameters[k], run_identity.json_value(p[k])) end
  return out
end

-- The way out that every refusal names last.
local ANEW = "or start the run anew in that directory with --overwrite"

-- Raises the refusal of `--resume dir` with the formatted reason.
local function refuse(dir, fmt, ...)
  error(string.format("--resume %s: " .. fmt, dir, ...), 0)
end

-- Checks the sources of the run in `dir` against what resume.txt recorded at its start: the
-- --from source's and the protocol's contents (before the checkpoint's identity is compared:
-- a changed source also changes the identity, and this says why). Raises an error naming what
-- changed and the ways out. `records`: M.records(dir).
function M.verify_sources(dir, identity, records)
  local resume_txt = dir .. "/resume.txt"
  if identity.from then
    local source = run_identity.source_path(identity.from)
    if not records.from_checkpoint then
      refuse(dir, "%s records no content hash of the --from source %s (written by an older invasim), " ..
             "so it cannot be told whether the source is still the tissue this run started from; %s",
             resume_txt, source, ANEW)
    end
    if records.from_checkpoint ~= identity.from_checkpoint then
      refuse(dir, "the --from source changed: when this run started, %s had the content hash %s " ..
             "(recorded in %s); it now %s. Continuing would put this run on another tissue than " ..
             "the one it started from; restore that file, %s", source, records.from_checkpoint,
             resume_txt, identity.from_checkpoint and "has " .. identity.from_checkpoint ..
             " (replaced by another run's, or " .. identity.from .. " was run again)" or
             "is missing", ANEW)
    end
  end
  local protocol_hash = iv.hash_file(iv.script)
  if records.protocol_hash and records.protocol_hash ~= protocol_hash then
    refuse(dir, "the protocol %s changed since this run started (content hash %s recorded in %s, %s " ..
           "now): the resumed run would follow other stages than the ones that wrote its files " ..
           "and checkpoint; restore the script (e.g. from version control), %s", iv.script,
           records.protocol_hash, resume_txt, protocol_hash, ANEW)
  end
  local names = {}
  for name in pairs(records.modules or {}) do names[#names + 1] = name end
  table.sort(names)
  for _, name in ipairs(names) do
    local path = package.searchpath(name, package.path)
    local now = path and iv.hash_file(path) or nil
    if now ~= records.modules[name] then
      refuse(dir, "the module %s (%s) changed since this run started (content hash %s recorded " ..
             "in %s, %s now): the resumed run would write its series and checkpoints with other " ..
             "code than the part already written; restore it (e.g. from version control), %s",
             name, path or "not found", records.modules[name], resume_txt, now or "missing", ANEW)
    end
  end
end

-- Checks params.json and resume.txt's own run id against the identity resume.txt gives
-- (lib.run_identity.of of the resolved parameters p); raises an error naming what differs and
-- the ways out. Returns the list of warnings (a different binary, unchecked records) for the
-- log. `records`: M.records(dir).
function M.verify_records(dir, identity, p, records)
  local resume_txt = dir .. "/resume.txt"
  local params_json = dir .. "/params.json"
  if not iv.exists(params_json) then
    refuse(dir, "%s is missing: the run's record of its parameters is gone; %s", params_json, ANEW)
  end
  local recorded = iv.read_json(params_json)
  if type(recorded) ~= "table" then recorded = {} end
  local diff = params_json_differences(recorded, identity, p, records)
  if #diff > 0 then
    refuse(dir, "%s does not agree with %s, which this resume follows: %s. params.json describes the " ..
           "run's results; it was edited or comes from another run. Restore it, %s", params_json,
           resume_txt, table.concat(diff, "; "), ANEW)
  end
  if records.run_id and records.run_id ~= identity.id then
    refuse(dir, "%s records run %s, but its protocol, --from and parameters make run %s: the file " ..
           "was edited; restore it, %s", resume_txt, records.run_id, identity.id, ANEW)
  end
  local warnings = {}
  if not records.protocol_hash then
    warnings[#warnings + 1] = string.format("%s records no content hash of the protocol " ..
                                            "(written by an older invasim): %s is not checked",
                                            resume_txt, iv.script)
  end
  if recorded.invasim_version ~= iv.version or recorded.git_revision ~= iv.git_revision then
    warnings[#warnings + 1] = string.format(
        "this run was started by invasim %s (%s) and is continued by invasim %s (%s): the " ..
        "checkpoint is checked on loading, but the continuation is not guaranteed to be bit for " ..
        "bit what the first binary would have computed", tostring(recorded.invasim_version),
        tostring(recorded.git_revision), iv.version, iv.git_revision)
  end
  return warnings
end

return M
