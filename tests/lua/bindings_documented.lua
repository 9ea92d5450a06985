-- Test: every function and value of the invasim module and every method of every bound type
-- is in docs/lua.md's "Index of the bindings", each with a line saying what it does, and the
-- index names nothing that is not bound. The bindings are enumerated at run time: the module
-- table, and the method table of each metatable "invasim.<Type>" in the Lua registry (the
-- first upvalue of its __index function, as binding.cpp's define_metatable makes it).
local iv = require("invasim")

local bound = {}  -- "invasim.name" and "Type:method" -> true
for name in pairs(iv) do bound["invasim." .. name] = true end
local types = 0
for key, mt in pairs(debug.getregistry()) do
  local type_name = type(key) == "string" and key:match("^invasim%.(.+)$")
  if type_name and type(mt) == "table" then
    local index = rawget(mt, "__index")
    local methods = index
    if type(index) == "function" then
      local _, upvalue = debug.getupvalue(index, 1)
      methods = upvalue
    end
    assert(type(methods) == "table", "no method table found for " .. key)
    types = types + 1
    for method in pairs(methods) do bound[type_name .. ":" .. method] = true end
  end
end
assert(types >= 10, "found only " .. types .. " bound types in the registry")

-- The index: rows "| `name...` | what it does |" of the section "## Index of the bindings".
local f = assert(io.open("../../docs/lua.md"))
local text = f:read("a")
f:close()
local section = text:match("\n## Index of the bindings\n(.-)\n## ") or text:match("\n## Index of the bindings\n(.*)$")
assert(section, "docs/lua.md has no section '## Index of the bindings'")
local documented, optional_rows, problems = {}, {}, {}
for line in section:gmatch("[^\n]+") do
  local name, what = line:match("^| `([%w_.:]+)[^`]*` | (.-) |$")
  if name then
    if documented[name] then problems[#problems + 1] = "listed twice: " .. name end
    documented[name] = true
    if not what:find("%a") then problems[#problems + 1] = "no description: " .. name end
    if what:find("absent unless") then optional_rows[name] = true end
  end
end

local function sorted(set)
  local list = {}
  for k in pairs(set) do list[#list + 1] = k end
  table.sort(list)
  return list
end
local count = 0
for _, name in ipairs(sorted(bound)) do
  count = count + 1
  if not documented[name] then problems[#problems + 1] = "bound but not in docs/lua.md's index: " .. name end
end
for _, name in ipairs(sorted(documented)) do
  -- (invasim.from and invasim.resume exist only with --from / --resume: their rows say so)
  local optional = name:match("^invasim%.") and optional_rows[name]
  if not bound[name] and not optional then
    problems[#problems + 1] = "in docs/lua.md's index but not bound: " .. name
  end
end
if #problems > 0 then error("FAILED:\n  " .. table.concat(problems, "\n  "), 0) end
print(string.format("bindings_documented: all %d bindings are in docs/lua.md (%d types)", count, types))
