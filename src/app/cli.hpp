#pragma once
// The command line of the `invasim` executable:
//   invasim run PROTOCOL.lua [--set key=value ...] [--out DIR] [--threads N] [--seed S]
//   invasim params PROTOCOL.lua [--set key=value ...] [--seed S]
//   invasim render SNAPSHOT --slice x|y|z=VALUE -o FILE.svg [--size PIXELS]
//   invasim --help | --version
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/slice.hpp"
#include "lua/context.hpp"

namespace invasim::app {

// A malformed command line (exit code 2, with a pointer to --help).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// `invasim render`: a slice picture of one snapshot frame (io/render_slice.hpp).
struct RenderOptions {
  std::string snapshot;  // any file of the frame: cells_*.xyz, spheres_*.vtp, adipocytes_*.vtp
  SlicePlane plane;      // --slice x=|y=|z=VALUE
  std::string output;    // -o / --output FILE.svg
  double size_px = 800;  // --size PIXELS: the longer box side in the picture
};

// The largest --threads accepted (more than any node has cores: a typo, not a request).
constexpr int kMaxThreads = 1024;

struct Command {
  enum class Kind { kRun, kParams, kHelp, kVersion, kRender, kKeys };
  Kind kind = Kind::kHelp;
  lua::RunOptions options;           // script path, --set, --seed, --out
  std::optional<int> threads;        // --threads N
  bool traceback = false;            // --traceback: print the Lua stack on errors
  RenderOptions render;              // kRender only
  std::vector<std::string> keys_of;  // kKeys: the types to list (empty: all)
};

// Parses argv (without argv[0]); throws UsageError. --out defaults to out/<protocol stem>.
Command parse_command_line(const std::vector<std::string>& args);

std::string help_text();

}  // namespace invasim::app
