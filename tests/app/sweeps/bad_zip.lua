return {
  protocol = "../../../protocols/invasion.lua",
  zip = { {
    beta = { 0.0, 0.01 },
    tau_p = { 25.0 },
  } },
}
