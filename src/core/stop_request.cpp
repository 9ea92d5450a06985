#include "core/stop_request.hpp"

#include <csignal>

namespace invasim {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void record_stop(int signal) {
  g_stop_signal = signal;
  std::signal(signal, SIG_DFL);  // a second Ctrl-C ends the process at once
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, &record_stop);
  std::signal(SIGTERM, &record_stop);
}

int stop_requested() {
  return g_stop_signal;
}

void clear_stop_request() {
  g_stop_signal = 0;
}

const char* stop_signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "a signal";
}

}  // namespace invasim
