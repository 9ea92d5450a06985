-- error({}) in a spec: the message names this line and the type (it used to be empty).
local values = { 1e-4 }
if #values < 2 then error({ reason = "too few values" }) end
return { protocol = "../../../protocols/invasion.lua", product = { kT = values } }
