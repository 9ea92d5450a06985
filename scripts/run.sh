#!/usr/bin/env bash
# Installs what is missing, builds, and runs the main job: protocols/invasion.lua with its
# embedded defaults (the reduced system: about 15 seconds on 2 cores), printing progress and a
# final summary; results in out/invasion/. Extra arguments go to `invasim run`, e.g.
#   bash scripts/run.sh --set system=paper --out runs/paper
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
# Without arguments this is the demo: it replaces the previous demo's results in out/invasion
# (--overwrite). With arguments, they are passed on unchanged (a run into a directory that
# holds another run is then refused unless --overwrite is among them).
if [ $# -eq 0 ]; then set -- --overwrite; fi
exec build/invasim run protocols/invasion.lua "$@"
