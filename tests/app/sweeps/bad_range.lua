return {
  protocol = "../../../protocols/invasion.lua",
  product = { phi = { 0.5, 1.5 } },
}
