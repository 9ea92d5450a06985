#!/usr/bin/env bash
# A sweep point run under Slurm copies its output to run.log through a pipe (app/tee_output).
# A protocol that leaves a background child holding that pipe must not keep the point from
# ending: `sweep job` exits within seconds (the child sleeps 60 s; before, the job waited for
# it), and run.log and the job's own output both hold the protocol's line.
# Usage: sweep_job_background_child.sh INVASIM SPEC_DIR WORK_DIR
set -euo pipefail
invasim=$1 specs=$2 work=$3
source "$(dirname "$0")/../lua/wait_for.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"
"$invasim" sweep init "$specs/background_child.lua" --workspace ws > /dev/null
id=$(ls ws/workspace)
status=0
SLURM_JOB_ID=1 timeout 30 "$invasim" sweep job ws "$id" --threads 1 > job.log 2>&1 || status=$?
pkill -x -f "sleep 59.9" || true
[ $status -eq 0 ] || fail "sweep job exited $status (124: still waiting after 30 s)" job.log
grep -q "background_child: started a child" "ws/workspace/$id/run.log" ||
  fail "run.log lacks the protocol's output" "ws/workspace/$id/run.log"
grep -q "background_child: started a child" job.log || fail "the job's output lacks it" job.log
echo "sweep_job_background_child: the point ended while its child ran on"
