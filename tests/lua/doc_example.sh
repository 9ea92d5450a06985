#!/usr/bin/env bash
# Test: the worked example of docs/protocols.md (a pressure ramp, tethers, production) is
# docs/examples/ramp_tether.lua, character for character, and runs as the doc says (from the
# repository root, on a tiny tissue): each stage in order, the ramp ends at P, the tethers
# are made, and the run directory holds the main job's outputs.
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")/../.."
rm -rf "$work" && mkdir -p "$work"
# The listing after the marker line, up to its closing fence.
awk '/^<!-- example: docs\/examples\/ramp_tether.lua -->$/ { found = 1; next }
     found == 1 && /^```lua$/ { found = 2; next }
     found == 2 && /^```$/ { exit }
     found == 2 { print }' docs/protocols.md > "$work/listing.lua"
[ -s "$work/listing.lua" ] || { echo "FAILED: no example listing in docs/protocols.md"; exit 1; }
diff -u docs/examples/ramp_tether.lua "$work/listing.lua" ||
  { echo "FAILED: docs/protocols.md's listing differs from docs/examples/ramp_tether.lua"; exit 1; }
"$invasim" run docs/examples/ramp_tether.lua --set N_a=4 --set N_c=60 --set L0=32.0 \
  --set P_start=2e-4 --set ramp_steps=300 --set quench_steps=100 --set steps=400 --set every=100 \
  --set snapshot_every=200 --set correlate_every=10 --out "$work/run" > "$work/run.log" 2>&1 ||
  { echo "FAILED: the example did not run"; cat "$work/run.log"; exit 1; }
# The stages in the protocol's order.
order=$(grep -o "^\(init\|compress\|ramp\|tether\|equilibrate\|production\|summary\):" "$work/run.log" | uniq | tr '\n' ' ')
[ "$order" = "init: compress: ramp: tether: equilibrate: summary: " ] ||
  [ "$order" = "init: compress: ramp: tether: equilibrate: production: summary: " ] ||
  { echo "FAILED: stage order '$order'"; cat "$work/run.log"; exit 1; }
grep -q "^ramp: P = 0.0002 (ramp), .* 300 steps" "$work/run.log" || { echo "FAILED: ramp"; cat "$work/run.log"; exit 1; }
grep -q "^tether: [1-9][0-9]* tethers (K = 0.04) between 4 adipocytes" "$work/run.log" ||
  { echo "FAILED: tethers"; exit 1; }
grep -q "^equilibrate: P = 0.0013, .* 100 steps" "$work/run.log" || { echo "FAILED: equilibrate at P"; exit 1; }
rows=$(($(wc -l < "$work/run/series.csv") - 1))
[ "$rows" = 4 ] || { echo "FAILED: series.csv has $rows rows, expected 4"; exit 1; }
for f in summary.json correlations.csv shapes.csv params.json checkpoint/compressed.ckpt; do
  [ -s "$work/run/$f" ] || { echo "FAILED: no $f"; exit 1; }
done
frames=$(ls "$work/run/snapshots" | grep -c "^cells_.*\.xyz$")
[ "$frames" = 3 ] || { echo "FAILED: $frames snapshot frames, expected 3"; exit 1; }
grep -q '"P_start": 0.0002' "$work/run/params.json" || { echo "FAILED: params.json"; exit 1; }
echo "doc_example: the listing is docs/examples/ramp_tether.lua and it ran: $order($rows rows, $frames frames)"
