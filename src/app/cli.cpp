#include "app/cli.hpp"

#include <filesystem>

#include "app/options.hpp"
#include "app/resume_options.hpp"
#include "core/errors.hpp"
#include "io/text_format.hpp"

namespace invasim::app {

std::string help_text() {
  return R"(invasim: cancer cells invading adipose tissue, driven by Lua protocols

Usage:
  invasim run PROTOCOL.lua [options]     run a protocol
  invasim params PROTOCOL.lua [options]  list the protocol's parameters (default, unit,
                                         meaning) without running it
  invasim keys [NAME...]                 list the keys of the engine's constructors and
                                         methods (invasim.Contacts{...}, ...): type,
                                         default, allowed values, unit, meaning
  invasim render SNAPSHOT --slice z=VALUE -o FILE.svg [--size PIXELS]
                                         draw a cross-section of a snapshot frame as SVG
  invasim sweep init|run|status|collect|analyze|submit|job ...
                                         parameter sweeps: a workspace of runs, run here or
                                         on Slurm, collected into one table (invasim sweep
                                         --help; docs/sweeps.md)
  invasim --help                         this text
  invasim --version                      version and git revision

Options of run and params:
  --set key=value   override a parameter declared with invasim.params{...} (repeatable);
                    an undeclared key or a value of the wrong type is an error
  --seed S          same as --set seed=S (the protocol must declare `seed`)
  --out DIR         output directory, invasim.out_dir in scripts (default out/<protocol name>
                    followed by _key=value for each --set, e.g. out/invasion_P=2e-3)
  --threads N       number of OpenMP threads, 1 to 1024 (default: OMP_NUM_THREADS or all
                    cores)
  --traceback       on a Lua error, also print the Lua stack traceback
  --from RUN_DIR    start from the compressed tissue that run saved (invasim.from)
  --overwrite       the --out directory may hold another run: delete that run's files
                    (params.json, resume.txt, log.txt, series.csv, summary.json,
                    correlations.csv, shapes.csv, checkpoint/, snapshots/, plots/) and
                    start anew (without it, a protocol refuses a directory holding a run)
  invasim run --resume DIR [--threads N]
                    continue the run in DIR (killed, or stopped by Ctrl-C / SIGTERM) from
                    its last checkpoint, with the protocol, parameters and --from it was
                    started with; a checkpoint written by another run (other parameters) is
                    refused, and so is a --from source, protocol or params.json changed since
                    the start (docs/reliability.md); a run directory is locked (DIR/.lock) while
                    a run uses it: a second run into it is refused

Options of render:
  --slice A=VALUE   the cutting plane, x=VALUE, y=VALUE or z=VALUE (required)
  -o FILE.svg       the picture to write, also --output FILE (required; FILE.png needs
                    rsvg-convert from Debian's librsvg2-bin)
  --size PIXELS     length of the longer box side in the picture (default 800)
  SNAPSHOT is any file of one frame (cells_<step>.xyz, spheres_<step>.vtp or
  adipocytes_<step>.vtp); the other files of the same step next to it are read too.

Exit status: 0 on success, 1 on an error in the protocol, the run or the rendering,
2 on a bad command line.
See docs/lua.md for the Lua API and docs/output_formats.md for the pictures.
)";
}

namespace {

Command of_kind(Command::Kind kind) {
  Command command;
  command.kind = kind;
  return command;
}

// The command word: the first argument that is neither an option nor an option's value.
std::string command_word(const std::vector<std::string>& args) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (arg == "-o") {
      ++i;
    } else if (arg.rfind("--", 0) == 0) {
      static const char* const with_value[] = {"--set",     "--seed",   "--out",
                                               "--threads", "--slice",  "--size",
                                               "--output",  "--resume", "--from"};
      for (const char* name : with_value)
        if (arg == name) ++i;
    } else {
      return arg;
    }
  }
  return "";
}

double parse_size(const std::string& text) {
  const auto value = text::parse<double>(text);
  if (!value || !(*value > 0.0) || !(*value <= 1e5))
    throw UsageError("--size expects a number of pixels in (0, 100000], got '" + text + "'");
  return *value;
}

// out/<protocol stem>, then _key=value for each --set (and --seed) in command-line order, so
// that runs of a sweep get their own directories: out/invasion_P=2e-3_seed=7. Characters
// that do not belong in a file name become '-'.
std::string default_out_dir(const lua::RunOptions& options) {
  std::string name = std::filesystem::path(options.script_path).stem().string();
  auto append = [&](const std::string& key, const std::string& value) {
    std::string part = "_" + key + "=" + value;
    for (char& c : part)
      if (c == '/' || c == '\\' || c == ' ' || c == ':' || c == '*' || c == '?') c = '-';
    name += part;
  };
  for (const auto& o : options.overrides) append(o.key, o.text);
  if (options.seed) append("seed", *options.seed);
  return (std::filesystem::path("out") / name).string();
}

// `invasim render SNAPSHOT --slice A=VALUE -o FILE.svg [--size PIXELS]`.
Command parse_render(const std::vector<std::string>& args) {
  Command command = of_kind(Command::Kind::kRender);
  RenderOptions& render = command.render;
  const ParsedOptions p = parse_options(
      args, {{"--slice", "--output", "--size"},
             {},
             {},
             "",
             "render",
             {{"--out", "invasim render writes one file: give it with -o FILE.svg, not --out"}}});
  if (p.help || p.version) return of_kind(p.help ? Command::Kind::kHelp : Command::Kind::kVersion);
  const std::vector<std::string>& positional = p.positional;
  const auto slice = p.value("--slice"), output = p.value("--output"), size = p.value("--size");
  if (positional.size() < 2)
    throw UsageError(
        "invasim render: missing SNAPSHOT (a cells_*.xyz, spheres_*.vtp or adipocytes_*.vtp "
        "file)");
  if (positional.size() > 2)
    throw UsageError("invasim render: unexpected argument '" + positional[2] + "'");
  render.snapshot = positional[1];
  if (!slice) throw UsageError("invasim render: missing --slice x=VALUE, y=VALUE or z=VALUE");
  try {
    render.plane = parse_slice_plane(*slice);
  } catch (const InputError&) {
    throw UsageError("--slice expects x=VALUE, y=VALUE or z=VALUE, got '" + *slice + "'");
  }
  if (!output) throw UsageError("invasim render: missing -o FILE.svg");
  if (output->empty()) throw UsageError("-o needs a file name");
  render.output = *output;
  if (size) render.size_px = parse_size(*size);
  return command;
}

// --threads N with N in [1, kMaxThreads]: more threads than any node has cores is a typo.
int parse_threads(const std::string& text) {
  const auto value = text::parse<int>(text);
  if (!value || *value < 1)
    throw UsageError("--threads expects a positive integer, got '" + text + "'");
  if (*value > kMaxThreads)
    throw UsageError("--threads must be in [1, " + std::to_string(kMaxThreads) + "], got '" + text +
                     "'");
  return *value;
}

}  // namespace

Command parse_command_line(const std::vector<std::string>& args) {
  if (command_word(args) == "render") return parse_render(args);
  if (command_word(args) == "keys") {  // invasim keys [NAME...]: no options
    Command command = of_kind(Command::Kind::kKeys);
    for (std::size_t i = 1; i < args.size(); ++i) {
      if (args[i] == "-h" || args[i] == "--help") return of_kind(Command::Kind::kHelp);
      if (args[i].rfind("-", 0) == 0)
        throw UsageError("invasim keys takes type names only, not '" + args[i] + "'");
      command.keys_of.push_back(args[i]);
    }
    return command;
  }
  const ParsedOptions p =
      parse_options(args, {{"--set", "--seed", "--out", "--threads", "--resume", "--from"},
                           {"--overwrite", "--traceback"},
                           {"--set"},
                           ""});
  if (p.help || p.version) return of_kind(p.help ? Command::Kind::kHelp : Command::Kind::kVersion);
  Command command;
  command.traceback = p.flag("--traceback");
  command.options.overwrite = p.flag("--overwrite");
  if (p.values.count("--set"))
    for (const auto& text : p.values.at("--set")) try {
        command.options.overrides.push_back(parse_override(text));
      } catch (const InputError& e) {
        throw UsageError(e.what());
      }
  command.options.seed = p.value("--seed");
  const auto out = p.value("--out"), resume = p.value("--resume");
  if (out && out->empty()) throw UsageError("--out needs a directory");
  if (resume && resume->empty()) throw UsageError("--resume needs a run directory");
  command.options.from_dir = p.value("--from").value_or("");
  if (p.values.count("--from") && command.options.from_dir.empty())
    throw UsageError("--from needs a run directory");
  if (const auto threads = p.value("--threads")) command.threads = parse_threads(*threads);
  const std::vector<std::string>& positional = p.positional;
  if (positional.empty()) throw UsageError("missing command (run, params, keys, render or sweep)");
  const std::string& verb = positional[0];
  if (verb == "run")
    command.kind = Command::Kind::kRun;
  else if (verb == "params")
    command.kind = Command::Kind::kParams;
  else if (verb == "help")
    return of_kind(Command::Kind::kHelp);
  else
    throw UsageError("unknown command '" + verb +
                     "' (expected run, params, keys, render or sweep)");
  if (resume) {
    if (command.kind != Command::Kind::kRun) throw UsageError("--resume goes with invasim run");
    if (positional.size() > 1)
      throw UsageError(
          "invasim run --resume DIR takes no PROTOCOL.lua (the run directory names it)");
    if (!command.options.overrides.empty() || command.options.seed || out ||
        !command.options.from_dir.empty())
      throw UsageError(
          "--resume continues a run with its own parameters: --set, --seed, --out and --from "
          "cannot be combined with it");
    if (command.options.overwrite)
      throw UsageError(
          "--resume continues the run in its directory, --overwrite deletes it: choose one");
    try {
      command.options = read_resume_options(*resume);
    } catch (const InputError& e) {
      throw UsageError(e.what());
    }
    return command;
  }
  if (positional.size() < 2) throw UsageError("invasim " + verb + ": missing PROTOCOL.lua");
  if (positional.size() > 2)
    throw UsageError("invasim " + verb + ": unexpected argument '" + positional[2] + "'");
  if (command.options.overwrite && command.kind != Command::Kind::kRun)
    throw UsageError("--overwrite goes with invasim run");
  command.options.script_path = positional[1];
  command.options.list_params = command.kind == Command::Kind::kParams;
  command.options.out_dir = out ? *out : default_out_dir(command.options);
  return command;
}

}  // namespace invasim::app
