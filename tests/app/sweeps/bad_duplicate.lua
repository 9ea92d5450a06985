-- The same value twice in an axis (or in seeds) would be one point twice: refused.
return {
  protocol = "../../../protocols/invasion.lua",
  product = { P = { 1e-3, 2e-3, 1e-3 } },
  seeds = { 1, 2 },
}
