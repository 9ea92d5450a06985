return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2 },
  tiny = { set = { steps = 100 },
           take = 0 },
}
