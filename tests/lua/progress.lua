-- invasim.Progress from Lua, forced to plain lines, one line per update.
local iv = require("invasim")
local progress = iv.Progress{ total = 50, every_seconds = 0, live = false, label = "" }
for step = 0, 50, 10 do progress:update(step, step * 0.05) end
progress:finish()
progress:finish()  -- a second finish is harmless
print(tostring(progress))
