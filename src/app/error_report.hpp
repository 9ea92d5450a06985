#pragma once
// How a run that ended with an exception reports it on stderr: a clean stop by a signal (the
// protocol's own stop path: "stopped by SIGINT ...; checkpoint saved ...; continue with: ...")
// is not an error and reads "invasim: stopped by ..."; everything else, including a stop that
// the Lua stop hook forced ("file:line: stopped by ..."), reads "invasim: error: ...".
#include <exception>
#include <ostream>

namespace invasim::app {

void report_run_end(const std::exception& e, std::ostream& err);

}  // namespace invasim::app
