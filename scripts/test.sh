#!/usr/bin/env bash
# Installs what is missing, builds, and runs the default test suite (everything but the
# "long" label; run those with: ctest --test-dir build -L long).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
ctest --test-dir build -LE long --output-on-failure -j1
