#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: protocols/invasion.lua with its
# embedded defaults (the reduced system: about a minute on 2 cores), printing progress and a
# final summary; results in out/invasion/. Extra arguments go to `invasim run`, e.g.
#   bash scripts/run.sh --set system=paper --out runs/paper
# A second run into out/invasion is refused (it holds the first run's results); run again with
#   bash scripts/run.sh --overwrite
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
exec build/invasim run protocols/invasion.lua "$@"
