#include "app/cli.hpp"

#include <charconv>
#include <filesystem>

#include "core/errors.hpp"

namespace invasim::app {

std::string help_text() {
  return R"(invasim: cancer cells invading adipose tissue, driven by Lua protocols

Usage:
  invasim run PROTOCOL.lua [options]     run a protocol
  invasim params PROTOCOL.lua [options]  list the protocol's parameters (default, unit,
                                         meaning) without running it
  invasim --help                         this text
  invasim --version                      version and git revision

Options:
  --set key=value   override a parameter declared with invasim.params{...} (repeatable);
                    an undeclared key or a value of the wrong type is an error
  --seed S          same as --set seed=S (the protocol must declare `seed`)
  --out DIR         output directory, invasim.out_dir in scripts (default out/<protocol name>)
  --threads N       number of OpenMP threads (default: OMP_NUM_THREADS or all cores)
  --traceback       on a Lua error, also print the Lua stack traceback

Exit status: 0 on success, 1 on an error in the protocol or the run, 2 on a bad command line.
See docs/lua.md for the Lua API.
)";
}

namespace {

int parse_threads(const std::string& text) {
  int value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size() || value < 1)
    throw UsageError("--threads expects a positive integer, got '" + text + "'");
  return value;
}

}  // namespace

Command parse_command_line(const std::vector<std::string>& args) {
  Command command;
  std::vector<std::string> positional;
  std::optional<std::string> out;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string arg = args[i];
    if (arg == "-h" || arg == "--help") return Command{Command::Kind::kHelp, {}, {}, false};
    if (arg == "--version") return Command{Command::Kind::kVersion, {}, {}, false};
    if (arg.rfind("--", 0) != 0 || arg == "--") {
      if (arg == "--") throw UsageError("unexpected '--'");
      positional.push_back(arg);
      continue;
    }
    // --name value or --name=value
    std::string name = arg, value;
    bool has_value = false;
    if (const auto eq = arg.find('='); eq != std::string::npos) {
      name = arg.substr(0, eq);
      value = arg.substr(eq + 1);
      has_value = true;
    }
    if (name == "--traceback") {
      if (has_value) throw UsageError("--traceback takes no value");
      command.traceback = true;
      continue;
    }
    if (name != "--set" && name != "--seed" && name != "--out" && name != "--threads")
      throw UsageError("unknown option '" + name + "'");
    if (!has_value) {
      if (i + 1 >= args.size()) throw UsageError(name + " needs a value");
      value = args[++i];
    }
    if (name == "--set") {
      try {
        command.options.overrides.push_back(lua::parse_override(value));
      } catch (const InputError& e) {
        throw UsageError(e.what());
      }
    } else if (name == "--seed") {
      if (command.options.seed) throw UsageError("--seed given twice");
      command.options.seed = value;
    } else if (name == "--out") {
      if (value.empty()) throw UsageError("--out needs a directory");
      out = value;
    } else {
      command.threads = parse_threads(value);
    }
  }
  if (positional.empty()) throw UsageError("missing command (run or params)");
  const std::string& verb = positional[0];
  if (verb == "run")
    command.kind = Command::Kind::kRun;
  else if (verb == "params")
    command.kind = Command::Kind::kParams;
  else if (verb == "help")
    return Command{Command::Kind::kHelp, {}, {}, false};
  else
    throw UsageError("unknown command '" + verb + "' (expected run or params)");
  if (positional.size() < 2) throw UsageError("invasim " + verb + ": missing PROTOCOL.lua");
  if (positional.size() > 2)
    throw UsageError("invasim " + verb + ": unexpected argument '" + positional[2] + "'");
  command.options.script_path = positional[1];
  command.options.list_params = command.kind == Command::Kind::kParams;
  command.options.out_dir =
      out ? *out
          : (std::filesystem::path("out") / std::filesystem::path(positional[1]).stem()).string();
  return command;
}

}  // namespace invasim::app
