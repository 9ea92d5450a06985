-- 400 points (seeds 1 to 400), never run: `sweep submit --dry-run` writes a points.txt of
-- 13 kB, larger than its sbatch scripts (tests/app/sweep_write_failures.sh).
local seeds = {}
for i = 1, 400 do seeds[i] = i end
return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2, N_c = 200, steps = 1000 },
  seeds = seeds,
}
