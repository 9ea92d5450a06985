#!/usr/bin/env bash
# Test: `invasim run --from RUN_DIR` starts from the compressed tissue that RUN_DIR
# saved (no compression of its own), with its own seed and the parameters that act after the
# compression; a run whose own tissue would differ (A_0, start, L0, eps_a; beta after a cohesive
# compression) is refused before any work.
set -euo pipefail
invasim=$1
work=$2
cd "$(dirname "$0")"
rm -rf "$work" && mkdir -p "$work"
args=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
      --set steps=400 --set every=200 --set snapshot_every=0)
"$invasim" "${args[@]}" --out "$work/first" > "$work/first.log" 2>&1
[ -f "$work/first/checkpoint/compressed.ckpt" ] || { echo "FAILED: no compressed.ckpt"; exit 1; }
"$invasim" "${args[@]}" --seed 7 --set P=2e-3 --set beta=1e-3 --from "$work/first" --out "$work/second" > "$work/second.log" 2>&1 ||
  { echo "FAILED: second run"; cat "$work/second.log"; exit 1; }
grep -q "compress: skipped: the compressed tissue of $work/first" "$work/second.log" ||
  { echo "FAILED: did not start from the first run"; cat "$work/second.log"; exit 1; }
first_box=$(grep -o "final box L_f = [0-9.]*" "$work/first.log" | grep -o "[0-9.]*$")
grep -q "compressed box L_f = $first_box" "$work/second.log" || { echo "FAILED: box"; exit 1; }
grep -q "quench: P = 0.002" "$work/second.log" || { echo "FAILED: own parameters"; exit 1; }
! "$invasim" "${args[@]}" --from "$work/missing" --out "$work/third" > "$work/third.log" 2>&1 ||
  { echo "FAILED: a missing run directory was accepted"; exit 1; }
grep -q "missing/checkpoint/compressed.ckpt" "$work/third.log" || { echo "FAILED: message"; cat "$work/third.log"; exit 1; }
# A tissue of another size is refused (groups and forces index the sites).
! "$invasim" run ../../protocols/invasion.lua --set N_a=4 --set N_c=61 --set L0=32.0 --from "$work/first" --out "$work/fourth" > "$work/fourth.log" 2>&1 ||
  { echo "FAILED: a tissue of another size was accepted"; exit 1; }
grep -q "holds 228 sites and 4 adipocytes, this System 229 sites" "$work/fourth.log" ||
  { echo "FAILED: size message"; cat "$work/fourth.log"; exit 1; }
# A run whose own tissue would differ is refused before any work, naming the parameter (the
# seed and P above may differ: they act after the compression).
! "$invasim" "${args[@]}" --set A_0=1.3 --from "$work/first" --out "$work/fifth" > "$work/fifth.log" 2>&1 ||
  { echo "FAILED: another A_0 was accepted"; exit 1; }
grep -q "its tissue was made with A_0 = 1.1, this run's is A_0 = 1.3" "$work/fifth.log" ||
  { echo "FAILED: A_0 message"; cat "$work/fifth.log"; exit 1; }
[ ! -e "$work/fifth" ] || { echo "FAILED: the refused run made its directory"; exit 1; }
! "$invasim" "${args[@]}" --set start=mixed --from "$work/first" --out "$work/sixth" > "$work/sixth.log" 2>&1 ||
  { echo "FAILED: another start was accepted"; exit 1; }
grep -q "start = demixed, this run's is start = mixed" "$work/sixth.log" ||
  { echo "FAILED: start message"; cat "$work/sixth.log"; exit 1; }
! "$invasim" run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=30.0 --from "$work/first" --out "$work/seventh" > "$work/seventh.log" 2>&1 ||
  { echo "FAILED: another L0 was accepted"; exit 1; }
grep -q "started from L0 = 32 (system reduced), this run's would start from L0 = 30" "$work/seventh.log" ||
  { echo "FAILED: L0 message"; cat "$work/seventh.log"; exit 1; }
# The shape energies shape the compressed tissue too; the contact parameters only when the
# source compressed with its cells' cohesion on (the first run did not: the second run's beta
# below may differ).
! "$invasim" "${args[@]}" --set eps_a=2 --from "$work/first" --out "$work/eighth" > "$work/eighth.log" 2>&1 ||
  { echo "FAILED: another eps_a was accepted"; exit 1; }
grep -q "its tissue was made with eps_a = 1, this run's is eps_a = 2" "$work/eighth.log" ||
  { echo "FAILED: eps_a message"; cat "$work/eighth.log"; exit 1; }
"$invasim" "${args[@]}" --set cohesive_compression=true --out "$work/cohesive" > "$work/cohesive.log" 2>&1 ||
  { echo "FAILED: cohesive compression"; cat "$work/cohesive.log"; exit 1; }
! "$invasim" "${args[@]}" --set cohesive_compression=true --set beta=1e-3 --from "$work/cohesive" --out "$work/ninth" > "$work/ninth.log" 2>&1 ||
  { echo "FAILED: another beta was accepted for a tissue compressed with cohesion"; exit 1; }
grep -q "its tissue was made with beta = 0.01, this run's is beta = 0.001" "$work/ninth.log" ||
  { echo "FAILED: beta message"; cat "$work/ninth.log"; exit 1; }
echo "from_run: the second run started from the first run's compressed tissue (L_f = $first_box)"
