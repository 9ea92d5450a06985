-- The end-of-run report printed by the protocols: one line per averaged quantity.
local log = require("lib.log")

local M = {}

-- Prints "name = mean +- error unit" for each name of `names` present in `summary`.
function M.print(label, summary, names, units)
  for _, name in ipairs(names) do
    local s = summary[name]
    if s then
      local unit = units and units[name] or ""
      if s.error == s.error then
        log.say(label, "%-8s = %.5g +- %.2g %s", name, s.mean, s.error, unit)
      else  -- too few samples for an error bar
        log.say(label, "%-8s = %.5g (no error bar: too few samples) %s", name, s.mean, unit)
      end
    end
  end
end

return M
