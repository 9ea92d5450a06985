#!/bin/bash
# Non-regular files: a FIFO (no writer), a directory or a device given as protocol,
# snapshot, checkpoint, run description or sweep spec is refused with a message naming it,
# instead of blocking. Each command runs under `timeout` so that a hang fails the test.
#   fifo_inputs.sh INVASIM
set -u
invasim=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkfifo "$dir/protocol.lua" "$dir/cells_0.xyz" "$dir/spheres_0.vtp" "$dir/state.ckpt" "$dir/spec.lua"
mkdir -p "$dir/run"
mkfifo "$dir/run/resume.txt"
failures=0
expect() {  # expect REGEX COMMAND...: exit status 1 or 2 and REGEX in stderr, within 20 s
  local regex=$1
  shift
  local out rc
  out=$(timeout -s KILL 20 "$@" 2>&1 </dev/null)
  rc=$?
  if [ $rc -eq 137 ] || [ $rc -eq 124 ]; then
    echo "HANG: $*"
    failures=$((failures + 1))
  elif [ $rc -eq 0 ] || ! grep -Eq "$regex" <<<"$out"; then
    echo "FAIL: $* (exit $rc): $out"
    failures=$((failures + 1))
  else
    echo "ok: $*: $out"
  fi
}
fifo="it is a FIFO \(named pipe\), not a regular file"
expect "cannot read protocol file '$dir/protocol.lua': $fifo" "$invasim" run "$dir/protocol.lua"
expect "cannot read protocol file '$dir/protocol.lua': $fifo" "$invasim" params "$dir/protocol.lua"
expect "cannot read snapshot '$dir/spheres_0.vtp': $fifo" "$invasim" render "$dir/spheres_0.vtp" --slice z=1 -o "$dir/x.svg"
expect "cannot read snapshot '$dir/cells_0.xyz': $fifo" "$invasim" render "$dir/cells_0.xyz" --slice z=1 -o "$dir/x.svg"
expect "cannot read run description '$dir/run/resume.txt': $fifo" "$invasim" run --resume "$dir/run"
expect "cannot read sweep spec '$dir/spec.lua': $fifo" "$invasim" sweep init "$dir/spec.lua" --workspace "$dir/ws"
cat > "$dir/load.lua" <<LUA
local iv = require("invasim")
iv.checkpoint_run("$dir/state.ckpt")
LUA
expect "cannot read '$dir/state.ckpt': $fifo" "$invasim" run "$dir/load.lua"
cat > "$dir/load2.lua" <<LUA
local iv = require("invasim")
iv.load_checkpoint("/dev/zero", { system = iv.System{ box = { 5, 5, 5 } } })
LUA
expect "cannot read '/dev/zero': it is a character device" "$invasim" run "$dir/load2.lua"
[ $failures -eq 0 ] && echo "fifo_inputs: all refused" && exit 0
exit 1
