#!/usr/bin/env bash
# `sweep collect` writes numbers as Python's repr (docs/sweeps.md, "Status and collection"):
# on tests/app/sweeps/collect_numbers.lua (kT = 0.0013 and 1e-5, tau_p = 25 and 25.0), with
# one point given a done status and a summary.json and series.csv by hand (no run):
#  1. every state-point cell of every row is Python's repr of the value in that point's
#     signac_statepoint.json (integers without a decimal point: 25 and 25.0 are two rows that
#     differ), and kT reads 0.0013, not 0.0012999999999999999;
#  2. the done point's means, errors, drift, tau_d and tau_r are the repr of their values
#     (0.1 + 0.2 = 0.30000000000000004 keeps its 17 digits: the text reads back exactly), its
#     flags (error_converged, tau_d_unresolved) 1 or 0;
#  3. a measured average named as a state-point key (kT) is written as measured_kT, and no two
#     columns share a name.
# Usage: sweep_collect_numbers.sh INVASIM SPEC_DIR WORK_DIR PYTHON3
set -euo pipefail
invasim=$1 specs=$2 work=$3 python=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $1" >&2; if [ $# -gt 1 ]; then cat "$2" >&2; fi; exit 1; }

"$invasim" sweep init "$specs/collect_numbers.lua" --workspace ws > init.log || fail "init" init.log
grep -q "4 new points, 0 kept" init.log || fail "init did not report 4 new points" init.log

# One point done, by hand: its job document, summary.json and a series.csv whose averaging
# window (4 rows) drifts by 0.0013 in A_t.
done_id=$(ls ws/workspace | head -1)
"$python" - "ws/workspace/$done_id" <<'PY' || fail "writing the done point"
import json, os, sys
d = sys.argv[1]
doc = json.load(open(os.path.join(d, "signac_job_document.json")))
doc.update(status="done", wall_seconds=12.5)
json.dump(doc, open(os.path.join(d, "signac_job_document.json"), "w"))
summary = {"averages": {"A_t": {"mean": 0.1 + 0.2, "error": 1e-05, "samples": 4,
                                "tau_int": 0.5, "error_converged": True},
                        "T_c": {"mean": 25.0, "error": 0.0013, "samples": 4,
                                "tau_int": 0.5, "error_converged": False},
                        "kT": {"mean": 0.5, "error": 0.01, "samples": 4,
                               "tau_int": 0.5, "error_converged": True},
                        "tau_d": 3.0, "tau_r": 1e20}}
json.dump(summary, open(os.path.join(d, "summary.json"), "w"))
with open(os.path.join(d, "series.csv"), "w") as f:
    f.write("step,A_t [sigma^2],T_c [eps_c],kT [eps_c]\n0,0,25,0.5\n1,0,25,0.5\n2,0,25,0.5\n"
            "3,0.0026,25,0.5\n")
PY

"$invasim" sweep collect ws -o results.csv
"$python" - ws results.csv "$done_id" <<'PY' || fail "results.csv is not written as Python's repr" results.csv
import csv, json, os, sys
ws, table, done_id = sys.argv[1:]
rows = list(csv.reader(open(table)))
header = [h.split(" [")[0] for h in rows[0]]
problems = []
def expect(row, column, value):
    text = row[header.index(column)]
    if text != repr(value):
        problems.append("%s: %s = %r, expected %r" % (row[0][:8], column, text, repr(value)))
taus = set()
if len(set(header)) != len(header):
    problems.append("columns named twice: %s" % sorted({h for h in header if header.count(h) > 1}))
if [r[0] for r in rows[1:]].count(done_id) != 1:
    problems.append("the done point %s is not one row of %s" % (done_id, table))
for row in rows[1:]:
    sp = json.load(open(os.path.join(ws, "workspace", row[0], "signac_statepoint.json")))
    for key, value in sp.items():
        expect(row, key, value)
    taus.add(row[header.index("tau_p")])
    if row[header.index("kT")] not in ("0.0013", "1e-05"):
        problems.append("kT = %s" % row[header.index("kT")])
    if row[0] == done_id:
        for column, value in (("wall_seconds", 12.5), ("A_t", 0.1 + 0.2), ("A_t_error", 1e-05),
                              ("A_t_drift", 0.0013), ("T_c", 25.0), ("T_c_error", 0.0013),
                              ("T_c_drift", 0.0), ("tau_d", 3.0), ("tau_r", 1e20),
                              ("measured_kT", 0.5), ("measured_kT_error", 0.01),
                              ("measured_kT_drift", 0.0)):
            expect(row, column, value)
        for column, text in (("A_t_error_converged", "1"), ("T_c_error_converged", "0"),
                             ("tau_d_unresolved", "0")):
            if row[header.index(column)] != text:
                problems.append("%s = %r, expected %r" % (column, row[header.index(column)], text))
        if not float(row[header.index("A_t_drift_error")]) >= 0:
            problems.append("A_t_drift_error = %r" % row[header.index("A_t_drift_error")])
    elif row[header.index("tau_d_unresolved")] != "":
        problems.append("a point not done has tau_d_unresolved %r" % row[header.index("tau_d_unresolved")])
if taus != {"25", "25.0"}:
    problems.append("tau_p cells %s, expected 25 and 25.0" % sorted(taus))
if problems:
    sys.exit("\n".join(problems))
PY
echo "sweep_collect_numbers: state points and measurements written as Python's repr"
