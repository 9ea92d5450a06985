-- Lua chunks are loaded as text only. Lua does not verify precompiled
-- (binary) chunks, and a corrupted one crashes or hangs the process, so load, loadfile,
-- dofile and require refuse them with a message naming the file. With TEXT_CHUNKS_OUT set,
-- writes a corrupted binary chunk there (text_chunks.sh runs it as a protocol).
local checks = 0
local function check(condition, message)
  if not condition then error("check failed: " .. tostring(message), 2) end
  checks = checks + 1
end

local function answer() return 42 end
local binary = string.dump(answer)
check(binary:sub(1, 4) == "\27Lua", "string.dump gives a binary chunk")

-- load: the default mode and "bt" load text only; an explicit binary mode is refused.
local f, err = load(binary)
check(f == nil and err:find("attempt to load a binary chunk %(mode is 't'%)"), err)
f, err = load(binary, "=bin", "bt")
check(f == nil and err:find("binary chunk"), err)
local ok, e = pcall(function() local chunk = load(binary, "=bin", "b"); return chunk end)
check(not ok and e:find("^text_chunks%.lua:%d+: load: mode 'b' refused: invasim loads Lua chunks as text only"), e)
ok, e = pcall(load, "return 1", "=t", "b")
check(not ok and e:find("load: mode 'b' refused"), e)
-- Text still loads, with the mode and environment arguments as in plain Lua.
check(load("return 1 + 1")() == 2)
check(load("return x", "=env", "t", { x = 7 })() == 7)
check(select("#", load("return ...", "=n", "t", nil)(1, 2)) == 2)
ok, e = pcall(load("return print", "=nilenv", "t", nil))  -- _ENV is nil, as in plain Lua
check(not ok and e:find("_ENV", 1, true), "an explicit nil environment is kept: " .. tostring(e))

-- Files: loadfile, dofile and require name the refused file.
local dir = os.tmpname()
os.remove(dir)
assert(os.execute("mkdir -p '" .. dir .. "'"))
local path = dir .. "/binmod.lua"
local file = assert(io.open(path, "wb"))
file:write(binary)
file:close()
f, err = loadfile(path)
check(f == nil and err:find(path, 1, true) and err:find("binary chunk"), err)
ok, e = pcall(loadfile, path, "b")
check(not ok and e:find("loadfile: mode 'b' refused"), e)
ok, e = pcall(dofile, path)
check(not ok and e:find(path, 1, true) and e:find("binary chunk"), e)
package.path = dir .. "/?.lua;" .. package.path
ok, e = pcall(require, "binmod")
check(not ok and e:find("error loading module 'binmod' from file '" .. path, 1, true)
      and e:find("binary chunk"), e)
-- A text module next to it still loads through require, dofile and loadfile.
local text = assert(io.open(dir .. "/textmod.lua", "w"))
text:write("return { value = 5 }\n")
text:close()
check(require("textmod").value == 5)
check(dofile(dir .. "/textmod.lua").value == 5)
check(loadfile(dir .. "/textmod.lua")().value == 5)
ok, e = pcall(require, "no_such_module_here")
check(not ok and e:find("module 'no_such_module_here' not found") and e:find("no file '", 1, true), e)
os.remove(path)
os.remove(dir .. "/textmod.lua")
os.remove(dir)

-- A corrupted precompiled chunk for the protocol test: one byte of this function's stripped
-- dump changed (with plain Lua 5.4.4, running it segfaults).
local out = os.getenv("TEXT_CHUNKS_OUT")
if out then
  local function sum(t) local s = 0 for i = 1, #t do s = s + t[i] * 2 end return s, tostring(s) .. "x" end
  local dump = string.dump(sum, true)
  local corrupt = assert(io.open(out, "wb"))
  corrupt:write(dump:sub(1, 39), string.char(dump:byte(40) ~ 0x5A), dump:sub(41))
  corrupt:close()
end
print("text_chunks: all " .. checks .. " checks passed")
