-- Keyword-table checking for the stage library, with the same messages as the engine's
-- constructors: an unknown key is an error that lists the valid ones (and suggests the
-- nearest), a wrong type names the key. Errors point at the caller of the stage.
local M = {}

local function sorted_keys(t)
  local keys = {}
  for k in pairs(t) do keys[#keys + 1] = k end
  table.sort(keys)
  return keys
end

-- Levenshtein distance, for "did you mean".
local function distance(a, b)
  local prev = {}
  for j = 0, #b do prev[j] = j end
  for i = 1, #a do
    local cur = { [0] = i }
    for j = 1, #b do
      local cost = a:sub(i, i) == b:sub(j, j) and 0 or 1
      cur[j] = math.min(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost)
    end
    prev = cur
  end
  return prev[#b]
end

local function suggestion(key, valid)
  local best, best_d = nil, math.huge
  for _, v in ipairs(valid) do
    local d = distance(key, v)
    if d < best_d then best, best_d = v, d end
  end
  if best and best_d <= math.max(1, #key // 3) then return " (did you mean '" .. best .. "'?)" end
  return ""
end

-- M.check(stage, given, defaults [, required]) -> options
-- `given` is the user's table (nil = {}), `defaults` maps every valid key to its default
-- (M.REQUIRED for a key without one; M.OPTIONAL for a key whose default is nil). Returns a
-- new table with the defaults filled in. Types must match the default's type (numbers accept
-- integers and floats; an invasim userdata is accepted where the default is M.ANY).
M.REQUIRED = setmetatable({}, { __tostring = function() return "required" end })
M.OPTIONAL = setmetatable({}, { __tostring = function() return "optional" end })
M.ANY = setmetatable({}, { __tostring = function() return "any" end })

function M.check(stage, given, defaults, types)
  given = given or {}
  if type(given) ~= "table" then
    error(stage .. ": expected a keyword table, got " .. type(given), 3)
  end
  local valid = sorted_keys(defaults)
  for k, v in pairs(given) do
    if type(k) ~= "string" then
      error(stage .. ": unexpected positional value [" .. tostring(k) .. "]; write key = value", 3)
    end
    if defaults[k] == nil then
      error(string.format("%s: unknown key '%s'%s; valid keys: %s", stage, k,
                          suggestion(k, valid), table.concat(valid, ", ")), 3)
    end
    local d = defaults[k]
    local want = types and types[k]
    if not want and d ~= M.REQUIRED and d ~= M.OPTIONAL and d ~= M.ANY then want = type(d) end
    if want and type(v) ~= want then
      error(string.format("%s: key '%s' must be a %s, got %s", stage, k, want, type(v)), 3)
    end
  end
  local out = {}
  for k, d in pairs(defaults) do
    local v = given[k]
    if v == nil then
      if d == M.REQUIRED then
        error(string.format("%s: missing required key '%s'", stage, k), 3)
      elseif d ~= M.OPTIONAL and d ~= M.ANY then
        v = d
      end
    end
    out[k] = v
  end
  return out
end

-- Raises "stage: key 'every' = 0 must be >= 1" at the stage's caller if o[key] < lo: for
-- stages called directly (the protocols' parameters are range-checked by iv.params).
function M.at_least(stage, o, key, lo)
  if o[key] < lo then
    error(string.format("%s: key '%s' = %s must be >= %s", stage, key, tostring(o[key]), tostring(lo)), 3)
  end
end

-- Raises a stage error at the stage's caller.
function M.fail(stage, message)
  error(stage .. ": " .. message, 3)
end

return M
