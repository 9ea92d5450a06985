#include "core/stop_request.hpp"

#include <atomic>
#include <csignal>

namespace invasim {

namespace {

volatile std::sig_atomic_t g_stop_signal = 0;
std::atomic<bool> g_taken{false};  // set by stop_requested(), never by the handler
int g_stop_path_work = 0;          // StopPathWork objects alive

// A second Ctrl-C (SIGINT) ends the process at once. A repeated SIGTERM only records the stop
// again: batch systems and the wrappers that forward their signals (a job script, srun) may
// deliver it twice, and the first one's checkpoint must still be written.
extern "C" void record_stop(int signal) {
  g_stop_signal = signal;
  if (signal == SIGINT) std::signal(signal, SIG_DFL);
}

}  // namespace

void install_stop_handlers() {
  std::signal(SIGINT, &record_stop);
  std::signal(SIGTERM, &record_stop);
  // A closed output pipe (`invasim run ... | tee log`, the tee ended by the same Ctrl-C) makes
  // writes to it fail instead of killing the run before its stop path saved anything.
  std::signal(SIGPIPE, SIG_IGN);
}

int stop_requested() {
  const int signal = g_stop_signal;
  if (signal != 0) g_taken.store(true, std::memory_order_relaxed);
  return signal;
}

int stop_signal_pending() {
  return g_stop_signal;
}

bool stop_request_taken() {
  return g_stop_signal != 0 && (g_taken.load(std::memory_order_relaxed) || g_stop_path_work > 0);
}

StopPathWork::StopPathWork() {
  ++g_stop_path_work;
}
StopPathWork::~StopPathWork() {
  --g_stop_path_work;
}

void clear_stop_request() {
  g_stop_signal = 0;
  g_taken.store(false, std::memory_order_relaxed);
}

const char* stop_signal_name(int signal) {
  if (signal == SIGINT) return "SIGINT";
  if (signal == SIGTERM) return "SIGTERM";
  return "a signal";
}

}  // namespace invasim
