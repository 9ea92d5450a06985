#include "sweep/window_statistics.hpp"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <vector>

#include "measure/mean_error.hpp"
#include "measure/quarter_drift.hpp"

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

std::map<std::string, WindowStatistics> window_statistics(const fs::path& series,
                                                          const Json& averages) {
  std::map<std::string, WindowStatistics> out;
  std::ifstream in(series);
  std::string line;
  if (!averages.is_object() || !std::getline(in, line)) return out;
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
    std::vector<double> window;
    for (std::size_t k = rows.size() - static_cast<std::size_t>(samples); k < rows.size(); ++k) {
      const auto& row = rows[k];
      window.push_back(column->second < row.size() ? parse_number(row[column->second]) : NAN);
      if (!std::isfinite(window.back())) break;
    }
    if (window.size() != static_cast<std::size_t>(samples) || !std::isfinite(window.back()))
      continue;
    // The halves are the window's last 2 floor(n/2) rows, as the steady-state test's; their
    // difference is written also at 1 row per half, where it has no error.
    const QuarterDrift d = quarter_drift(window);
    const double drift =
        d.quarter >= 2 ? d.drift : window[window.size() - 1] - window[window.size() - 2];
    const MeanError m = mean_error(window);
    out[item.key()] = {drift, d.error, m.error, m.resolved};
  }
  return out;
}

}  // namespace invasim::sweep
