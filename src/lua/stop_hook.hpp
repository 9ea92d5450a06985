#pragma once
// The stop hook: a Lua count hook that lets SIGINT/SIGTERM end a script that runs Lua code
// only (an endless loop, a loop in a callback), which the engine's stop points never see.
//
// A stop request is offered to the engine first: its stop points (Simulation::run's step
// loop, a stoppable FIRE or compression, invasim.interrupted()) take it and the protocol then
// stops gracefully (checkpoint, "stopped by SIGTERM at step N ..."), running whatever Lua code
// its stop path needs. The hook raises the Lua error "stopped by SIGTERM ..." only when
// - no stop point has taken the request kUntakenGrace after Lua code first ran with it
//   pending (the Lua code between two engine calls, a callback, normally takes microseconds),
// - or a stop point took it but Lua code still runs kTakenGrace after that (a protocol that
//   ignores the stop, e.g. calling sim:run in an endless loop).
// Once due, the error is raised again at every hook call, so a pcall cannot swallow it.
// Docs: docs/reliability.md, "Scripts that never end, ...".
#include <chrono>

struct lua_State;

namespace invasim::lua {

// Lua VM instructions between two calls of the hook.
inline constexpr int kStopHookInstructions = 10000;
inline constexpr std::chrono::milliseconds kUntakenGrace{1000};
inline constexpr std::chrono::milliseconds kTakenGrace{30000};

// Installs the hook on L (threads created from L afterwards inherit it).
void install_stop_hook(lua_State* L);

}  // namespace invasim::lua
