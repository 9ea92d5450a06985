-- Test: a protocol's seed also seeds math.random, so its own draws repeat for the same seed.
local iv = require("invasim")
local p = iv.params{ seed = 1 }
print(string.format("seed=%d random=%d", p.seed, math.random(1, 1000000000)))
