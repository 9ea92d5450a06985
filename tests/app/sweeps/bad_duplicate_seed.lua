-- The same seed twice would be one point twice: refused.
return {
  protocol = "../../../protocols/invasion.lua",
  product = { P = { 1e-3, 2e-3 } },
  seeds = { 1, 1 },
}
