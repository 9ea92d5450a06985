#pragma once
// `invasim sweep analyze WS [-o DIR] [master_curve.py options]`: collects the workspace into
// WS/results.csv and runs the master-curve analysis (scripts/master_curve.py, Debian's numpy,
// scipy and matplotlib) on it; its fit tables and figures go to DIR (default WS/analysis).
// Parameters the analysis needs (P, beta, gamma) that are not state-point columns are passed
// with --fixed at the protocol's declared defaults, so a spec need not repeat them.
#include <string>
#include <vector>

namespace invasim::app {

// args: the arguments after `analyze`. Returns the analysis' exit status.
int sweep_analyze(const std::vector<std::string>& args);

}  // namespace invasim::app
