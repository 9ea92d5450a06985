#pragma once
// The protocol's own state in a checkpoint (section "extra"): plain Lua data written by
// protocols/lib/resume.lua's serialize (nil, booleans, integers, floats in %a hexadecimal,
// 0/0, math.huge, %q strings, tables of [key]=value). It is read back by this parser, never
// by running it as Lua: a crafted checkpoint could otherwise loop forever or allocate without
// bound while "loading data". The grammar is data only, nesting is limited, and every value
// consumes input, so parsing is linear in the text. Numbers follow Lua's rules exactly
// (a decimal integer that overflows is a float, hexadecimal integers wrap, unary minus
// applies after), so the data come back equal, integer/float subtype included.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace invasim {

// The deepest table nesting accepted (Lua's own parser stops at 200 C levels).
inline constexpr int kMaxLuaDataDepth = 100;

// One value of the data subset.
struct LuaDatum {
  enum class Kind { kNil, kBoolean, kInteger, kNumber, kString, kTable };
  Kind kind = Kind::kNil;
  bool boolean = false;
  std::int64_t integer = 0;
  double number = 0.0;
  std::string string;
  std::vector<std::pair<LuaDatum, LuaDatum>> entries;  // tables: [key] = value, in text order
};

// Parses one value (surrounding whitespace allowed). Throws IoError "<origin>: line L (offset
// O): <what>" for anything else: code, an unknown escape, a nil or NaN key, nesting deeper than
// kMaxLuaDataDepth, trailing text.
LuaDatum parse_lua_data(std::string_view text, const std::string& origin);

}  // namespace invasim
