-- --threads N reaches OpenMP.
print("threads=" .. require("invasim").threads())
