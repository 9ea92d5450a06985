-- A small JSON encoder for run metadata (params.json, summary.json): tables with string keys
-- become objects (keys sorted, so files diff cleanly), arrays become arrays, numbers are
-- written in their shortest exact form (15-17 digits) (non-finite numbers as null).
local M = {}

local function escape(s)
  return '"' .. s:gsub('[%c"\\]', function(c)
    local named = { ['"'] = '\\"', ['\\'] = '\\\\', ['\n'] = '\\n', ['\t'] = '\\t', ['\r'] = '\\r' }
    return named[c] or string.format("\\u%04x", c:byte())
  end) .. '"'
end

local function is_array(t)
  local n = #t
  for k in pairs(t) do
    if math.type(k) ~= "integer" or k < 1 or k > n then return false end
  end
  return n > 0 or next(t) == nil
end

local function encode(v, indent)
  local t = type(v)
  if t == "nil" then return "null"
  elseif t == "boolean" then return tostring(v)
  elseif t == "number" then
    if v ~= v or v == math.huge or v == -math.huge then return "null" end
    if math.type(v) == "integer" then return tostring(v) end
    for digits = 15, 17 do  -- the shortest form that reads back exactly
      local text = string.format("%." .. digits .. "g", v)
      if digits == 17 or tonumber(text) == v then return text end
    end
  elseif t == "string" then return escape(v)
  elseif t == "table" then
    local inner = indent .. "  "
    local parts = {}
    if is_array(v) then
      if #v == 0 then return "[]" end
      for _, x in ipairs(v) do parts[#parts + 1] = encode(x, inner) end
      return "[" .. table.concat(parts, ", ") .. "]"
    end
    local keys = {}
    for k in pairs(v) do keys[#keys + 1] = tostring(k) end
    table.sort(keys)
    for _, k in ipairs(keys) do
      local x = v[k]
      if x == nil then x = v[tonumber(k)] end
      parts[#parts + 1] = inner .. escape(k) .. ": " .. encode(x, inner)
    end
    return "{\n" .. table.concat(parts, ",\n") .. "\n" .. indent .. "}"
  end
  return escape(tostring(v))  -- userdata (ramps, groups): their description
end

function M.encode(v) return encode(v, "") .. "\n" end

return M
