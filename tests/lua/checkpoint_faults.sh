#!/usr/bin/env bash
# Test: faults that lose nothing.
#  1. SIGKILL inside a checkpoint write (paused there by INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE)
#     leaves the previous state.ckpt byte for byte and loadable.
#  2. A write failing with ENOSPC (INVASIM_TEST_FAIL_CHECKPOINT_WRITE, as on a full disk) stops
#     the run with a message naming the file and the last good checkpoint, which stays valid,
#     and leaves no temporary file.
#  3. An output directory that cannot be written is refused before any work starts (a path
#     under a regular file; as root, also a read-only tmpfs: without root or mount, that case
#     is dropped, or fails under INVASIM_REQUIRE_ALL_TESTS=1, tests/support/prerequisites.sh).
# Usage: checkpoint_faults.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
source "$here/../support/prerequisites.sh"
rm -rf "$work" && mkdir -p "$work"
cd "$here"

# 1. SIGKILL inside the second checkpoint write.
log=$work/kill.log
INVASIM_TEST_PAUSE_IN_CHECKPOINT_WRITE=2 "$invasim" run checkpoint_faults.lua --out "$work/kill" > "$log" 2>&1 &
pid=$!
wait_for $pid "pause inside the second checkpoint write" grep -q "test hook: paused inside the write" "$log"
ckpt=$work/kill/checkpoint/state.ckpt
cp "$ckpt" "$work/before_kill.ckpt"
ls "$ckpt".tmp.* > /dev/null 2>&1 || fail "no half-written temporary file during the pause" "$log"
kill -KILL $pid
status=0
wait $pid || status=$?
[ "$status" -eq 137 ] || fail "the run paused in its checkpoint write exited with $status (expected 137: SIGKILL)" "$log"
cmp -s "$ckpt" "$work/before_kill.ckpt" || fail "state.ckpt changed by the killed write" "$log"
"$invasim" run checkpoint_faults.lua --set check="$ckpt" > "$work/load1.log" 2>&1 ||
  fail "the previous checkpoint does not load after SIGKILL" "$work/load1.log"
grep -q "at step 200$" "$work/load1.log" || fail "wrong step" "$work/load1.log"

# 2. ENOSPC in the second checkpoint write.
log=$work/nospace.log
status=0
INVASIM_TEST_FAIL_CHECKPOINT_WRITE=2 "$invasim" run checkpoint_faults.lua --out "$work/nospace" > "$log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "a failed checkpoint write exited with $status (expected 1)" "$log"
ckpt=$work/nospace/checkpoint/state.ckpt
grep -q "cannot write '$ckpt': write failed: No space left on device.*last good checkpoint: $ckpt (step 200)" "$log" ||
  fail "no message naming the file and the last good checkpoint" "$log"
! ls "$ckpt".tmp.* > /dev/null 2>&1 || fail "a temporary file was left behind" "$log"
"$invasim" run checkpoint_faults.lua --set check="$ckpt" > "$work/load2.log" 2>&1 ||
  fail "the last good checkpoint does not load after the failed write" "$work/load2.log"
grep -q "at step 200$" "$work/load2.log" || fail "wrong step" "$work/load2.log"

# 3. Unwritable output directories: refused before any work (no "init:" line).
touch "$work/a_file"
refused() {
  local out=$1 status=0
  "$invasim" run ../../protocols/invasion.lua --out "$out" > "$work/refused.log" 2>&1 || status=$?
  [ "$status" -eq 1 ] || fail "--out $out exited with $status (expected 1)" "$work/refused.log"
  grep -q "cannot create directory '$out" "$work/refused.log" || fail "no message for $out" "$work/refused.log"
  ! grep -q "init:" "$work/refused.log" || fail "work started with --out $out" "$work/refused.log"
}
refused "$work/a_file/run"
cases=1
if [ "$(id -u)" -eq 0 ] && mkdir -p "$work/ro" && mount -t tmpfs -o size=1m,ro tmpfs "$work/ro" 2> /dev/null; then
  trap 'umount "$work/ro"' EXIT
  refused "$work/ro"
  cases=2
elif [ "${INVASIM_REQUIRE_ALL_TESTS:-0}" = 1 ]; then
  # The other cases passed; only the read-only mount could not be made.
  skip_test "the read-only --out case needs root and mount -t tmpfs (uid $(id -u))" "mount"
fi
echo "checkpoint_faults: SIGKILL and ENOSPC inside a checkpoint write lost nothing; $cases unwritable --out refused"
