return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2 },
  seed = { 1, 2 },
}
