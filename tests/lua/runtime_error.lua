-- A plain Lua error two calls deep: file:line of the error, and a traceback on request.
local function inner(t)
  return t.missing + 1
end
local function outer() return inner({}) end
outer()
