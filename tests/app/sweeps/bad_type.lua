return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2 },
  product = {
    kT = { 1e-4, "hot" },
  },
}
