#include "app/sweep_analyze.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "app/cli.hpp"
#include "core/errors.hpp"
#include "io/atomic_file.hpp"
#include "sweep/collect.hpp"
#include "sweep/spec.hpp"
#include "sweep/workspace.hpp"

#ifndef INVASIM_SOURCE_DIR
#define INVASIM_SOURCE_DIR "."
#endif

namespace invasim::app {

namespace fs = std::filesystem;

namespace {

// The analysis script: $INVASIM_SCRIPTS_DIR/master_curve.py, else the source tree's.
fs::path analysis_script() {
  const char* dir = std::getenv("INVASIM_SCRIPTS_DIR");
  const fs::path script =
      fs::path(dir && *dir ? dir : INVASIM_SOURCE_DIR "/scripts") / "master_curve.py";
  if (!fs::exists(script))
    fail_input("sweep analyze: the analysis script ", script.string(),
               " is missing (set INVASIM_SCRIPTS_DIR to the directory holding master_curve.py)");
  return script;
}

// Debian's python3 (with python3-numpy, -scipy, -matplotlib) when present.
std::string python() {
  return ::access("/usr/bin/python3", X_OK) == 0 ? "/usr/bin/python3" : "python3";
}

// "K=V" text of a declared parameter's default (floats as Python's repr: they round-trip).
std::string default_text(const Param& p) {
  return p.name + "=" + sweep::set_text(sweep::to_json(p.default_value));
}

// Runs argv, returns its exit status (128 + signal if it was killed).
int run_child(const std::vector<std::string>& argv) {
  std::vector<char*> c_argv;
  for (const auto& a : argv) c_argv.push_back(const_cast<char*>(a.c_str()));
  c_argv.push_back(nullptr);
  std::cout << std::flush;
  const pid_t pid = ::fork();
  if (pid < 0) fail_input("sweep analyze: cannot start ", argv[0]);
  if (pid == 0) {
    ::execvp(c_argv[0], c_argv.data());
    std::cerr << "invasim: sweep analyze: cannot run " << argv[0] << '\n';
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

int sweep_analyze(const std::vector<std::string>& args) {
  std::string ws_arg, out;
  std::vector<std::string> passed;  // options for master_curve.py
  std::string fixed;                // the user's --fixed, merged with the defaults
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const bool with_value = a == "-o" || a == "--out" || a == "--fixed";
    if (with_value && i + 1 >= args.size()) throw UsageError(a + " needs a value");
    if (a == "-o" || a == "--out") {
      out = args[++i];
    } else if (a == "--fixed") {
      fixed = args[++i];
    } else if (a.rfind("--fixed=", 0) == 0) {
      fixed = a.substr(8);
    } else if (a.rfind("-", 0) != 0 && ws_arg.empty()) {
      ws_arg = a;
    } else {
      passed.push_back(a);
    }
  }
  if (ws_arg.empty())
    throw UsageError(
        "invasim sweep analyze: expected a workspace directory (invasim sweep analyze WS [-o "
        "DIR] [options of scripts/master_curve.py])");
  const auto ws = sweep::Workspace::open(ws_arg);
  if (out.empty()) out = (ws.root() / "analysis").string();

  std::ostringstream table;
  const int rows = sweep::collect(ws, table);
  const fs::path results = ws.root() / "results.csv";
  write_file_atomically(results, table.str());
  std::cout << "sweep analyze: " << rows << " rows in " << results.string() << '\n';

  // The parameters the fits use, at the protocol's defaults where the sweep does not set them.
  std::set<std::string> columns;
  for (const auto& id : ws.ids()) {
    const sweep::Json statepoint = ws.statepoint(id);
    for (const auto& item : statepoint.items()) columns.insert(item.key());
  }
  std::set<std::string> given;
  for (std::size_t at = 0; at < fixed.size();) {
    const auto comma = fixed.find(',', at);
    const std::string pair = fixed.substr(at, comma == std::string::npos ? fixed.npos : comma - at);
    given.insert(pair.substr(0, pair.find('=')));
    at = comma == std::string::npos ? fixed.size() : comma + 1;
  }
  const auto declared = sweep::protocol_params(ws.protocol());
  for (const char* name : {"P", "beta", "gamma"}) {
    if (columns.count(name) || given.count(name)) continue;
    if (const Param* p = sweep::find_param(declared, name)) {
      if (!fixed.empty()) fixed += ',';
      fixed += default_text(*p);
    }
  }

  std::vector<std::string> argv = {python(), analysis_script().string(), results.string(), "-o",
                                   out};
  if (!fixed.empty()) {
    argv.push_back("--fixed");
    argv.push_back(fixed);
  }
  argv.insert(argv.end(), passed.begin(), passed.end());
  std::cout << "sweep analyze:";
  for (const auto& a : argv) std::cout << ' ' << a;
  std::cout << '\n';
  return run_child(argv);
}

}  // namespace invasim::app
