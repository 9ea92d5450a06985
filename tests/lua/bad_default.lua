-- A declaration whose default lies outside its own range: an error at the invasim.params call.
local iv = require("invasim")
local p = iv.params{
  dt = { 0.0, range = "(0, inf)", unit = "tau", help = "time step" },
}
print("RUNNING", p.dt)
