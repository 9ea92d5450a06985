#pragma once
// Graceful stop on SIGINT / SIGTERM (Ctrl-C, a batch system's wall-time kill): the handler
// only records the signal; long runs check stop_requested() between chunks of steps, write a
// checkpoint and stop cleanly. A second signal of the same kind kills the process at once
// (the default action is restored after the first).
//
// A request is "taken" once a stop point has seen it (stop_requested() returned the signal:
// the step loop of Simulation::run, a stoppable FIRE, invasim.interrupted()). Lua's stop hook
// (lua/stop_hook.hpp) peeks at the request with stop_signal_pending() and gives a request that
// no stop point has taken only a short time before it ends the script itself.
namespace invasim {

// Installs the handlers (idempotent), and ignores SIGPIPE (a closed output pipe must not kill
// a run: its writes to that pipe fail, its files are written).
void install_stop_handlers();
// The signal that asked for a stop (SIGINT, SIGTERM), or 0. A stop point's check: a nonzero
// answer marks the request as taken.
int stop_requested();
// The recorded signal, or 0, without taking the request (the Lua stop hook).
int stop_signal_pending();
// Whether a stop point has seen the recorded request, or a StopPathWork is running (the stop
// point that follows it will).
bool stop_request_taken();

// Marks, for its lifetime, work that a stop point runs before its next check and that must
// not be cut short: a checkpoint being composed and written (its Lua state included, which
// grows with the run). A request arriving meanwhile counts as taken, so Lua's stop hook allows
// it the long grace. Lua code runs on one thread: the depth is a plain counter.
class StopPathWork {
 public:
  StopPathWork();
  ~StopPathWork();
  StopPathWork(const StopPathWork&) = delete;
  StopPathWork& operator=(const StopPathWork&) = delete;
};
// Forgets a recorded request (tests).
void clear_stop_request();
// "SIGINT", "SIGTERM" or "signal N".
const char* stop_signal_name(int signal);

}  // namespace invasim
