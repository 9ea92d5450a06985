#!/usr/bin/env bash
# `invasim sweep` on this machine, end to end, on tests/app/sweeps/tiny.lua (4 points and a
# shared preparation, a few seconds each):
#  1. init: .signac/config, one workspace/<id>/ per point, id = MD5 of Python's
#     json.dumps(statepoint, sort_keys=True) (checked with python3);
#  2. run, stopped with SIGINT once a point has written a checkpoint (an event, not a time):
#     the runner forwards it, exits 1, the stopped points are "interrupted";
#  3. a second run finishes only what is left (a stopped point continues from its
#     checkpoint): every point ends done, none ran twice to completion (one "results in"
#     line per log), and each series.csv equals that of an
#     uninterrupted run of the same sweep in another workspace, byte for byte;
#  4. init with a grown spec (a third seed) adds 2 points, keeps the 4 and their results;
#     collect shows the 2 new ones pending with empty cells; run does only those 2;
#  5. collect: the results.csv header of the contract (docs/sweeps.md);
#  6. a sweep with a failing point: the other point is done, the failure is reported with its
#     log, the exit status is 1;
#  7. analyze runs the master-curve script on the collected table (defaults of P, beta, gamma).
# Usage: sweep_local.sh INVASIM SPEC_DIR WORK_DIR PYTHON3
set -euo pipefail
unset PYTHONOPTIMIZE  # the Python heredocs below check with assert
invasim=$1 specs=$2 work=$3 python=$4
source "$(dirname "$0")/../lua/wait_for.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# The points run 40000 steps (seconds, not tiny.lua's milliseconds): the point whose
# checkpoint was seen is still running when SIGINT arrives.
long=(--set steps=40000 --set checkpoint_every=2000)
"$invasim" sweep init "$specs/tiny.lua" --workspace ws "${long[@]}" > init.log || fail "init" init.log
grep -q "4 new points, 0 kept" init.log || fail "init did not report 4 new points" init.log
[ "$(cat ws/.signac/config)" = "schema_version = 2" ] || fail ".signac/config is not schema 2"
"$python" - ws <<'PY' || fail "signac ids"
import hashlib, json, os, sys
ws = sys.argv[1]
ids = os.listdir(os.path.join(ws, "workspace"))
assert len(ids) == 4, ids
for i in ids:
    sp = json.load(open(os.path.join(ws, "workspace", i, "signac_statepoint.json")))
    assert hashlib.md5(json.dumps(sp, sort_keys=True).encode()).hexdigest() == i, (i, sp)
    assert sp["N_c"] == 200 and isinstance(sp["kT"], float) and isinstance(sp["seed"], int), sp
PY

# 2. Stop the sweep once some point has written a checkpoint.
"$invasim" sweep run ws --jobs 2 --threads 1 > run1.log 2>&1 &
pid=$!
wait_for $pid "a checkpoint of a point" \
  bash -c 'ls ws/workspace/*/checkpoint/state.ckpt > /dev/null 2>&1'
kill -INT $pid
status=0
wait $pid || status=$?
[ $status -eq 1 ] || fail "the stopped sweep run exited with $status (expected 1)" run1.log
grep -q "SIGINT: stopping the running jobs" run1.log || fail "no stop message" run1.log
grep -q "interrupted" run1.log || fail "no point was recorded as interrupted" run1.log
"$invasim" sweep status ws > status1.log
grep -Eq "interrupted: [1-9]" status1.log || fail "status shows no interrupted point" status1.log

# 3. The second run finishes the rest.
"$invasim" sweep run ws --jobs 2 --threads 1 > run2.log 2>&1 || fail "second run" run2.log
grep -q "4 of 4 points done" run2.log || fail "second run did not finish every point" run2.log
"$invasim" sweep init "$specs/tiny.lua" --workspace clean "${long[@]}" > /dev/null
"$invasim" sweep run clean --jobs 2 --threads 1 > clean.log 2>&1 || fail "uninterrupted run" clean.log
for dir in ws/workspace/*; do
  id=$(basename "$dir")
  n=$(grep -c "results in" "$dir/run.log" || true)
  [ "$n" -eq 1 ] || fail "point $id completed $n times" "$dir/run.log"
  cmp "$dir/series.csv" "clean/workspace/$id/series.csv" ||
    fail "point $id: series.csv differs from the uninterrupted run"
done
grep -q '"status": "done"' ws/prep/signac_job_document.json || fail "prep not done"
grep -q "resuming the run" ws/workspace/*/run.log || fail "no point continued from its checkpoint"

# 4. A grown spec: 2 new points; the old ones keep their results.
before=$(cat ws/workspace/*/series.csv | md5sum)
"$invasim" sweep init "$specs/tiny_grown.lua" --workspace ws "${long[@]}" > init2.log || fail "init grown" init2.log
grep -q "2 new points, 4 kept" init2.log || fail "grown init" init2.log
"$invasim" sweep collect ws -o pending.csv
[ "$(grep -c ',pending,,' pending.csv)" -eq 2 ] || fail "collect: 2 pending rows with empty cells" pending.csv
"$invasim" sweep run ws --jobs 2 --threads 1 > run3.log 2>&1 || fail "run after growing" run3.log
grep -q "2 done now, 4 done before" run3.log || fail "run after growing ran other points" run3.log
[ "$(cat $(ls -d ws/workspace/* | while read d; do
        grep -q '"seed": 3' "$d/signac_statepoint.json" || echo "$d/series.csv"; done) | md5sum)" \
  = "$before" ] || fail "the old points' results changed"

# 5. collect: the contract's columns.
"$invasim" sweep collect ws -o results.csv
"$python" - results.csv <<'PY' || fail "results.csv" results.csv
import csv, sys
rows = list(csv.reader(open(sys.argv[1])))
head = rows[0]
assert head[:3] == ["job_id", "status", "wall_seconds [s]"], head
keys = head[3:head.index("A_ratio")]
assert keys == sorted(keys) and "seed" in keys and "kT" in keys, keys
assert head[-3:] == ["tau_d [tau]", "tau_r [tau]", "tau_d_unresolved"], head
means = head[head.index("A_ratio"):-3]
names = [c.split(" [")[0] for c in means[0::5]]
assert names == sorted(names), names
for mean, err, conv, drift, derr in zip(*(means[k::5] for k in range(5))):
    n, _, unit = mean.partition(" [")
    u = " [" + unit if unit else ""
    assert (err, conv, drift, derr) == (n + "_error" + u, n + "_error_converged",
                                        n + "_drift" + u, n + "_drift_error" + u), mean
assert "T_c [eps_c]" in head and "T_c_error [eps_c]" in head and "A_ratio_error" in head, head
assert "L_x_drift [sigma]" in head, head
assert len(rows) == 7 and all(r[1] == "done" for r in rows[1:]), rows
# Every cell holds a number, but tau_r's where the point's run.log says it was not reached
# (a cold point's structure does not relax within the correlation window); the flags are 0/1.
import os
tau_r = head.index("tau_r [tau]")
for r in rows[1:]:
    assert all(c != "" for k, c in enumerate(r) if k != tau_r), r
    log = open(os.path.join("ws", "workspace", r[0], "run.log")).read()
    assert (r[tau_r] == "") == ("tau_r = not reached" in log), (r[0], r[tau_r])
    float(r[head.index("T_c [eps_c]")])
    assert r[-1] in ("0", "1") and r[head.index("T_c_error_converged")] in ("0", "1"), r
# The drift, recomputed from a job's series.csv and summary.json: the mean of the averaging
# window's second half minus its first half's (its last 2 floor(n/2) rows).
import json, os
for r in rows[1:]:
    job = os.path.join("ws", "workspace", r[0])
    series = list(csv.reader(open(os.path.join(job, "series.csv"))))
    n = json.load(open(os.path.join(job, "summary.json")))["averages"]["T_c"]["samples"]
    col = series[0].index("T_c [eps_c]")
    window = [float(s[col]) for s in series[1:]][-n:]
    h = n // 2
    want = sum(window[-h:]) / h - sum(window[-2 * h:-h]) / h
    got = float(r[head.index("T_c_drift [eps_c]")])
    assert n >= 2 and abs(got - want) <= 1e-12 * max(1.0, abs(want)), (r[0], n, got, want)
PY

# 6. A failing point does not stop the others.
"$invasim" sweep init "$specs/failing.lua" --workspace failing > /dev/null
status=0
"$invasim" sweep run failing --jobs 1 --threads 1 > failing.log 2>&1 || status=$?
[ $status -eq 1 ] || fail "a sweep with a failing point exited with $status" failing.log
grep -q "1 done now, 0 done before; 1 of 2 points done; 1 not done:" failing.log &&
  grep -q "^  [0-9a-f]\{8\} (.*beta=0.5.*): failed (exit status 1; log .*/run.log)" failing.log ||
  fail "failure tally" failing.log
grep -rq "beta = 0.5 must be smaller than alpha" failing/workspace/*/run.log || fail "failure log"
# 7. analyze: collects into ws/results.csv (the same table as collect) and runs
#    scripts/master_curve.py on it, with the user's options passed on and the protocol's
#    defaults of the parameters the fits need (beta, gamma: this sweep does not set them)
#    merged into the user's --fixed; two temperatures, one of them not steady in runs this
#    short, are too few for the fit, and the script says so (exit status 1).
status=0
"$invasim" sweep analyze ws --no-figures --fixed P=0.002 > analyze.log 2>&1 || status=$?
[ $status -eq 1 ] || fail "analyze of 2 temperatures exited with $status (expected 1)" analyze.log
grep -q "sweep analyze: 6 rows in [^ ]*ws/results.csv$" analyze.log || fail "analyze: collect" analyze.log
grep -q -- "master_curve.py [^ ]*ws/results.csv -o [^ ]*ws/analysis --fixed P=0.002,beta=0.01,gamma=0.2 --no-figures$" \
  analyze.log || fail "analyze: the script's command line" analyze.log
grep -q "needs at least 3\|A_n is undefined" analyze.log || fail "analyze: the script's verdict" analyze.log
cmp ws/results.csv results.csv || fail "analyze's results.csv differs from collect's"
echo "sweep local: OK"
