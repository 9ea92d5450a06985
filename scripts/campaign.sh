#!/usr/bin/env bash
# Runs sweep files one after the other as a campaign that survives the loss of its machine:
# each sweep's workspace OUT/<name> is made by `invasim sweep init` if missing, takes back
# the points kept in KEEP/<name> (scripts/sweep_results.py restore), runs with `invasim sweep
# run`, and keeps its done points in KEEP/<name> every 5 minutes and at the end, so that a
# fresh machine redoes only the points that had not finished. <name> is the sweep file's name,
# prefixed "paper_" for protocols/sweeps/paper_scale/. A file OUT/stop stops the campaign
# before its next sweep. Run it from a clone of its own at a fixed revision, with a copy of the
# binary (a workspace records its protocol's path, and a resumed point refuses a protocol
# edited since it started), in the background, detached, with a core left free, e.g.
#   JOBS=1 nohup setsid scripts/campaign.sh out docs/data/runs protocols/sweeps/fig5_long.lua \
#     protocols/sweeps/paper_scale/fig4b_starts.lua >> campaign.log 2>&1 < /dev/null &
# Environment: JOBS (points at a time, default 1), THREADS (per point, default 1), INVASIM
# (the binary, default build/invasim; give it a copy if you rebuild meanwhile).
# Usage: scripts/campaign.sh OUT KEEP SPEC...
set -u
[ $# -ge 3 ] || { sed -n '2,15p' "$0" >&2; exit 2; }
out=$1 keep=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
bin=${INVASIM:-build/invasim}
python=$(command -v /usr/bin/python3 || command -v python3)
[ -x "$bin" ] || { echo "campaign: $bin is not an executable (build first, or set INVASIM)" >&2; exit 2; }
mkdir -p "$out" "$keep"
for spec in "$@"; do
  [ -f "$out/stop" ] && { echo "campaign: $out/stop found: stopping"; exit 0; }
  name=$(basename "$spec" .lua)
  case $spec in */paper_scale/*) name=paper_$name ;; esac
  ws=$out/$name
  [ -d "$ws" ] || "$bin" sweep init "$spec" --workspace "$ws" || exit 1
  [ -d "$keep/$name" ] && "$python" "$here/sweep_results.py" restore "$keep/$name" "$ws"
  (while sleep 300; do "$python" "$here/sweep_results.py" save "$ws" "$keep/$name" > /dev/null; done) &
  saver=$!
  echo "=== $(date -u +%FT%TZ) $ws start"
  "$bin" sweep run "$ws" --jobs "${JOBS:-1}" --threads "${THREADS:-1}"
  status=$?
  echo "=== $(date -u +%FT%TZ) $ws end (exit status $status)"
  kill $saver 2> /dev/null
  "$python" "$here/sweep_results.py" save "$ws" "$keep/$name"
done
