-- The run's time series as CSV (series.csv): a header row of `name [unit]` entries, then one
-- row per sample, appended and flushed as the run goes, so that a killed run keeps every
-- sample written so far. A failed write or flush (a full disk) is an error naming the file.
local iv = require("invasim")
local files = require("lib.files")

local M = {}
M.__index = M

-- Writes the parts and flushes them; raises an error naming `path` if either fails.
local function put(file, path, ...)
  local ok, err = files.write_flushed(file, ...)
  if not ok then error(string.format("series: cannot write %s: %s", path, tostring(err)), 0) end
end

-- One row's CSV line (without the newline).
local function line(columns, row)
  local fields = {}
  for i, c in ipairs(columns) do
    local v = row[c]
    fields[i] = v == nil and "" or (math.type(v) == "integer" and tostring(v) or string.format("%.10g", v))
  end
  return table.concat(fields, ",")
end

-- Opens `path` for the given columns (names) with units (name -> unit, optional), holding the
-- header and the rows already sampled (`rows`, optional: a resumed run's), then appends. The
-- file is replaced atomically (temp file + rename), so that a run killed while it resumes
-- leaves the previous series.csv whole, never a truncated one.
function M.open(path, columns, units, rows)
  local text = {}
  for i, c in ipairs(columns) do
    local unit = units and units[c]
    text[i] = (unit and unit ~= "1") and (c .. " [" .. unit .. "]") or c
  end
  text = { table.concat(text, ",") }
  for _, row in ipairs(rows or {}) do text[#text + 1] = line(columns, row) end
  iv.write_file(path, table.concat(text, "\n") .. "\n")
  local file, err = io.open(path, "a")
  if not file then error("series: cannot write " .. path .. ": " .. tostring(err), 2) end
  return setmetatable({ file = file, columns = columns, path = path }, M)
end

function M:write(row)
  put(self.file, self.path, line(self.columns, row), "\n")
end

function M:close()
  if self.file then self.file:close(); self.file = nil end
end

-- CSV text of whole columns {names = {...}, columns = {name = {...}}}.
function M.columns_text(result)
  local rows = {}
  rows[1] = table.concat(result.names, ",")
  local n = #result.columns[result.names[1]]
  for i = 1, n do
    local fields = {}
    for j, name in ipairs(result.names) do fields[j] = string.format("%.10g", result.columns[name][i]) end
    rows[#rows + 1] = table.concat(fields, ",")
  end
  return table.concat(rows, "\n") .. "\n"
end

return M
