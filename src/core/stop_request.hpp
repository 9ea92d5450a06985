#pragma once
// Graceful stop on SIGINT / SIGTERM (Ctrl-C, a batch system's wall-time kill): the handler
// only records the signal; long runs check stop_requested() between chunks of steps, write a
// checkpoint and stop cleanly. A second signal of the same kind kills the process at once
// (the default action is restored after the first).
namespace invasim {

// Installs the handlers (idempotent).
void install_stop_handlers();
// The signal that asked for a stop (SIGINT, SIGTERM), or 0.
int stop_requested();
// Forgets a recorded request (tests).
void clear_stop_request();
// "SIGINT", "SIGTERM" or "signal N".
const char* stop_signal_name(int signal);

}  // namespace invasim
