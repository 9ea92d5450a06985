#include "lua/stop_hook.hpp"

#include <lua.hpp>

#include "core/stop_request.hpp"

namespace invasim::lua {

namespace {

// When the hook first saw the current request (Lua code runs on one thread only).
bool g_seen = false;
std::chrono::steady_clock::time_point g_first_seen;

// The count hook. Plain C-style code: lua_error longjmps out of it, so its frame owns no C++
// object with a destructor.
void stop_hook(lua_State* L, lua_Debug* ar) {
  const int signal = stop_signal_pending();
  if (signal == 0) {
    g_seen = false;
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!g_seen) {
    g_seen = true;
    g_first_seen = now;
  }
  const bool taken = stop_request_taken();
  if (now - g_first_seen < (taken ? kTakenGrace : kUntakenGrace)) return;
  const char* name = stop_signal_name(signal);
  lua_getinfo(L, "Sl", ar);
  if (ar->currentline > 0)
    lua_pushfstring(L, "%s:%d: ", ar->short_src, ar->currentline);
  else
    lua_pushliteral(L, "");
  if (taken)
    lua_pushfstring(L,
                    "stopped by %s: the protocol still ran Lua code %d s after the engine "
                    "stopped for the signal (a loop that ignores invasim.interrupted()?); "
                    "nothing saved after the last checkpoint",
                    name, int(kTakenGrace.count() / 1000));
  else
    lua_pushfstring(L,
                    "stopped by %s while the script ran Lua code with no stop point of the "
                    "engine (an endless loop?); nothing saved after the last checkpoint",
                    name);
  lua_concat(L, 2);
  lua_error(L);
}

}  // namespace

void install_stop_hook(lua_State* L) {
  lua_sethook(L, &stop_hook, LUA_MASKCOUNT, kStopHookInstructions);
}

}  // namespace invasim::lua
