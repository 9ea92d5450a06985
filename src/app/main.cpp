// invasim: the command-line driver. Parses the command line, runs (or lists the parameters
// of) a Lua protocol or renders a snapshot slice, and turns every error into one line on
// stderr and a nonzero exit code.
#include <omp.h>
#include <lua.hpp>

#include <exception>
#include <iostream>

#include "app/cli.hpp"
#include "app/error_report.hpp"
#include "app/render_command.hpp"
#include "app/sweep_command.hpp"
#include "core/errors.hpp"
#include "core/names.hpp"
#include "core/wait_policy.hpp"
#include "invasim_version.hpp"
#include "lua/fields.hpp"
#include "lua/lua_state.hpp"

namespace {

using invasim::app::Command;

std::string version_text() {
  std::string text = std::string("invasim ") + invasim::kInvasimVersion;
  if (*invasim::kInvasimGitRevision)
    text += std::string(" (git ") + invasim::kInvasimGitRevision + ")";
  return text + "\n" LUA_RELEASE "\n";
}

// After a complete run: --set/--seed given to a protocol that never declared parameters.
void check_overrides_used(const Command& command, const invasim::lua::ScriptContext& context) {
  const auto& options = command.options;
  if (context.params || (options.overrides.empty() && !options.seed)) return;
  invasim::fail_input(options.script_path, " never called invasim.params{...}, so ",
                      options.seed ? "--seed" : "--set " + options.overrides[0].key + "=...",
                      " cannot apply");
}

int list_params(const Command& command) {
  invasim::lua::LuaState state(command.options);
  state.run_file(command.options.script_path);
  const auto& context = state.context();
  if (!context.params) {
    std::cout << command.options.script_path
              << " declares no parameters (it never calls invasim.params{...})\n";
    return 0;
  }
  std::cout << "Parameters of " << command.options.script_path
            << " (change with --set name=value):\n"
            << invasim::format_param_table(*context.params);
  return 0;
}

// `invasim keys [NAME...]`: the field tables of the engine's bindings (lua/fields.hpp).
int list_keys(const Command& command) {
  invasim::lua::LuaState state;
  state.run_string("require('invasim')");
  const auto& tables = invasim::lua::registered_field_tables();
  std::vector<std::string> names = command.keys_of;
  if (names.empty())
    for (const auto& [name, infos] : tables) names.push_back(name);
  std::vector<std::string> all;
  for (const auto& [name, infos] : tables) all.push_back(name);
  for (const auto& name : names) {
    const auto it = tables.find(name);
    if (it == tables.end())
      invasim::fail_input("invasim keys: no type or method '", name, "'",
                          invasim::did_you_mean(name, all), "; known: ", invasim::join_names(all));
    std::cout << name << ":\n" << invasim::lua::format_field_table(it->second);
  }
  return 0;
}

int run(const Command& command) {
  if (command.threads) omp_set_num_threads(*command.threads);
  invasim::lua::LuaState state(command.options);
  state.run_file(command.options.script_path);
  check_overrides_used(command, state.context());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  invasim::use_passive_wait_policy_by_default(argv);
  bool traceback = false;
  const bool sweep = argc > 1 && std::string(argv[1]) == "sweep";
  try {
    if (sweep)
      return invasim::app::run_sweep_command(std::vector<std::string>(argv + 2, argv + argc));
    const Command command =
        invasim::app::parse_command_line(std::vector<std::string>(argv + 1, argv + argc));
    traceback = command.traceback;
    switch (command.kind) {
      case Command::Kind::kHelp:
        std::cout << invasim::app::help_text();
        return 0;
      case Command::Kind::kVersion:
        std::cout << version_text();
        return 0;
      case Command::Kind::kParams:
        return list_params(command);
      case Command::Kind::kRun:
        return run(command);
      case Command::Kind::kKeys:
        return list_keys(command);
      case Command::Kind::kRender:
        return invasim::app::run_render(command.render, std::cout);
    }
  } catch (const invasim::app::UsageError& e) {
    // "invasim sweep run: ..." names the program already; the hint names the help that lists
    // the command's options.
    const std::string what = e.what();
    std::cerr << (what.rfind("invasim ", 0) == 0 ? "" : "invasim: ") << what << " (see invasim "
              << (sweep ? "sweep " : "") << "--help)\n";
    return 2;
  } catch (const invasim::lua::ScriptError& e) {
    invasim::app::report_run_end(e, std::cerr);
    if (traceback && !e.traceback().empty()) std::cerr << e.traceback() << '\n';
    return 1;
  } catch (const std::exception& e) {
    invasim::app::report_run_end(e, std::cerr);
    return 1;
  }
  return 1;
}
