#!/usr/bin/env bash
# A run directory is locked for the life of its run (DIR/.lock, protocols/lib/run_dir.lua):
#  1. while a run holds it (paused inside its first checkpoint write by the test hook
#     INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE), a new run, an --overwrite run and a --resume
#     into the same directory are refused with exit 1, naming the directory and the holder's
#     pid, and no file of the running run changes;
#  2. after that run is killed with SIGKILL, the kernel has released its lock: --resume runs,
#     and removes (and logs) the temporary file the killed write left behind.
# Usage: run_dir_lock.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
cd "$here"
run=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
     --set steps=400 --set every=200 --set snapshot_every=0)
dir=$work/run

# 1. The holder: paused inside the write of checkpoint/compressed.ckpt (after params.json,
#    resume.txt and log.txt were written).
INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE=1 "$invasim" "${run[@]}" --out "$dir" > "$work/holder.log" 2>&1 &
pid=$!
wait_for $pid "the pause inside the first checkpoint write" grep -q "test hook: paused inside the write" "$work/holder.log"
snapshot() { (cd "$dir" && find . -type f | sort | xargs md5sum); }
snapshot > "$work/before.md5"
refused() {
  local name=$1 status=0
  shift
  "$invasim" "$@" > "$work/$name.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] || fail "$name exited with $status while the directory was locked (expected 1)" "$work/$name.log"
  grep -qF "$dir: the run directory is in use by another invasim run (pid $pid on host " "$work/$name.log" ||
    fail "$name: no message naming the directory and the holder (pid $pid)" "$work/$name.log"
  ! grep -q "^init:" "$work/$name.log" || fail "$name started working" "$work/$name.log"
}
refused new "${run[@]}" --set P=2e-3 --out "$dir"
refused overwrite "${run[@]}" --set P=2e-3 --out "$dir" --overwrite
refused resume run --resume "$dir"
snapshot > "$work/after.md5"
cmp -s "$work/before.md5" "$work/after.md5" || { diff "$work/before.md5" "$work/after.md5"; fail "a refused run changed the running run's files"; }

# 2. SIGKILL releases the lock; --resume removes the half-written temporary file.
kill -KILL $pid
wait $pid || true
tmp=$(cd "$dir" && ls checkpoint/compressed.ckpt.tmp.*) || fail "no temporary file left by the killed write"
"$invasim" run --resume "$dir" > "$work/resumed.log" 2>&1 || fail "--resume after SIGKILL" "$work/resumed.log"
grep -qF "run: removed 1 temporary file(s) of writes interrupted by a killed run in $dir: $tmp" "$dir/log.txt" ||
  fail "log.txt does not name the removed temporary file" "$dir/log.txt"
[ -z "$(find "$dir" -name '*.tmp.*')" ] || fail "temporary files left: $(find "$dir" -name '*.tmp.*')"
grep -q "^summary: results in" "$work/resumed.log" || fail "the resumed run did not finish" "$work/resumed.log"
echo "run_dir_lock passed: a locked run directory refused 3 other runs; after SIGKILL --resume ran and removed $tmp"
