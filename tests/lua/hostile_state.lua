-- Test: the protocol state in a checkpoint (section "extra") is read back as data, never run.
-- A crafted checkpoint whose state is code (an endless loop, a string of 2^40 bytes) used to
-- hang or exhaust memory in lib/resume.lua's deserialize (load + call); it is now refused with
-- the checkpoint, the section and the offending text. What serialize writes still round-trips,
-- subtypes included. CTest gives this test a timeout: before the fix it never ended.
package.path = "../../protocols/?.lua;" .. package.path
local iv = require("invasim")
local resume = require("lib.resume")
iv.make_dirs(iv.out_dir)
local path = iv.out_dir .. "/crafted.ckpt"
local sys = iv.System{ box = { 6, 6, 6 }, seed = 1 }

local function load_state(extra)
  iv.save_checkpoint(path, { system = sys, extra = extra })
  return resume.deserialize(iv.load_checkpoint(path, { system = sys }), path)
end

for _, evil in ipairs{ "(function() while true do end end)()", "('x'):rep(1 << 40)",
                       "{[1]=(function() local t = {} while true do t[#t + 1] = t end end)()}",
                       string.rep("{[1]=", 1000) .. "1" .. string.rep("}", 1000) } do
  local ok, err = pcall(load_state, evil)
  assert(not ok, "a crafted state was accepted: " .. evil:sub(1, 40))
  err = tostring(err)
  assert(err:find("checkpoint " .. path .. ": section 'extra': line 1", 1, true), err)
  assert(err:find("unexpected character") or err:find("nested deeper than 100"), err)
end

local state = { rows = { { T = 1e-3, step = 1200, ok = true, name = "a\"b\n\0" }, { nan = 0 / 0, inf = -math.huge } },
                end_step = 2400, compression = { phi = 0.82, steps = 12 }, [3.5] = "float key", [-7] = false }
local back = load_state(resume.serialize(state))
assert(resume.serialize(back) == resume.serialize(state), "the state did not round-trip")
assert(math.type(back.end_step) == "integer" and math.type(back.compression.phi) == "float")
assert(back.rows[2].nan ~= back.rows[2].nan and back[-7] == false and back[3.5] == "float key")
-- growing_list: the text serialize writes for the list, as the list grows (each element
-- serialized once), also nested as the production stage's checkpoint state nests it.
local rows, grown = {}, nil
grown = resume.growing_list(rows)
for n = 0, 5 do
  if n > 0 then rows[n] = { A_t = n + 0.25, step = 1000 * n, label = "r" .. n } end
  assert(resume.serialize(grown()) == resume.serialize(rows), "growing_list at " .. n .. " rows")
  assert(resume.serialize{ rows = grown(), end_step = 7 } == resume.serialize{ rows = rows, end_step = 7 },
         "growing_list nested at " .. n .. " rows")
end
print("hostile_state: crafted states refused, serialize round-trips")
