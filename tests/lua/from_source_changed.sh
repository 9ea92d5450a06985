#!/usr/bin/env bash
# The --from source is identified by its contents (the FNV-1a 64 of S/checkpoint/compressed.ckpt
# is part of the run's identity and recorded in resume.txt and params.json):
#  1. a --resume after S's compressed.ckpt was replaced by another run's is refused, naming the
#     recorded and the current hash; with the file restored it runs;
#  2. a new run --from S is refused while S's compressed.ckpt was written by another run than
#     S/resume.txt describes.
# Usage: from_source_changed.sh INVASIM WORKDIR
set -euo pipefail
invasim=$1 work=$2
here=$(cd "$(dirname "$0")" && pwd)
source "$here/wait_for.sh"
rm -rf "$work" && mkdir -p "$work"
cd "$here"
run=(run ../../protocols/invasion.lua --set N_a=4 --set N_c=60 --set L0=32.0 --set quench_steps=200
     --set steps=400 --set every=200 --set snapshot_every=0)
"$invasim" "${run[@]}" --out "$work/source" > "$work/source.log" 2>&1 || fail "source run" "$work/source.log"
"$invasim" "${run[@]}" --seed 3 --out "$work/other" > "$work/other.log" 2>&1 || fail "other run" "$work/other.log"
"$invasim" "${run[@]}" --set P=2e-3 --from "$work/source" --out "$work/run" > "$work/run.log" 2>&1 ||
  fail "the run --from source" "$work/run.log"
source_ckpt=$(cd "$work/source" && pwd -P)/checkpoint/compressed.ckpt
hash=$(sed -n 's/^# from_checkpoint=//p' "$work/run/resume.txt")
[ -n "$hash" ] || fail "resume.txt records no content hash of the --from source" "$work/run/resume.txt"
grep -qF "\"from_checkpoint\": \"$hash\"" "$work/run/params.json" || fail "params.json has no from_checkpoint" "$work/run/params.json"

# 1. S's compressed.ckpt replaced by another run's.
cp "$source_ckpt" "$work/saved.ckpt"
cp "$work/other/checkpoint/compressed.ckpt" "$source_ckpt"
status=0
"$invasim" run --resume "$work/run" > "$work/changed.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "--resume after the --from source changed exited with $status (expected 1)" "$work/changed.log"
grep -qF "the --from source changed: when this run started, $source_ckpt had the content hash $hash" "$work/changed.log" ||
  fail "no message naming the changed source and its recorded hash" "$work/changed.log"

# 2. A new run --from S while S's compressed.ckpt is another run's.
status=0
"$invasim" "${run[@]}" --from "$work/source" --out "$work/new" > "$work/new.log" 2>&1 || status=$?
[ "$status" -eq 1 ] || fail "--from a source holding another run's checkpoint exited with $status (expected 1)" "$work/new.log"
grep -qF "refusing $source_ckpt: it was written by run " "$work/new.log" ||
  fail "no message saying the source's checkpoint is another run's" "$work/new.log"
[ ! -e "$work/new" ] || fail "the refused run created its directory"

cp "$work/saved.ckpt" "$source_ckpt"
"$invasim" run --resume "$work/run" > "$work/restored.log" 2>&1 || fail "--resume with the source restored" "$work/restored.log"
echo "from_source_changed passed: a changed --from source was refused on --resume and on --from"
