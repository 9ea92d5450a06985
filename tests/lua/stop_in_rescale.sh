#!/usr/bin/env bash
# Test (issue 14): SIGTERM inside the rescale stage's FIRE stops the run within a few seconds
# with a message saying that the rescale is not checkpointed and what --resume does.
# Usage: stop_in_rescale.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
log=$work/log.txt
cd "$here"
"$invasim" run stop_in_rescale.lua > "$log" 2>&1 &
pid=$!
wait_for $pid "rescale" grep -q "stop_in_rescale: rescaling" "$log"
sleep 1  # inside the FIRE (it never converges)
start=$(date +%s.%N)
status=0
kill -TERM $pid
# A guard against the old behaviour (the FIRE ran to max_steps): give up after 60 s.
for _ in $(seq 600); do kill -0 $pid 2> /dev/null || break; sleep 0.1; done
if kill -0 $pid 2> /dev/null; then
  kill -KILL $pid
  fail "still running 60 s after SIGTERM inside the rescale's FIRE" "$log"
fi
wait $pid || status=$?
seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
[ "$status" -eq 1 ] || fail "exit status $status (expected 1)" "$log"
grep -q "stopped by SIGTERM during the rescale's FIRE at iteration [0-9]*.*no checkpoint is written during the rescale" "$log" ||
  fail "no stop message" "$log"
awk -v s="$seconds" 'BEGIN { exit !(s < 5) }' || fail "exited $seconds s after SIGTERM (limit 5 s)" "$log"
echo "stop_in_rescale: SIGTERM inside the rescale's FIRE stopped the run in $seconds s"
