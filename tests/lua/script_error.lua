-- A misspelled keyword: the error names the key, the valid ones and this line.
local iv = require("invasim")

local progress = iv.Progress{ totl = 10 }
