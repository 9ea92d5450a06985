-- Test: key `contacts` of invasim.compress and fire:minimize changes the System's contact
-- parameters for that call only (the compress stage's cohesion off): the change is in force
-- during the call (the compression's callback sees it, and the result is bit for bit that of
-- a run with contacts:set{} before and after), and the contacts' own parameters are back
-- after a normal return, an engine error, an error raised by the callback and a stop signal
-- (SIGTERM; last, since the stop request stays set).
local iv = require("invasim")
local checks = 0
local function check(ok, fmt, ...)
  if not ok then error("FAILED: " .. string.format(fmt, ...), 2) end
  checks = checks + 1
end

-- A small tissue with cohesive contacts (beta = 1e-2).
local function tissue()
  local sys = iv.System{ box = { 24, 16, 16 }, periodic = { false, true, true }, seed = 3 }
  sys:place{ cells = { n = 60, diameters = { 0.9, 1.1 }, x = { 1, 5 } },
             adipocytes = { n = 2, diameter = 6, vertex_diameter = 2, shape_param = 1.1, x = { 9, 20 } } }
  sys:add(iv.Walls{ eps = 1 })
  local contacts = sys:add(iv.Contacts{ alpha = 0.2, beta = 1e-2 })
  sys:add(iv.Shape{ eps_v = 1e3, eps_a = 1 })
  return sys, contacts
end
local function own(contacts, what)
  local c = contacts:params()
  check(c.beta == 1e-2 and c.alpha == 0.2, "%s: contacts have beta = %g, alpha = %g, not their own 0.01, 0.2",
        what, c.beta, c.alpha)
end
local function same_positions(a, b, what)
  local pa, pb = a:positions(), b:positions()
  for i = 1, #pa do
    for k = 1, 3 do check(pa[i][k] == pb[i][k], "%s: site %d differs", what, i) end
  end
end
local compression = { to_phi = 0.3, ftol = 1e-4, max_steps = 2000 }
local function with(t, extra)
  local all = {}
  for k, v in pairs(t) do all[k] = v end
  for k, v in pairs(extra) do all[k] = v end
  return all
end

-- During the compression the contacts have beta = 0, after it their own; the result equals
-- that of contacts:set{beta = 0} ... contacts:set{beta = 1e-2}.
local sys, contacts = tissue()
local seen = {}
local r = iv.compress(sys, with(compression, { contacts = { beta = 0 }, callback = function()
  seen[#seen + 1] = contacts:params().beta
end }))
check(#seen > 0 and r.steps == #seen, "the callback ran once per compression step")
for i, beta in ipairs(seen) do check(beta == 0, "compression step %d ran with beta = %g", i, beta) end
own(contacts, "after compress")
local fire = iv.Fire{ ftol = 1e-6, max_steps = 5000 }
fire:minimize(sys, { contacts = { beta = 0 } })
own(contacts, "after minimize")
local ref, ref_contacts = tissue()
ref_contacts:set{ beta = 0 }
iv.compress(ref, compression)
fire:minimize(ref)
ref_contacts:set{ beta = 1e-2 }
same_positions(sys, ref, "compress + minimize with contacts = {beta = 0} vs contacts:set")
fire:minimize(sys, nil, { contacts = {} })  -- nil Dynamics, empty change: allowed
own(contacts, "after an empty change")

-- Errors: the change is undone (or never made) and the message names the key.
local function fails(pattern, fn, ...)
  local ok, err = pcall(fn, ...)
  check(not ok and tostring(err):find(pattern), "expected an error matching '%s', got %s", pattern, tostring(err))
end
sys, contacts = tissue()
fails("boom", iv.compress, sys, with(compression, { contacts = { beta = 0 }, callback = function() error("boom") end }))
own(contacts, "after an error in the callback")
fails("compress: the packing fraction is already", iv.compress, sys, with(compression, { to_phi = 0.01, contacts = { beta = 0 } }))
own(contacts, "after an engine error")
fails("compress.contacts: unknown key 'bta' %(did you mean 'beta'%?%)", iv.compress, sys,
      with(compression, { contacts = { bta = 0 } }))
fails("minimize.contacts: key 'beta' must be a number", fire.minimize, fire, sys, { contacts = { beta = "off" } })
fails("minimize: unknown key 'contact'", fire.minimize, fire, sys, { contact = { beta = 0 } })
fails("compress: .*beta = 0.5 must be smaller than alpha = 0.2", iv.compress, sys,
      with(compression, { contacts = { beta = 0.5 } }))
own(contacts, "after refused changes")
local bare = iv.System{ box = { 10, 10, 10 }, periodic = { false, true, true } }
bare:place{ cells = { n = 5, x = { 1, 9 } } }
fails("compress: key 'contacts': the System has no Contacts force", iv.compress, bare,
      { to_phi = 0.1, contacts = { beta = 0 } })

-- A stop signal at the first compression step boundary: stopped, contacts restored.
sys, contacts = tissue()
r = iv.compress(sys, with(compression, { contacts = { beta = 0 }, callback = function(step)
  if step.steps == 1 then os.execute("kill -TERM $PPID") end
end }))
check(r.stopped and r.steps == 1, "SIGTERM stopped the compression after step 1 (steps = %d)", r.steps)
check(iv.interrupted() == "SIGTERM", "interrupted: %s", tostring(iv.interrupted()))
own(contacts, "after a stop signal")
print(string.format("temporary_contacts: all %d checks passed", checks))
