#!/usr/bin/env bash
# Test: `invasim render` accepts every snapshot of a run whose box moves. A short
# invasion run (the piston moves the left wall every step) writes a frame every 50 steps;
# each frame's cells (.xyz), adipocytes (.vtp) and spheres (.vtp) file is rendered. The XYZ
# stores Origin and the Lattice lengths, the VTP box_lo and box_hi; for some boxes
# Origin + Lattice != box_hi in floating point, and an exact frame-consistency check refused
# those frames. The test also checks that the run has such frames (6 of 41 with these
# parameters), so that it keeps exercising the case if the trajectory changes.
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
"$invasim" run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=34.0 \
  --set quench_steps=200 --set steps=2000 --set every=50 --set snapshot_every=50 \
  --out "$work/run" > "$work/run.log" 2>&1 || { echo "FAILED: run"; cat "$work/run.log"; exit 1; }
snaps="$work/run/snapshots"
files=0
for f in "$snaps"/cells_*.xyz "$snaps"/adipocytes_*.vtp "$snaps"/spheres_*.vtp; do
  [ -f "$f" ] || { echo "FAILED: no snapshot files"; exit 1; }
  "$invasim" render "$f" --slice z=5 -o "$work/s.svg" > "$work/render.log" 2>&1 ||
    { echo "FAILED: render $f"; cat "$work/render.log"; exit 1; }
  files=$((files + 1))
done
# Frames whose upper x corner does not round-trip: Origin + Lattice (XYZ) != box_hi (VTP).
odd=0
for xyz in "$snaps"/cells_*.xyz; do
  vtp=${xyz/cells_/adipocytes_}
  vtp=${vtp%.xyz}.vtp
  lo_len=$(sed -n 2p "$xyz" | sed -E 's/.*Lattice="([^ ]+) .*Origin="([^ ]+) .*/\2 \1/')
  hi=$(grep -A1 'Name="box_hi"' "$vtp" | tail -1 | awk '{print $1}')
  if ! echo "$lo_len $hi" | awk '{ exit !(($1 + $2) == $3) }'; then odd=$((odd + 1)); fi
done
frames=$(ls "$snaps"/cells_*.xyz | wc -l)
[ "$files" -eq $((3 * frames)) ] && [ "$frames" -ge 40 ] && [ "$odd" -ge 1 ] ||
  { echo "FAILED: $files files of $frames frames, $odd frames whose box does not round-trip"; exit 1; }
echo "render_every_snapshot: rendered all $files files of $frames frames ($odd frames with Origin + Lattice != box_hi)"
