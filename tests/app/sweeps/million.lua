-- A spec of 10^6 points (three axes of 100 values): `sweep init` must count them and refuse
-- before writing anything (tests/app/sweep_workspace.sh).
local kT, f0, tau_p = {}, {}, {}
for i = 1, 100 do
  kT[i] = i * 1e-5
  f0[i] = i * 1e-4
  tau_p[i] = i * 1.0
end
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, quench_steps = 100, steps = 1000, every = 50 },
  product = { kT = kT, f0 = f0, tau_p = tau_p },
}
