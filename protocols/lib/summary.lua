-- The end-of-run report printed by the protocols: one line per averaged quantity.
local log = require("lib.log")

local M = {}

-- Prints "name = mean +- error unit" for each name of `names` present in `summary`. An error
-- bar that is only a lower bound (error_converged false: the autocorrelation sum did not
-- meet Sokal's window criterion, the window being too short for the quantity's correlation
-- time) is marked with "(*)", and one line after the list says what the mark means.
function M.print(label, summary, names, units)
  local marked = false
  for _, name in ipairs(names) do
    local s = summary[name]
    if s then
      local unit = units and units[name] or ""
      if s.mean ~= s.mean then  -- nothing averaged: no sample in the window, or NaN samples
        log.say(label, "%-8s = undefined (%s)", name,
                (s.samples or 0) == 0 and "no sample in the averaging window: a smaller every" or
                string.format("some of its %d samples are not numbers", s.samples))
      elseif s.error == s.error then
        local lower_bound = s.error_converged == false
        marked = marked or lower_bound
        log.say(label, "%-8s = %.5g +- %.2g %s%s", name, s.mean, s.error, unit, lower_bound and " (*)" or "")
      else  -- too few samples for an error bar
        log.say(label, "%-8s = %.5g (no error bar: too few samples) %s", name, s.mean, unit)
      end
    end
  end
  if marked then
    log.say(label, "(*) error bar a lower bound: the window is too short for the correlation time " ..
            "(the autocorrelation time's sum needs a window of 5 correlation times, at most a third of the samples)")
  end
end

return M
