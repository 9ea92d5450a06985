-- A run's identity: the FNV-1a 64 hash (invasim.hash) of the text
--   protocol <resolved path of the protocol>
--   from <resolved path of the --from run directory>      (only with --from)
--   from_checkpoint <FNV-1a 64 of its compressed.ckpt>    (only with --from: the source's
--                                                          contents, not just its path)
--   key=value                                             (every resolved parameter, sorted)
-- with floats in their shortest round-trip form. params.json (run_id), resume.txt and every
-- checkpoint the run writes (sections run.id and run.parameters, which hold this text) carry
-- it; `invasim run --resume` refuses a checkpoint whose identity is not the run's.
local iv = require("invasim")

local M = {}

-- A parameter value as text: floats in the shortest %g form that reads back to the same
-- double, everything else with tostring.
function M.format_value(v)
  if v == 0 and math.type(v) == "float" then v = 0.0 end  -- -0.0 is the same value as 0.0
  if math.type(v) == "float" and v == v and v ~= math.huge and v ~= -math.huge then
    for digits = 1, 17 do
      local text = string.format("%." .. digits .. "g", v)
      if tonumber(text) == v then return text end
    end
  end
  return tostring(v)
end

-- A parameter value as params.json records it: infinities as the text "inf" or "-inf" (JSON
-- has no number for them; null would read as a parameter not set), everything else as is.
function M.json_value(v)
  if v == math.huge or v == -math.huge then return tostring(v) end
  return v
end

-- The parameters as sorted key=value lines (the --set syntax of resume.txt).
function M.parameter_lines(p)
  local names = {}
  for k in pairs(p) do names[#names + 1] = k end
  table.sort(names)
  local lines = {}
  for i, k in ipairs(names) do lines[i] = k .. "=" .. M.format_value(p[k]) end
  return lines
end

-- The identity of the running protocol with resolved parameters p:
-- { id = 16 hex digits, text = the hashed text, protocol = resolved path of the protocol
--   (what params.json and resume.txt record), from = resolved --from or nil,
--   from_checkpoint = content hash of the --from source's compressed.ckpt (nil if missing),
--   lines = the parameter lines }.
function M.of(p)
  local from = iv.from and iv.resolve_path(iv.from) or nil
  local protocol = iv.resolve_path(iv.script)
  local head = { "protocol " .. protocol }
  local from_checkpoint
  if from then
    from_checkpoint = M.source_hash(from)
    head[#head + 1] = "from " .. from
    head[#head + 1] = "from_checkpoint " .. (from_checkpoint or "missing")
  end
  local lines = M.parameter_lines(p)
  local text = table.concat(head, "\n") .. "\n" .. table.concat(lines, "\n") .. "\n"
  return { id = iv.hash(text), text = text, protocol = protocol, from = from,
           from_checkpoint = from_checkpoint, lines = lines }
end

-- The Lua modules the protocol has loaded from files (the lib/ stages, observers, ...), as
-- { {name =, path =, hash = FNV-1a 64 of the file}, ... } sorted by name: resume.txt records
-- them so that a resume refuses stage code edited since the run started (a series half
-- written by the old code and half by the new).
function M.module_hashes()
  local out = {}
  for name in pairs(package.loaded) do
    local path = type(name) == "string" and package.searchpath(name, package.path)
    if path then out[#out + 1] = { name = name, path = path, hash = iv.hash_file(path) } end
  end
  table.sort(out, function(a, b) return a.name < b.name end)
  return out
end

-- The compressed tissue of the run directory `from` (what --from starts from).
function M.source_path(from) return from .. "/checkpoint/compressed.ckpt" end

-- The content hash (FNV-1a 64 of the bytes) of the --from source's compressed.ckpt, or nil
-- if there is no such file.
function M.source_hash(from)
  local path = M.source_path(from)
  if not iv.exists(path) then return nil end
  return iv.hash_file(path)
end

-- The entries of an identity text: protocol, --from and each parameter.
local function entries(text)
  local t = {}
  for line in (text or ""):gmatch("[^\n]+") do
    local key, value = line:match("^(protocol) (.*)$")
    if not key then key, value = line:match("^(from) (.*)$") end
    if key == "from" then key = "--from" end
    if not key and line:match("^from_checkpoint ") then
      key, value = "the content hash of the --from source", line:match("^from_checkpoint (.*)$")
    end
    if not key then key, value = line:match("^([^=]+)=(.*)$") end
    if key then t[key] = value end
  end
  return t
end

-- What differs between two identity texts, e.g. "P = 0.0013 in the checkpoint, 0.002 in this
-- run"; an empty list if nothing can be told.
function M.differences(a_text, b_text, a_name, b_name)
  local a, b = entries(a_text), entries(b_text)
  local keys, seen = {}, {}
  for _, t in ipairs{ a, b } do
    for k in pairs(t) do
      if not seen[k] then seen[k] = true; keys[#keys + 1] = k end
    end
  end
  table.sort(keys)
  local out = {}
  for _, k in ipairs(keys) do
    if a[k] ~= b[k] then
      out[#out + 1] = string.format("%s = %s in %s, %s in %s", k, a[k] or "(not set)", a_name,
                                    b[k] or "(not set)", b_name)
    end
  end
  return out
end

return M
