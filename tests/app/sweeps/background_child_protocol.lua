-- A protocol that starts a background child which outlives the run and holds the run's
-- standard output (os.execute("... &")), as a protocol starting a plotting script might.
local iv = require("invasim")
local p = iv.params{ n = 1, seed = 1 }
os.execute("sleep 59.9 &")
print("background_child: started a child that outlives the run, n = " .. p.n)
