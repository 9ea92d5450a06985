return {
  protocol = "../../../protocols/invasion.lua",
  set = {
    N_a = 2,
    stpes = 100,
  },
}
