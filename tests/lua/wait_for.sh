# Sourced by the kill-and-resume tests: wait for an event, not for a time.
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
