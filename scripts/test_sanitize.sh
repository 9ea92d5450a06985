#!/usr/bin/env bash
# The sanitizer job (issue 14; run by .ci/run after the Release suite): builds a second
# build directory, build-sanitize, with
# -DINVASIM_SANITIZE=address,undefined and runs a fast subset of the default suite under it
# (every unit test and the Lua/CLI tests, less the long kill-and-resume and full-protocol runs;
# budget about 15 minutes on 2 cores with a warm ccache, not yet measured). The first ASan or
# UBSan finding fails the run.
# Usage: scripts/test_sanitize.sh [--all]   (--all: the whole default suite, ctest -LE long)
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-sanitize
launcher=()
command -v ccache > /dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DINVASIM_SANITIZE=address,undefined \
  "${launcher[@]}" > /dev/null
cmake --build "$build" -j"$(nproc)"
# halt_on_error: the first finding ends the process (and fails its test). LeakSanitizer (part of
# ASan) checks leaks at exit.
# Suppressions, each justified there: scripts/ubsan.supp, scripts/lsan.supp.
here=$(pwd)
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=0"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:suppressions=$here/scripts/ubsan.supp"
export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp"
if [ "${1:-}" = "--all" ]; then
  ctest --test-dir "$build" -LE long --output-on-failure -j2
else
  # Slow protocol runs (minutes each under the sanitizers), covered by the Release suite.
  slow='resume_after_kill|identical_runs|tethers_at_compression|doc_example|temporary_contacts'
  slow+='|checkpoint_continuation|stale_checkpoint|from_|run_from|production_|packing_drift'
  slow+='|sweep|render|plot|stages_|protocol_'
  ctest --test-dir "$build" -LE long -R '^(test_|cli_)' -E "$slow" --output-on-failure -j2
fi
