return {
  protocol = "../../../protocols/invasion.lua",
  set = { kT = 1e-4 },
  product = { kT = { 1e-3 } },
}
