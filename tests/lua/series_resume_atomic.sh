#!/usr/bin/env bash
# Test: a resumed run rewrites series.csv (its header and the rows the checkpoint holds)
# atomically, so a resume that fails while writing it (here a file-size limit, as a full disk or
# a quota would) leaves the previous series.csv whole instead of truncated; a resume whose first
# checkpoint write fails (ENOSPC, the test hook of io/test_hooks.hpp) names the checkpoint it
# resumed from as the last good one; a later resume then finishes the run.
# Usage: series_resume_atomic.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
. ./wait_for.sh
args=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
      --set steps=20000 --set every=10 --set snapshot_every=0 --set checkpoint_every=2000
      --set correlate_every=0)
"$invasim" "${args[@]}" --out "$work/run" > "$work/killed.log" 2>&1 &
pid=$!
checkpoint_written() {
  grep -q "^production: checkpoint of step [0-9]* written" "$work/run/log.txt" 2> /dev/null
}
wait_for "$pid" "the first production checkpoint" checkpoint_written || fail "no checkpoint" "$work/killed.log"
stop_with_sigterm "$pid" "$work/killed.log" "the run"
cp "$work/run/series.csv" "$work/series_before.csv"
series=$(stat -c %s "$work/series_before.csv")
log=$(stat -c %s "$work/run/log.txt")
# A limit (in KiB) below the series' size but well above the log's, which the resume appends to.
limit=$((series / 1024 - 2))
[ $((limit * 1024)) -gt $((log + 8192)) ] || fail "series.csv ($series bytes) too small beside log.txt ($log)"
if (trap '' XFSZ; ulimit -f "$limit"; "$invasim" run --resume "$work/run") > "$work/limited.log" 2>&1; then
  fail "the resume under a $limit KiB file-size limit succeeded" "$work/limited.log"
fi
cmp "$work/series_before.csv" "$work/run/series.csv" ||
  fail "series.csv changed by the failed resume ($(stat -c %s "$work/run/series.csv") of $series bytes)" "$work/limited.log"
stopped=$(grep -o "stopped by SIGTERM at step [0-9]*" "$work/killed.log" | grep -o "[0-9]*$")
if INVASIM_TEST_FAIL_CHECKPOINT_WRITE=1 "$invasim" run --resume "$work/run" > "$work/nospace.log" 2>&1; then
  fail "a resume whose checkpoint write failed succeeded" "$work/nospace.log"
fi
grep -q "last good checkpoint: $work/run/checkpoint/state.ckpt (step $stopped)" "$work/nospace.log" ||
  fail "the failed resume does not name the checkpoint of step $stopped" "$work/nospace.log"
"$invasim" run --resume "$work/run" > "$work/resumed.log" 2>&1 || fail "resume" "$work/resumed.log"
rows=$(($(wc -l < "$work/run/series.csv") - 1))
[ "$rows" -eq 2000 ] || fail "series.csv has $rows rows after the resume, not 2000"
echo "series_resume_atomic: series.csv ($series bytes) whole after a resume failed under a $limit KiB limit"
