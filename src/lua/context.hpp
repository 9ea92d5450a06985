#pragma once
// What the command line hands to a protocol script, and what the script declares back. One
// ScriptContext lives in each LuaState; bindings reach it through script_context(L).
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/params.hpp"

struct lua_State;

namespace invasim::lua {

// Options from `invasim run|params`: --set overrides (in command-line order), --seed, --out.
struct RunOptions {
  std::string script_path;
  std::vector<Override> overrides;
  std::optional<std::string> seed;  // --seed S: sets the declared parameter `seed`
  std::string out_dir;              // exposed to scripts as invasim.out_dir
  bool list_params = false;         // `invasim params`: stop at invasim.params{...}
  bool resume = false;              // --resume DIR: continue the run in out_dir (invasim.resume)
  std::string from_dir;    // --from RUN_DIR: start from its compressed tissue (invasim.from)
  bool overwrite = false;  // --overwrite: a new run may replace the run in out_dir
                           // (invasim.overwrite)
  // The command that continues this run after a stop, when it is not `invasim run --resume
  // DIR` (a sweep's point: `invasim sweep run WS`); invasim.continue_command, else nil.
  std::string continue_command;
};

// Per-state shared data: the options in, the declared parameters out.
struct ScriptContext {
  RunOptions options;
  std::optional<std::vector<Param>> params;  // set once invasim.params{...} has run
};

// The context of the LuaState that owns L (a light userdata in the registry; defined in
// lua_state.cpp).
ScriptContext& script_context(lua_State* L);

}  // namespace invasim::lua
