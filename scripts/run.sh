#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job. Until the Lua protocol layer lands
# (protocols/invasion.lua, issue 3) the main job is the engine demonstration: the benchmark
# workloads, a few hundred steps each, printing throughput in particle-steps per second.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
if [ -x build/invasim ] && [ -f protocols/invasion.lua ]; then
  exec build/invasim run protocols/invasion.lua "$@"
fi
exec build/tests/bench/bench_engine "${1:-300}"
