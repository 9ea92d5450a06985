#include "sweep/window_drift.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

namespace invasim::sweep {

namespace {

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream in(line);
  for (std::string cell; std::getline(in, cell, ',');) cells.push_back(cell);
  return cells;
}

// The number in `text`, or NaN if it is not one whole number.
double parse_number(const std::string& text) {
  if (text.empty()) return std::nan("");
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() ? value : std::nan("");
}

}  // namespace

std::string bare_column_name(const std::string& column) {
  const auto open = column.find(" [");
  return open == std::string::npos ? column : column.substr(0, open);
}

std::map<std::string, double> window_drifts(const fs::path& series, const Json& averages) {
  std::map<std::string, double> drifts;
  std::ifstream in(series);
  std::string line;
  if (!averages.is_object() || !std::getline(in, line)) return drifts;
  std::map<std::string, std::size_t> column_of;
  const auto header = split_csv_line(line);
  for (std::size_t c = 0; c < header.size(); ++c) column_of.emplace(bare_column_name(header[c]), c);
  std::vector<std::vector<std::string>> rows;
  while (std::getline(in, line))
    if (!line.empty()) rows.push_back(split_csv_line(line));
  for (const auto& item : averages.items()) {
    const Json& entry = item.value();
    const auto column = column_of.find(item.key());
    if (column == column_of.end() || !entry.is_object() || !entry.contains("samples") ||
        !entry["samples"].is_number_integer())
      continue;
    const long long samples = entry["samples"].get<long long>();
    if (samples < 2 || static_cast<std::size_t>(samples) > rows.size()) continue;
    const std::size_t n = static_cast<std::size_t>(samples), half = n / 2;
    const std::size_t first = rows.size() - n;
    double sum_early = 0, sum_late = 0;
    bool finite = true;
    for (std::size_t k = 0; k < half && finite; ++k) {
      const auto& early = rows[first + k];
      const auto& late = rows[rows.size() - half + k];
      const double a = column->second < early.size() ? parse_number(early[column->second]) : NAN;
      const double b = column->second < late.size() ? parse_number(late[column->second]) : NAN;
      finite = std::isfinite(a) && std::isfinite(b);
      sum_early += a;
      sum_late += b;
    }
    if (finite) drifts[item.key()] = (sum_late - sum_early) / static_cast<double>(half);
  }
  return drifts;
}

}  // namespace invasim::sweep
