#!/usr/bin/env bash
# Test: SIGTERM inside the rescale stage's FIRE stops the run at the next FIRE
# iteration with a message saying that the rescale is not checkpointed and what --resume does.
# The run waits for the signal at a test hook inside the FIRE
# (INVASIM_TEST_PAUSE_IN_RESCALE_FIRE=50, src/setup/test_hooks.hpp); the FIRE must stop right
# there, at iteration 50 (an operation count, not a time: the FIRE used to run on to
# max_steps).
# Usage: stop_in_rescale.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
log=$work/log.txt
cd "$here"
INVASIM_TEST_PAUSE_IN_RESCALE_FIRE=50 "$invasim" run stop_in_rescale.lua > "$log" 2>&1 &
pid=$!
wait_for $pid "pause inside the rescale's FIRE" grep -q "test hook: paused in the rescale's FIRE before iteration 50" "$log"
kill -TERM $pid
# A guard against a hang only (the FIRE ignoring the signal runs on to max_steps).
for _ in $(seq 600); do kill -0 $pid 2> /dev/null || break; sleep 0.1; done
if kill -0 $pid 2> /dev/null; then
  kill -KILL $pid
  fail "still running 60 s after SIGTERM inside the rescale's FIRE" "$log"
fi
status=0
wait $pid || status=$?
[ "$status" -eq 1 ] || fail "exit status $status (expected 1)" "$log"
grep -q "stopped by SIGTERM during the rescale's FIRE at iteration 50 .*no checkpoint is written during the rescale" "$log" ||
  fail "no stop message naming iteration 50 (the FIRE did not stop at its next iteration)" "$log"
echo "stop_in_rescale: SIGTERM inside the rescale's FIRE stopped the run at the next iteration"
