#!/usr/bin/env bash
# The sanitizer job (run by .ci/run after the Release suite; docs/reliability.md): builds a
# second build directory, build-sanitize, with -DINVASIM_SANITIZE=address,undefined and runs
# under it, from the default suite (ctest -LE long):
#   - every Catch2 unit test (test_*: test_io_render and test_sweep_ids included), and
#   - the Lua/CLI tests (cli_*) except the slow protocol runs named in $slow below (minutes
#     each under the sanitizers; the Release suite runs them);
# not the app_*, io_*, analysis_*, validation_*, regression_* and fuzz_* tests (--all runs
# those too). A finding exits with its own status (ASan and LSan 86, UBSan 87; a refused input
# exits 1, a bad command line 2), and any test whose output holds a report fails
# (FAIL_REGULAR_EXPRESSION, tests/CMakeLists.txt).
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
# ASan) checks leaks at exit and exits with ASan's exitcode; UBSan (built into the same runtime)
# reads its own exitcode from UBSAN_OPTIONS.
# Suppressions, each justified there: scripts/ubsan.supp, scripts/lsan.supp.
here=$(pwd)
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_stack_use_after_return=0:exitcode=86"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:exitcode=87:suppressions=$here/scripts/ubsan.supp"
export LSAN_OPTIONS="suppressions=$here/scripts/lsan.supp"
if [ "${1:-}" = "--all" ]; then
  ctest --test-dir "$build" -LE long --output-on-failure -j2
else
  # Slow protocol runs (minutes each under the sanitizers), covered by the Release suite. The
  # exclusion applies to the cli_ tests only: every unit test runs.
  slow='resume_after_kill|identical_runs|tethers_at_compression|doc_example|temporary_contacts'
  slow+='|checkpoint_continuation|stale_checkpoint|from_|run_from|production_|packing_drift'
  slow+='|stages_|protocol_'
  ctest --test-dir "$build" -LE long -R '^(test_|cli_)' -E "^cli_.*($slow)" --output-on-failure -j2
fi
