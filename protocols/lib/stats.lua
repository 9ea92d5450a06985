-- Time-series statistics for stage summaries: mean and standard error by block averaging
-- (Flyvbjerg-Petersen: halve the series repeatedly, take the largest error estimate among
-- the levels with at least 8 blocks; a correlated series gets an honest error bar).
local M = {}

function M.mean(xs, first)
  first = first or 1
  local s, n = 0.0, 0
  for i = first, #xs do s = s + xs[i]; n = n + 1 end
  return n > 0 and s / n or 0 / 0
end

-- Returns mean, standard error of the samples xs[first..#xs].
function M.block_average(xs, first)
  first = first or 1
  local level = {}
  for i = first, #xs do level[#level + 1] = xs[i] end
  local n = #level
  if n == 0 then return 0 / 0, 0 / 0 end
  local mean = M.mean(level)
  local best = 0.0
  while #level >= 8 do
    local var = 0.0
    for _, x in ipairs(level) do var = var + (x - mean) ^ 2 end
    var = var / (#level - 1)
    best = math.max(best, math.sqrt(var / #level))
    local next_level = {}
    for i = 1, #level - 1, 2 do next_level[#next_level + 1] = 0.5 * (level[i] + level[i + 1]) end
    level = next_level
  end
  if n < 8 then
    local var = 0.0
    for _, x in ipairs(level) do var = var + (x - mean) ^ 2 end
    best = n > 1 and math.sqrt(var / (n - 1) / n) or 0 / 0
  end
  return mean, best
end

return M
