#pragma once
// Helpers for error messages that list valid names: "valid keys: a, b, c" and a
// "did you mean 'box'?" hint for near misses.
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace invasim {

// Concatenates streamable parts: cat("[", 3, "]") -> "[3]". (Also sidesteps GCC 12's false
// -Wrestrict warning on `"literal" + std::string&&`.)
template <typename... Parts>
std::string cat(const Parts&... parts) {
  std::ostringstream out;
  (out << ... << parts);
  return out.str();
}

// Whether `item` is one of `names`.
inline bool contains(const std::vector<std::string>& names, std::string_view item) {
  for (const auto& n : names)
    if (n == item) return true;
  return false;
}

// Sorted, de-duplicated, comma-separated: {"seed", "box"} -> "box, seed".
std::string join_names(std::vector<std::string> names);

// " (did you mean 'box'?)" when a candidate is within a small edit distance of `name`, else
// "": optimal string alignment (Levenshtein plus adjacent transpositions, so "bxo" -> "box" is
// one edit), at most 1 edit for names of up to 3 characters, else max(2, length / 3). The one
// "did you mean" of the engine's and the stages' keyword checks (invasim.keywords).
std::string did_you_mean(std::string_view name, const std::vector<std::string>& candidates);

// Rows of cells as text columns, each padded to its widest cell, two spaces before each
// line (the listings of `invasim params` and `invasim keys`); trailing blanks trimmed.
std::string aligned_table(const std::vector<std::vector<std::string>>& rows);

}  // namespace invasim
