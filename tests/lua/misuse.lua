-- Every wrong call must raise a catchable Lua error with this file's line; none may crash.
local iv = require("invasim")
local checks = 0

local function expect_error(pattern, f, ...)
  local ok, err = pcall(f, ...)
  assert(not ok, "expected an error matching " .. pattern)
  assert(type(err) == "string" and err:find(pattern), tostring(err))
  assert(err:find("^misuse%.lua:%d+: "), "no location: " .. err)
  checks = checks + 1
end

local p = iv.params{ a = {1, help = "a"}, s = "x" }

-- params: read-only, no undeclared names, one call only, malformed declarations
expect_error("no parameter 'b'", function() return p.b end)
expect_error("read%-only", function() p.a = 2 end)
expect_error("read%-only", function() p.new = 2 end)
expect_error("already called", iv.params, { c = 1 })
assert(not pcall(setmetatable, p, {}) and getmetatable(p) == false)
checks = checks + 1

-- Progress: constructors with wrong tables, methods with wrong arguments
expect_error("expected a keyword table", iv.Progress)
expect_error("expected a keyword table", iv.Progress, 5)
expect_error("key 'total' must be an integer, got string", iv.Progress, { total = "10" })
expect_error("key 'total' = %-1 is out of range", iv.Progress, { total = -1 })
expect_error("key 'total' must be an integer, got 2.5", iv.Progress, { total = 2.5 })
expect_error("key 'live' must be a boolean", iv.Progress, { live = 1 })
expect_error("unexpected positional value %[1%]", iv.Progress, { 10 })
expect_error("unknown keys 'a', 'b'", iv.Progress, { a = 1, b = 2 })
local progress = iv.Progress{ total = 10, live = false, every_seconds = 1e9 }
expect_error("bad argument #1 to 'update' %(Progress expected, got number; for a method call",
             function() progress.update(5) end)
local impostor = { update = progress.update }
-- One hint, not two: a "bad self" says to call with ':' and adds no "for a method call" hint.
expect_error("bad self for 'update' %(Progress expected, got table; call methods with ':', as in "
             .. "obj:update%(%.%.%.%)%)$", function() impostor:update(1) end)
expect_error("bad argument #1 to 'update' %(integer expected, got no value%)", function() progress:update() end)
expect_error("bad argument #1 to 'update' %(integer expected, got string%)", function() progress:update("x") end)
expect_error("bad argument #2 to 'update' %(number expected, got table%)", function() progress:update(1, {}) end)
-- called through pcall, where Lua cannot name the function: named from the module's table
expect_error("bad argument #1 to 'save_checkpoint' %(", iv.save_checkpoint, 5, {})
expect_error("Progress expected, got table", progress.finish, {})
expect_error("has no method or field 'updte' %(did you mean 'update'%?%)", function() progress:updte(1) end)
expect_error("has no field of type number", function() return progress[1] end)
expect_error("Progress expected, got FILE%*", function() return progress.update(io.stdout, 1) end)

-- Deep recursion and non-string errors stay Lua errors.
local function recurse() return recurse() + 1 end
local ok, err = pcall(recurse)
assert(not ok and err:find("stack overflow"))
checks = checks + 1

print("misuse: all " .. checks .. " checks passed")
