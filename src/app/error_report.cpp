#include "app/error_report.hpp"

#include <string_view>

#include "core/stop_request.hpp"

namespace invasim::app {

void report_run_end(const std::exception& e, std::ostream& err) {
  const std::string_view message = e.what();
  const bool clean_stop = stop_signal_pending() != 0 && message.rfind("stopped by ", 0) == 0;
  err << (clean_stop ? "invasim: " : "invasim: error: ") << message << '\n';
}

}  // namespace invasim::app
