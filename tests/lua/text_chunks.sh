#!/usr/bin/env bash
# Runs text_chunks.lua (load, loadfile, dofile and require refuse binary
# chunks), then a corrupted precompiled chunk as the protocol: invasim must refuse it with
# exit status 1 and a message naming the file (it used to crash or hang).
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
TEXT_CHUNKS_OUT="$work/corrupt.lua" "$invasim" run text_chunks.lua > "$work/chunks.log" 2>&1 ||
  { echo "FAILED: text_chunks.lua"; cat "$work/chunks.log"; exit 1; }
grep -q "text_chunks: all [0-9]* checks passed" "$work/chunks.log" || { cat "$work/chunks.log"; exit 1; }
rc=0
timeout 60 "$invasim" run "$work/corrupt.lua" > "$work/protocol.log" 2>&1 || rc=$?
[ "$rc" -eq 1 ] || { echo "FAILED: exit status $rc (expected 1)"; cat "$work/protocol.log"; exit 1; }
grep -q "^invasim: error: cannot load protocol file '$work/corrupt.lua': attempt to load a binary chunk (mode is 't'): invasim runs Lua source files only" \
  "$work/protocol.log" || { echo "FAILED: message"; cat "$work/protocol.log"; exit 1; }
echo "text_chunks: binary chunks refused by load, loadfile, dofile, require and invasim run"
