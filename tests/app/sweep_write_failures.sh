#!/usr/bin/env bash
# A sweep's files survive failed writes and broken points (docs/sweeps.md). A full disk is
# provoked by `ulimit -f` with SIGXFSZ ignored, so that write() fails with EFBIG. One case per
# run:
#   writes   `sweep run` and a growing `sweep init` that cannot write fail, and leave every
#            job document and invasim_sweep.json as it was (they used to be emptied), with no
#            temporary file behind;
#   collect  `sweep collect -o results.csv` with a point's job document emptied, or unable to
#            write, fails naming the file and leaves the previous results.csv as it was (it
#            used to be truncated to 0 bytes first);
#   summary  a done point whose summary.json is missing, malformed or no object stops
#            `sweep collect` with an error naming the file (its row used to have empty cells);
#   points   `sweep submit --slurm --dry-run` that cannot write points.txt fails naming it
#            (a cut list, the first 8 kB, used to be left with exit status 0).
# Usage: sweep_write_failures.sh INVASIM SPEC_DIR WORK_DIR CASE
set -euo pipefail
invasim=$1 specs=$2 work=$3 case=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $1" >&2; if [ $# -gt 1 ]; then cat "$2" >&2; fi; exit 1; }

# limited BLOCKS LOG COMMAND...: runs invasim with files limited to BLOCKS kB; its output goes
# through a pipe (a file of the limited process could not be written); returns its status.
limited() {
  local blocks=$1 log=$2
  shift 2
  set +e
  (trap '' XFSZ; ulimit -f "$blocks"; exec "$invasim" "$@") 2>&1 | cat > "$log"
  local rc=${PIPESTATUS[0]}
  set -e
  return "$rc"
}
# The JSON files of a workspace with their checksums, to compare before and after.
json_sums() { (cd "$1" && find . -name '*.json' -type f | sort | xargs md5sum); }
no_temporaries() {
  local left
  left=$(find "$1" -name '*.tmp*')
  [ -z "$left" ] || fail "temporary files left behind: $left"
}
# A point made done by hand (no run), with a summary.json of one average.
make_done() {
  printf '{"status": "done", "wall_seconds": 12.5}\n' > "$1/signac_job_document.json"
  printf '{"averages": {"A_t": {"error": 0.1, "mean": 1.5, "samples": 4}}}\n' > "$1/summary.json"
}

case $case in
writes)
  "$invasim" sweep init "$specs/tiny.lua" --workspace ws > init.log || fail "init" init.log
  json_sums ws > before.sums
  if limited 0 run.log sweep run ws --jobs 1 --threads 1; then
    fail "sweep run succeeded without writing a file" run.log
  fi
  json_sums ws > after.sums
  cmp -s before.sums after.sums ||
    fail "a failed sweep run changed the workspace's documents: $(diff before.sums after.sums)"
  no_temporaries ws
  "$invasim" sweep status ws > status.log 2>&1 || fail "sweep status after the failed run" status.log
  if limited 0 grow.log sweep init "$specs/tiny_grown.lua" --workspace ws; then
    fail "sweep init succeeded without writing a file" grow.log
  fi
  grep -q "cannot write '.*': write failed: File too large" grow.log ||
    fail "the failed init does not name the file it could not write" grow.log
  json_sums ws > after.sums
  cmp -s before.sums after.sums ||
    fail "a failed sweep init changed the workspace's documents: $(diff before.sums after.sums)"
  no_temporaries ws
  "$invasim" sweep init "$specs/tiny_grown.lua" --workspace ws > regrow.log ||
    fail "sweep init after the failed one" regrow.log
  grep -q "2 new points, 4 kept" regrow.log || fail "the next init did not add 2 points" regrow.log
  echo "sweep_write_failures: ok: failed writes leave the documents as they were"
  ;;
collect)
  "$invasim" sweep init "$specs/collect_numbers.lua" --workspace ws > init.log || fail "init" init.log
  done_dir=ws/workspace/$(ls ws/workspace | head -1)
  broken=ws/workspace/$(ls ws/workspace | tail -1)
  make_done "$done_dir"
  "$invasim" sweep collect ws -o results.csv 2> collect.log || fail "collect" collect.log
  grep -q ',done,12.5,.*,1.5,0.1,' results.csv || fail "no done row" results.csv
  cp results.csv good.csv
  cp "$broken/signac_job_document.json" document.json
  : > "$broken/signac_job_document.json"
  if "$invasim" sweep collect ws -o results.csv 2> broken.log; then
    fail "collect succeeded with an emptied job document" broken.log
  fi
  grep -q "$broken/signac_job_document.json': malformed JSON" broken.log ||
    fail "the error does not name the emptied job document" broken.log
  cmp -s good.csv results.csv || fail "a failed collect changed results.csv ($(wc -c < results.csv) bytes)"
  cp document.json "$broken/signac_job_document.json"
  if limited 0 full.log sweep collect ws -o results.csv; then
    fail "collect succeeded without writing results.csv" full.log
  fi
  grep -q "cannot write 'results.csv': write failed: File too large" full.log ||
    fail "the error does not name results.csv" full.log
  cmp -s good.csv results.csv || fail "a collect that could not write changed results.csv"
  no_temporaries .
  echo "sweep_write_failures: ok: a failed collect keeps the previous results.csv"
  ;;
summary)
  "$invasim" sweep init "$specs/collect_numbers.lua" --workspace ws > init.log || fail "init" init.log
  id=$(ls ws/workspace | head -1)
  make_done "ws/workspace/$id"
  "$invasim" sweep collect ws > good.csv || fail "collect of a done point"
  summary=ws/workspace/$id/summary.json
  mv "$summary" kept.json
  for damage in missing '{"averages": {"A_t"' '[1, 2]'; do
    [ "$damage" = missing ] || printf '%s\n' "$damage" > "$summary"
    if "$invasim" sweep collect ws > out.csv 2> err.log; then
      fail "collect succeeded with summary.json $damage" out.csv
    fi
    grep -q "sweep collect: point $id is done but its summary is unusable: .*'[^']*$summary'" err.log ||
      fail "the error for summary.json $damage does not name the point and the file" err.log
    [ ! -s out.csv ] || fail "a failed collect printed rows" out.csv
  done
  mv kept.json "$summary"
  "$invasim" sweep collect ws > again.csv || fail "collect after the summary is back"
  cmp -s good.csv again.csv || fail "collect differs after the summary is back"
  echo "sweep_write_failures: ok: a done point without a usable summary.json is an error"
  ;;
points)
  "$invasim" sweep init "$specs/four_hundred.lua" --workspace ws > init.log || fail "init" init.log
  submit=(sweep submit ws --slurm --dry-run --max-array-size 1000)
  "$invasim" "${submit[@]}" > submit.log 2>&1 || fail "submit --dry-run" submit.log
  ls ws/workspace | sort > ids.txt
  sort ws/slurm/submit-1/points.txt | cmp -s - ids.txt || fail "points.txt does not list the 400 points"
  if limited 8 cut.log "${submit[@]}"; then
    fail "submit succeeded with points.txt cut at 8 kB" cut.log
  fi
  grep -q "cannot write '.*/submit-2/points.txt': write failed: File too large" cut.log ||
    fail "the error does not name points.txt" cut.log
  [ ! -e ws/slurm/submit-2/points.txt ] || fail "a cut points.txt was left: $(wc -l < ws/slurm/submit-2/points.txt) lines"
  no_temporaries ws/slurm
  echo "sweep_write_failures: ok: a points.txt that cannot be written is an error"
  ;;
*)
  fail "unknown case $case (writes, collect, summary or points)"
  ;;
esac
