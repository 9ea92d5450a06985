return {
  protocol = "../../../protocols/invasion.lua",
  set = { steps = 2.5e3 },
}
