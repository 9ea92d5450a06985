-- One parameter of each type; prints what reached the script (tests/lua/CMakeLists.txt).
local iv = require("invasim")
local p = iv.params{
  n = {5, unit = "cells", help = "number of cancer cells"},
  x = {0.5, help = "packing fraction"},
  flag = {false, help = "a switch"},
  name = {"abc", help = "a label"},
  seed = {1, help = "random seed"},
}
print("RUNNING")
print(string.format("n=%s %s x=%s %s flag=%s name=%s seed=%s out=%s", p.n, math.type(p.n), p.x,
                    math.type(p.x), tostring(p.flag), p.name, p.seed, iv.out_dir))
