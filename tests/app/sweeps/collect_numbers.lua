-- Points whose values print differently under %.17g and Python's repr (kT = 0.0013), and two
-- points that differ only in the Lua subtype of tau_p (25 and 25.0: two signac ids), for
-- sweep_collect_numbers.sh. Never run: the test writes the results of one point by hand.
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, steps = 1000 },
  product = { tau_p = { 25, 25.0 }, kT = { 0.0013, 1e-5 } },
  seeds = { 1 },
}
