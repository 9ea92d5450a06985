-- A spec cannot write files: io is not in its environment.
io.open("written_by_a_spec.txt", "w"):write("x")
return { protocol = "../../../protocols/invasion.lua", product = { kT = { 1e-4, 2e-4 } } }
