-- Declares parameters but no `seed`: --seed must be rejected.
local p = require("invasim").params{ steps = 10 }
print("RUNNING", p.steps)
