-- invasim.json_encode: the layout of params.json and summary.json, byte for byte; __pairs,
-- userdata, the indent option and the errors (unknown option, a table that contains itself, a
-- __pairs that fails or returns no iterator: each at the script's line).
local iv = require("invasim")
local checks = 0
local function check(condition, message)
  if not condition then error("check failed: " .. tostring(message), 2) end
  checks = checks + 1
end
local function expect_error(pattern, f, ...)
  local ok, err = pcall(f, ...)
  check(not ok and type(err) == "string" and err:find(pattern), "wrong message: " .. tostring(err))
  check(err:find("^json_encode%.lua:%d+: "), "no location: " .. err)
end

local doc = {
  floats = { 0.1, 1.0, 1/3, 1e-5, 1e15, 1234567890123456.0, 0.1 + 0.2, 5e-324, 1.7976931348623157e308,
             -0.0, 100.0, 123456.789, 2^53, 1e16, 0.0001, 6.02214076e23, -2.5e-7, 0/0, math.huge },
  ints = { 0, -1, 42, math.maxinteger, math.mininteger },
  text = "tab\there \"q\" back\\ nl\n cr\r bell\7 del\127 \xc3\xa9",
  empty = {},
  nested = { list_of_objects = { { b = 2, a = 1 }, {} }, flag = true, off = false, [3] = "three" },
  [1.5] = "float key",
}
-- The old encoder's output for `doc`.
local expected = [==[
{
  "1.5": "float key",
  "empty": [],
  "floats": [0.1, 1, 0.3333333333333333, 1e-05, 1e+15, 1234567890123456, 0.30000000000000004, 4.94065645841247e-324, 1.7976931348623157e+308, -0, 100, 123456.789, 9007199254740992, 1e+16, 0.0001, 6.02214076e+23, -2.5e-07, null, null],
  "ints": [0, -1, 42, 9223372036854775807, -9223372036854775808],
  "nested": {
    "3": "three",
    "flag": true,
    "list_of_objects": [{
        "a": 1,
        "b": 2
      }, []],
    "off": false
  },
  "text": "tab\there \"q\" back\\ nl\n cr\r bell\u0007 del\u007f é"
}
]==]
check(iv.json_encode(doc) == expected, "\n" .. iv.json_encode(doc))
check(iv.json_encode({}) == "[]\n")
check(iv.json_encode({ 1, 2, nil, 4 }) == "[1, 2]\n")  -- as ipairs: up to the first nil
check(iv.json_encode("x") == "\"x\"\n")
check(iv.json_encode(nil) == "null\n")
check(iv.json_encode({ b = { 1, 2.5 }, a = { x = true } }, { indent = 0 }) ==
      "{\"a\": {\"x\": true}, \"b\": [1, 2.5]}\n")
check(iv.json_encode({ a = { x = 1 } }, { indent = 4 }) == "{\n    \"a\": {\n        \"x\": 1\n    }\n}\n")
-- __pairs is honoured (read-only tables such as invasim.params' result).
local proxy = setmetatable({}, { __pairs = function() return next, { b = 2, a = 1 }, nil end })
check(iv.json_encode(proxy) == "{\n  \"a\": 1,\n  \"b\": 2\n}\n", iv.json_encode(proxy))
-- Userdata and functions: their tostring text.
check(iv.json_encode({ f = io.stdout }) == "{\n  \"f\": \"" .. tostring(io.stdout) .. "\"\n}\n")

expect_error("json_encode: unknown key 'indnet' %(did you mean 'indent'%?%)", iv.json_encode, {}, { indnet = 2 })
expect_error("indent", iv.json_encode, {}, { indent = 17 })
local loop = {}
loop.self = loop
expect_error("json_encode: tables nested deeper than 256 levels %(does a table contain itself%?%)",
             iv.json_encode, loop)
expect_error("__pairs failed", iv.json_encode, setmetatable({}, { __pairs = function() error("__pairs failed") end }))
expect_error("^json_encode%.lua:%d+: json_encode: a table's __pairs returned a number where pairs needs an iterator function",
             iv.json_encode, setmetatable({}, { __pairs = function() return 5 end }))
print(string.format("json_encode: all %d checks passed", checks))
