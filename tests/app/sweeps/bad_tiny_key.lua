return {
  protocol = "../../../protocols/invasion.lua",
  set = { N_a = 2 },
  tiny = { sett = { steps = 100 }, take = 2 },
}
