// What protocols/lib/run_dir.lua needs to keep a run directory to one run (src/io):
//   invasim.lock_run_dir(dir)        -- true, or false and the holder ("pid 12 on host h,
//                                    -- started ...") if another process holds DIR/.lock
//   invasim.record_run_lock(dir)     -- writes this process into DIR/.lock (lock held)
//   invasim.hash_file(path)          -- FNV-1a 64 of the file's bytes, as 16 hex digits
//   invasim.remove_temporaries(dir)  -- removes the "*.tmp.<pid>" files of killed atomic
//                                    -- writes in dir's tree; returns their relative paths
#include <lua.hpp>

#include <optional>
#include <string>
#include <vector>

#include "core/fnv1a.hpp"
#include "io/atomic_file.hpp"
#include "io/run_lock.hpp"
#include "lua/engine_types.hpp"
#include "lua/module.hpp"

namespace invasim::lua {

namespace {

int l_lock_run_dir(lua_State* L) {
  const std::string dir = arg_path(L, 1);
  const std::optional<std::string> holder =
      engine_call("lock_run_dir", [&] { return lock_run_directory(dir); });
  if (!holder) {
    lua_pushboolean(L, 1);
    return 1;
  }
  return push_results(L, 2, [&holder](lua_State* S) noexcept {
    lua_pushboolean(S, 0);
    lua_pushlstring(S, holder->data(), holder->size());
    return 2;
  });
}

}  // namespace

void open_run_dir(lua_State* L) {
  add_functions(
      L, {INVASIM_LUA_FN(lock_run_dir),
          method<"record_run_lock", [](Path dir) { record_run_lock_holder(dir.value); }>(),
          method<"hash_file", [](Path path) { return fnv1a64_hex(read_file(path.value)); }>(),
          method<"remove_temporaries", [](Path dir) {
            std::vector<std::string> removed;
            for (const auto& path : remove_atomic_temporaries(dir.value))
              removed.push_back(path.string());
            return removed;
          }>()});
}

}  // namespace invasim::lua
