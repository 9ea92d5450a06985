#!/usr/bin/env bash
# Test: one SIGTERM ends a script that runs Lua code only (the stop hook, lua/stop_hook.hpp):
# an endless loop at the top level and one inside an engine callback each end with exit status
# 1 and "stopped by SIGTERM" naming the script's line, within 10 s; a stop the engine took
# first keeps its own stop path, even when that path runs Lua code for 2 s, and a second
# SIGTERM 0.5 s into that path (a batch system or a wrapper repeating it) does not cut it short;
# a SIGTERM while a checkpoint's Lua state takes 2 s lets that checkpoint finish.
# Usage: stop_endless_loop.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
cd "$here"

# stop CASE WAIT_TEXT EXPECT [OUT]: runs the case, sends one SIGTERM once WAIT_TEXT was
# printed (and a second one 0.5 s later when OUT is given: the run's directory and log name),
# and checks the exit status, the time to exit and the message.
stop() {
  local case=$1 wait_text=$2 expect=$3 out=${4:-$1} status=0
  local log=$work/$out.txt
  "$invasim" run stop_endless_loop.lua --set case="$case" --out "$work/$out" > "$log" 2>&1 &
  local pid=$!
  wait_for $pid "'$wait_text'" grep -q "$wait_text" "$log"
  local start
  start=$(date +%s.%N)
  kill -TERM $pid
  if [ -n "${4:-}" ]; then sleep 0.5 && kill -TERM $pid; fi
  # A guard against the old behaviour (the first SIGTERM was ignored): give up after 60 s.
  for _ in $(seq 600); do kill -0 $pid 2> /dev/null || break; sleep 0.1; done
  if kill -0 $pid 2> /dev/null; then
    kill -KILL $pid
    fail "$case: still running 60 s after SIGTERM" "$log"
  fi
  wait $pid || status=$?
  local seconds
  seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
  [ "$status" -eq 1 ] || fail "$case: exit status $status (expected 1)" "$log"
  grep -q -- "$expect" "$log" || fail "$case: no message matching '$expect'" "$log"
  awk -v s="$seconds" 'BEGIN { exit !(s < 10) }' || fail "$case: exited $seconds s after SIGTERM (limit 10 s)" "$log"
  echo "stop_endless_loop: $case stopped in $seconds s"
}

stop loop "stop_endless_loop: looping" \
  "^invasim: error: stop_endless_loop.lua:29: stopped by SIGTERM while the script ran Lua code with no stop point of the engine"
stop callback "stop_endless_loop: looping in a callback" \
  "^invasim: error: stop_endless_loop.lua:34: stopped by SIGTERM while the script ran Lua code with no stop point of the engine"
stop graceful "stop_endless_loop: running" \
  "^invasim: stopped by SIGTERM after the script's own stop path"
grep -q "stop_endless_loop: the stop path finished" "$work/graceful.txt" ||
  fail "graceful: the script's stop path was cut short" "$work/graceful.txt"
stop graceful "stop_endless_loop: running" \
  "^invasim: stopped by SIGTERM after the script's own stop path" graceful_twice
grep -q "stop_endless_loop: the stop path finished" "$work/graceful_twice.txt" ||
  fail "graceful: a second SIGTERM cut the script's stop path short" "$work/graceful_twice.txt"
# The signal during a checkpoint's slow Lua state (2 s, past the hook's 1 s for a stop that no
# stop point took): the checkpoint is finished, then the stop point takes the signal.
stop checkpoint "stop_endless_loop: composing a slow checkpoint" \
  "^invasim: stopped by SIGTERM at step 200; the slow checkpoint finished"
echo "stop_endless_loop: one SIGTERM ended every Lua loop; the engine's stop path kept"
