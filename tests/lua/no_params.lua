-- Never declares parameters: any --set must be rejected.
local x = 1 + 1
