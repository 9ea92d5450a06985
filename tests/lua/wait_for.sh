# Sourced by the kill-and-resume tests: wait for an event, not for a time; stop a run as a
# batch system would; report a failure.
# wait_for PID DESCRIPTION COMMAND...: polls COMMAND every 0.1 s until it succeeds. Fails
# (naming the event that never came) if process PID ends first, or after WAIT_LIMIT seconds
# (default 1200: a guard against hangs only, never a timing assumption).
wait_for() {
  local pid=$1 what=$2
  shift 2
  local limit=${WAIT_LIMIT:-1200}
  local start=$SECONDS
  until "$@"; do
    if ! kill -0 "$pid" 2> /dev/null; then
      echo "FAILED: the run ended before $what"
      return 1
    fi
    if ((SECONDS - start > limit)); then
      echo "FAILED: no $what after ${limit} s (the run still runs: a hang?)"
      return 1
    fi
    sleep 0.1
  done
}

# fail MESSAGE [LOG]: prints the failure (and the log, if given) and exits 1.
fail() {
  echo "FAILED: $1"
  [ -n "${2:-}" ] && cat "$2"
  exit 1
}

# stop_with_sigterm PID LOG WHAT: sends SIGTERM to the run PID and waits for it; a run stopped
# by a signal exits with status 1, anything else fails naming WHAT and showing LOG.
stop_with_sigterm() {
  local pid=$1 log=$2 what=$3 status=0
  kill -TERM "$pid"
  wait "$pid" || status=$?
  [ "$status" -eq 1 ] || fail "$what exited with $status (expected 1)" "$log"
}
