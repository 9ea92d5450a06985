#include "sweep/collect.hpp"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "io/io_error.hpp"
#include "sweep/python_json.hpp"
#include "sweep/window_statistics.hpp"

namespace invasim::sweep {

namespace {

// A float as Python's repr writes it: the shortest text that reads back to the same double,
// always with a decimal point or an exponent (25.0, 0.0013, 1e-05), so that a float never
// reads like an integer; nan, inf and -inf as repr spells them.
std::string number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  return python_float_repr(value);
}

// A CSV cell: floats as Python's repr, integers without a decimal point (tau_p = 25 and
// tau_p = 25.0 are different points and stay different rows), booleans true/false, strings
// quoted if needed.
std::string cell(const Json& value) {
  if (value.is_null()) return "";
  if (value.is_number_float()) return number(value.get<double>());
  if (value.is_number()) return value.dump();
  if (value.is_boolean()) return value.get<bool>() ? "true" : "false";
  std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

// The units of series.csv's columns: "T_c [eps_c]" -> T_c: eps_c.
void read_units(const fs::path& series, std::map<std::string, std::string>& units) {
  std::ifstream in(series);
  std::string header;
  if (!std::getline(in, header)) return;
  std::stringstream columns(header);
  for (std::string column; std::getline(columns, column, ',');) {
    const std::string name = bare_column_name(column);
    if (name.size() + 3 <= column.size() && column.back() == ']')
      units.emplace(name, column.substr(name.size() + 2, column.size() - name.size() - 3));
  }
}

// The summary.json of a done point. Missing, malformed or not an object is an error naming
// the file, as a broken state point or job document is: a done row with empty cells would
// pass for a point that measured nothing.
Json read_summary(const std::string& id, const fs::path& dir) {
  const fs::path path = dir / "summary.json";
  try {
    Json summary = read_json(path);
    if (!summary.is_object()) fail_io(quoted(path), ": not a JSON object");
    return summary;
  } catch (const IoError& e) {
    fail_io("sweep collect: point ", id, " is done but its summary is unusable: ", e.what());
  }
}

// summary.json's `name` from its averages, or the top level (cells_only.lua writes tau_d
// there), when `is_kind` accepts it (a number, a flag); else null.
template <class Kind>
Json entry_of(const Json& summary, const std::string& name, Kind is_kind) {
  if (summary.contains("averages") && summary["averages"].contains(name) &&
      is_kind(summary["averages"][name]))
    return summary["averages"][name];
  if (summary.contains(name) && is_kind(summary[name])) return summary[name];
  return Json();
}
Json time_of(const Json& summary, const std::string& name) {
  return entry_of(summary, name, [](const Json& j) { return j.is_number(); });
}
Json flag_of(const Json& summary, const std::string& name) {
  return entry_of(summary, name, [](const Json& j) { return j.is_boolean(); });
}

std::string with_unit(const std::string& name, const std::map<std::string, std::string>& units,
                      const std::string& base) {
  const auto it = units.find(base);
  return it == units.end() ? name : name + " [" + it->second + "]";
}

}  // namespace

int collect(const Workspace& ws, std::ostream& out) {
  struct Row {
    std::string id, status;
    Json statepoint, document, summary;
    std::map<std::string, WindowStatistics> window;
  };
  std::vector<Row> rows;
  std::set<std::string> keys, averages;
  std::map<std::string, std::string> units;
  for (const auto& id : ws.ids()) {
    const fs::path dir = ws.job_dir(id);
    Row row{id, job_status(dir), ws.statepoint(id), read_document(dir), Json(), {}};
    for (const auto& item : row.statepoint.items()) keys.insert(item.key());
    if (row.status == "done") {
      row.summary = read_summary(id, dir);
      read_units(dir / "series.csv", units);
      if (row.summary.contains("averages")) {
        row.window = window_statistics(dir / "series.csv", row.summary["averages"]);
        for (const auto& item : row.summary["averages"].items())
          if (item.value().is_object() && item.value().contains("mean") &&
              item.value().contains("error"))
            averages.insert(item.key());
      }
    }
    rows.push_back(std::move(row));
  }
  out << "job_id,status,wall_seconds [s]";
  for (const auto& k : keys) out << ',' << k;
  for (const auto& a : averages) {
    // A measured average named as a sweep key (the compression's target phi and the measured
    // phi): its columns are measured_<name>, so that no two columns share a name.
    const std::string c = keys.count(a) ? "measured_" + a : a;
    out << ',' << with_unit(c, units, a) << ',' << with_unit(c + "_error", units, a) << ',' << c
        << "_error_converged," << with_unit(c + "_drift", units, a) << ','
        << with_unit(c + "_drift_error", units, a);
  }
  out << ",tau_d [tau],tau_r [tau],tau_d_unresolved\n";
  for (const auto& row : rows) {
    const bool done = row.status == "done";
    out << row.id << ',' << row.status << ','
        << (done && row.document.contains("wall_seconds") ? cell(row.document["wall_seconds"])
                                                          : "");
    for (const auto& k : keys)
      out << ',' << (row.statepoint.contains(k) ? cell(row.statepoint[k]) : "");
    for (const auto& a : averages) {
      Json entry;
      if (done && row.summary.contains("averages") && row.summary["averages"].contains(a))
        entry = row.summary["averages"][a];
      const bool ok = entry.is_object();
      const auto w = row.window.find(a);
      const bool in_window = w != row.window.end();
      // A summary without tau_int holds a blocking error: the window's is written instead.
      const bool recomputed = ok && !entry.contains("tau_int") && in_window;
      std::string error = ok && entry.contains("error") ? cell(entry["error"]) : "";
      std::string converged =
          ok && entry.contains("error_converged") && entry["error_converged"].is_boolean()
              ? (entry["error_converged"].get<bool>() ? "1" : "0")
              : "";
      if (recomputed) {
        error = number(w->second.error);
        converged = w->second.error_converged ? "1" : "0";
      }
      out << ',' << (ok && entry.contains("mean") ? cell(entry["mean"]) : "") << ',' << error << ','
          << converged << ',' << (in_window ? number(w->second.drift) : "") << ','
          << (in_window ? number(w->second.drift_error) : "");
    }
    const Json flag = done ? flag_of(row.summary, "tau_d_unresolved") : Json();
    const bool unresolved = flag.is_boolean() && flag.get<bool>();
    out << ',' << (done ? cell(time_of(row.summary, "tau_d")) : "") << ','
        << (done ? cell(time_of(row.summary, "tau_r")) : "") << ','
        << (done ? (unresolved ? "1" : "0") : "") << '\n';
  }
  return static_cast<int>(rows.size());
}

}  // namespace invasim::sweep
