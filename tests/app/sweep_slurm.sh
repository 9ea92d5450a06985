#!/usr/bin/env bash
# `invasim sweep submit --slurm` against a real Slurm: starts a private single-node Slurm
# (Debian 12's Slurm 22.05: munge, slurmctld and slurmd with private state directories and
# free ports; only the processes this script started are stopped, by their pids, also on
# failure), submits tests/app/sweeps/tiny.lua (shared preparation chained before the array
# with --dependency=afterok), stops the array with SIGTERM once a point has written a
# checkpoint (as a time limit does), submits again (the stopped points continue from their
# checkpoints), waits until every point is done, and compares each point's series.csv and
# summary.json (timings aside) with a local `sweep run` of the same sweep, byte for byte;
# then a sweep whose preparation fails: the dependent array is cancelled, the points are
# pending again with the reason in `status`, and `submit` submits them again.
# Where Slurm's or munge's binaries are missing or not root: skipped (77), or a failure under
# INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.sh).
# Usage: sweep_slurm.sh INVASIM SPEC_DIR WORK_DIR
set -euo pipefail
invasim=$1 specs=$2 work=$3
source "$(dirname "$0")/../support/prerequisites.sh"
for b in slurmctld slurmd sbatch squeue sinfo scancel munged munge unmunge; do
  command -v $b > /dev/null || PATH=$PATH:/usr/sbin command -v $b > /dev/null ||
    skip_test "$b is not installed" "slurm-wlm munge"
done
[ "$(id -u)" = 0 ] || skip_test "starting munged and slurmd needs root" "slurm-wlm munge"
export PATH=$PATH:/usr/sbin
source "$(dirname "$0")/../lua/wait_for.sh"
# within SECONDS WHAT COMMAND...: polls COMMAND every 0.1 s until it succeeds; fails naming
# WHAT if it has not happened after SECONDS (a bound against a hang, e.g. a dependency that is
# never satisfied; far above the few seconds each event takes).
within() {
  local limit=$1 what=$2 start=$SECONDS
  shift 2
  until "$@"; do
    ((SECONDS - start <= limit)) || fail "$what did not happen within $limit s" "$work/slurmctld.log"
    sleep 0.1
  done
}
rm -rf "$work" && mkdir -p "$work/state" "$work/spool" && cd "$work"

munged_pid=
cleanup() {
  for f in slurmd.pid slurmctld.pid; do
    [ -s "$work/$f" ] && kill "$(cat "$work/$f")" 2> /dev/null || true
  done
  [ -n "$munged_pid" ] && kill "$munged_pid" 2> /dev/null || true
}
trap cleanup EXIT

# 1. munge, unless one already answers.
if ! munge -n 2> /dev/null | unmunge > /dev/null 2>&1; then
  install -d -o munge -g munge -m 0755 /run/munge
  runuser -u munge -- /usr/sbin/munged
  munged_pid=$(cat /run/munge/munged.pid)
  munge -n | unmunge > /dev/null || fail "munge does not work"
fi

# 2. slurm.conf with two free ports.
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')
cat > slurm.conf <<CONF
ClusterName=invasim-test
SlurmctldHost=localhost
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
MaxArraySize=500
CONF
export SLURM_CONF=$work/slurm.conf

# 3. The daemons; wait until the node is idle.
slurmctld -f "$SLURM_CONF" > slurmctld.log 2>&1
slurmd -f "$SLURM_CONF" -N localhost > slurmd.log 2>&1
node_idle() { [ "$(sinfo -h -o %t 2> /dev/null)" = idle ]; }
within 60 "the Slurm node becoming idle" node_idle

# 4. Submit; stop the array once a point has a checkpoint; submit again; wait.
# The points stopped by a signal run 100000 steps (seconds, not tiny.lua's milliseconds): a
# point whose checkpoint was seen is still running when the signal arrives.
long=(--set steps=100000 --set checkpoint_every=2000)
"$invasim" sweep init "$specs/tiny.lua" --workspace ws "${long[@]}" > /dev/null
# --max-requeues 0: a stopped point waits for the next submit (section 8 tests the requeue).
"$invasim" sweep submit ws --slurm --cpus-per-task 1 --time 10 --max-requeues 0 > submit1.log ||
  fail submit submit1.log
grep -q "after job" submit1.log || fail "the preparation was not chained before the array" submit1.log
grep -q "dependency\|afterok" ws/slurm/submit-1/array.sbatch && fail "dependency belongs on the command line"
array=$(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit1.log)
[ -n "$array" ] || fail "no array job id in the submit output" submit1.log
queue_holds() { [ -n "$(squeue -h -j "$1" 2> /dev/null)" ]; }
queue_empty() { ! queue_holds "$1"; }
# A point's checkpoint while the array still runs: the array ending first (every point done
# without being stopped) would leave nothing to resume, and fails.
checkpoint_or_end() {
  ls ws/workspace/*/checkpoint/state.ckpt > /dev/null 2>&1 || ! queue_holds "$array"
}
within 300 "a point's checkpoint (or the end of array $array)" checkpoint_or_end
ls ws/workspace/*/checkpoint/state.ckpt > /dev/null 2>&1 ||
  fail "array $array ended before any point wrote a checkpoint" submit1.log
queue_holds "$array" || fail "array $array ended before it could be stopped: nothing to resume"
# scancel's status is not its effect (it can report an error for a step that has just ended):
# the effect is checked, the array ending within the bound below.
scancel --signal=TERM --full "$array" 2> scancel.log || echo "scancel: $(cat scancel.log)"
within 120 "the end of array $array after scancel --signal=TERM" queue_empty "$array"
"$invasim" sweep status ws > status1.log
cat status1.log
# Points started before the preparation had saved its tissue would have failed.
grep -q "failed: 0" status1.log || { cat ws/workspace/*/run.log; fail "points failed in the first array" status1.log; }
"$invasim" sweep submit ws --slurm --cpus-per-task 1 > submit2.log || fail "second submit" submit2.log
cat submit2.log
array2=$(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit2.log)
[ -n "$array2" ] || fail "the second submit started no array" submit2.log
within 600 "the end of the second array $array2" queue_empty "$array2"
"$invasim" sweep status ws > status2.log
grep -q "done: 4" status2.log || { cat ws/slurm/submit-*/slurm-*.out; fail "not every point is done" status2.log; }
grep -q '"slurm_job_id"' ws/workspace/*/signac_job_document.json || fail "no Slurm job id recorded"
# A task's slurm-%A_%a.out holds the point's own output (as its run.log does), not a pointer.
grep -l "results in" ws/slurm/submit-2/slurm-*_*.out > /dev/null ||
  fail "no slurm-%A_%a.out holds its point's output" "$(ls ws/slurm/submit-2/slurm-*_*.out | head -1)"

# 5. The same sweep locally (1 thread per point, as --cpus-per-task 1).
"$invasim" sweep init "$specs/tiny.lua" --workspace local "${long[@]}" > /dev/null
"$invasim" sweep run local --jobs 2 --threads 1 > local.log 2>&1 || fail "local run" local.log
for dir in ws/workspace/*; do
  id=$(basename "$dir")
  cmp "$dir/series.csv" "local/workspace/$id/series.csv" || fail "point $id: series.csv differs"
  diff <(grep -v '"seconds"\|wall_clock_seconds' "$dir/summary.json") \
       <(grep -v '"seconds"\|wall_clock_seconds' "local/workspace/$id/summary.json") > /dev/null ||
    fail "point $id: summary.json differs"
  n=$(grep -c "results in" "$dir/run.log" || true)
  [ "$n" -eq 1 ] || fail "point $id completed $n times" "$dir/run.log"
done
# At least one point stopped by the scancel continued from its checkpoint.
resumed=$(grep -l 'resuming the run' ws/workspace/*/run.log 2> /dev/null | wc -l)
[ "$resumed" -ge 1 ] || fail "no point resumed from its checkpoint on Slurm" status2.log
echo "resumed on Slurm: $resumed points"

# 6. A failing preparation: its dependent array is cancelled (not left pending forever), the
#    points are pending again with the reason in status, and submit submits them again.
"$invasim" sweep init "$specs/failing_prep.lua" --workspace badprep > /dev/null
"$invasim" sweep submit badprep --slurm --cpus-per-task 1 > submit3.log || fail submit submit3.log
array3=$(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit3.log)
[ -n "$array3" ] || fail "no array job id for the failing preparation's sweep" submit3.log
prep_failed() { grep -q '"status": "failed"' badprep/prep/signac_job_document.json; }
within 120 "the preparation's failure" prep_failed
within 60 "the end of array $array3 after its preparation failed" queue_empty "$array3"
"$invasim" sweep status badprep > status3.log
grep -q "pending: 2" status3.log || fail "the cancelled points are not pending" status3.log
grep -q "cancelled: 2 pending points whose Slurm array was cancelled: the shared preparation failed (Slurm job [0-9]*, log .*badprep/prep/run.log)" status3.log ||
  fail "status does not say why the points wait" status3.log
"$invasim" sweep submit badprep --slurm --cpus-per-task 1 > submit4.log || fail submit4 submit4.log
grep -q "shared preparation: Slurm job" submit4.log && grep -q "2 points as Slurm job array" submit4.log ||
  fail "the second submit did not submit the preparation and the points again" submit4.log
array4=$(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit4.log)
within 120 "the end of the resubmitted array $array4" queue_empty "$array4"

# 7. Arrays within MaxArraySize: the cluster's (500 in slurm.conf) read by submit; with
#    --max-array-size 3 the 4 points go as two arrays (3 + 1 tasks), which finish them all.
"$invasim" sweep init "$specs/tiny.lua" --workspace split > /dev/null
"$invasim" sweep submit split --slurm --dry-run > dry.log || fail "dry run" dry.log
grep -q "1 array script(s) .*(4 points, at most 500 per array)" dry.log ||
  fail "submit did not read MaxArraySize = 500 from the cluster" dry.log
rm -rf split/slurm
"$invasim" sweep submit split --slurm --cpus-per-task 1 --max-array-size 3 > submit5.log ||
  fail "split submit" submit5.log
[ "$(grep -c "points as Slurm job array" submit5.log)" -eq 2 ] &&
  grep -q "^sweep submit: 3 points as Slurm job array" submit5.log &&
  grep -q "^sweep submit: 1 points as Slurm job array" submit5.log ||
  fail "4 points with --max-array-size 3 are not two arrays of 3 and 1" submit5.log
grep -q -- "--array=0-2" split/slurm/submit-1/array-1.sbatch &&
  grep -q -- "--array=0-0" split/slurm/submit-1/array-2.sbatch || fail "the array scripts' ranges"
for a in $(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit5.log); do
  within 600 "the end of array $a" queue_empty "$a"
done
"$invasim" sweep status split > status5.log
grep -q "done: 4" status5.log || fail "the split arrays did not finish every point" status5.log

# 8. Resources and the time limit's warning. Named options reach the scripts (the preparation
#    its own); bad values are refused naming the option; a point stopped by SIGTERM (what
#    --signal=B:TERM@S sends before the limit) requeues itself and finishes, no submit needed.
"$invasim" sweep init "$specs/tiny.lua" --workspace res "${long[@]}" > /dev/null
if "$invasim" sweep submit res --slurm --dry-run --mem 4X > badmem.log 2>&1; then
  fail "--mem 4X was accepted" badmem.log
fi
grep -q "\-\-mem '4X' is not a memory size" badmem.log || fail "the refusal names no option" badmem.log
if "$invasim" sweep submit res --slurm --dry-run --time 1h > badtime.log 2>&1; then
  fail "--time 1h was accepted" badtime.log
fi
grep -q "\-\-time '1h' is not a Slurm time" badtime.log || fail "--time refusal" badtime.log
"$invasim" sweep submit res --slurm --dry-run --time 2:00:00 --mem 4G --account lab_1 \
  --qos normal --prep-time 30 --prep-mem 8G --prep-cpus-per-task 2 > dry2.log || fail dry2 dry2.log
a=res/slurm/submit-1/array.sbatch p=res/slurm/submit-1/prep.sbatch
grep -qx "#SBATCH --time=2:00:00" $a && grep -qx "#SBATCH --mem=4G" $a &&
  grep -qx "#SBATCH --account=lab_1" $a && grep -qx "#SBATCH --qos=normal" $a &&
  grep -qx "#SBATCH --cpus-per-task=1" $a || fail "the array's resources" $a
grep -qx "#SBATCH --time=30" $p && grep -qx "#SBATCH --mem=8G" $p &&
  grep -qx "#SBATCH --cpus-per-task=2" $p && grep -qx "#SBATCH --account=lab_1" $p ||
  fail "the preparation's own resources" $p
grep -qx "#SBATCH --signal=B:TERM@300" $a && grep -qx "#SBATCH --requeue" $a &&
  grep -q "sweep job .* --max-requeues 3$" $a || fail "the time limit's warning and requeue" $a
rm -rf res/slurm
"$invasim" sweep submit res --slurm --cpus-per-task 1 --time 10 --signal-before 120 > submit6.log ||
  fail "submit with requeues" submit6.log
array6=$(sed -n 's/.*Slurm job array \([0-9]*\).*/\1/p' submit6.log)
grep -qx "#SBATCH --signal=B:TERM@120" res/slurm/submit-1/array.sbatch || fail "--signal-before 120"
res_checkpoint_or_end() {
  ls res/workspace/*/checkpoint/state.ckpt > /dev/null 2>&1 || ! queue_holds "$array6"
}
within 300 "a point's checkpoint (or the end of array $array6)" res_checkpoint_or_end
queue_holds "$array6" || fail "array $array6 ended before it could be signalled"
scancel --signal=TERM --batch "$array6" 2> scancel6.log || echo "scancel: $(cat scancel6.log)"
requeued() { grep -q '"requeues": 1' res/workspace/*/signac_job_document.json 2> /dev/null; }
within 120 "a point requeuing itself" requeued
# Slurm holds a requeued job back for a while (its begin time); start it now, as the test
# checks what runs after the requeue, not Slurm's delay.
nudge_or_end() {
  queue_empty "$array6" && return 0
  scontrol update JobId="$array6" StartTime=now > /dev/null 2>&1 || true
  return 1
}
within 600 "the end of array $array6 after its requeues" nudge_or_end
"$invasim" sweep status res > status6.log
grep -q "done: 4" status6.log || { cat res/workspace/*/run.log; fail "requeued points did not finish" status6.log; }
grep -l '"requeues": 1' res/workspace/*/signac_job_document.json > /dev/null ||
  fail "no point recorded a requeue" status6.log
grep -q "requeued as Slurm job ${array6}_[0-9]* (requeue 1 of 3)" res/workspace/*/run.log ||
  fail "no point logged its requeue" status6.log

# 9. The guard where flock does not reach across nodes: a point whose document says it runs as
#    a Slurm job that the queue shows RUNNING is refused by `sweep job` (exit 75) although its
#    lock is free here, and `sweep run` lists it as running elsewhere.
"$invasim" sweep init "$specs/tiny.lua" --workspace guard > /dev/null
other=$(sbatch --parsable --wrap "sleep 300" | cut -d';' -f1)
other_running() { [ "$(squeue -h -j "$other" -o %T 2> /dev/null)" = RUNNING ]; }
within 60 "the other Slurm job $other running" other_running
gid=$(ls guard/workspace | head -1)
echo "{\"status\": \"running\", \"slurm_job_id\": \"$other\", \"host\": \"node-b\"}" \
  > "guard/workspace/$gid/signac_job_document.json"
status=0
"$invasim" sweep job guard "$gid" > guard_job.log 2>&1 || status=$?
[ $status -eq 75 ] || fail "sweep job on a point running elsewhere exited $status, not 75" guard_job.log
grep -q "is running as Slurm job $other on node-b" guard_job.log || fail "the guard's message" guard_job.log
status=0
"$invasim" sweep run guard --jobs 2 --threads 1 > guard_run.log 2>&1 || status=$?
[ $status -eq 1 ] && grep -q "^  ${gid:0:8} (.*): running elsewhere (Slurm job $other, pid -1 on node-b" guard_run.log ||
  fail "sweep run did not list the guarded point as running elsewhere" guard_run.log
scancel "$other"
echo "sweep slurm: OK"
