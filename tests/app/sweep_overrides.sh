#!/bin/bash
# sweep init --tiny / --set / --take (docs/sweeps.md, "Tiny runs and overrides"): the points
# they make (state points read back), and that the preparation keeps its own prep.set values.
# Usage: sweep_overrides.sh INVASIM SPECS_DIR WORKDIR PYTHON3
set -euo pipefail
unset PYTHONOPTIMIZE  # the Python heredocs below check with assert
invasim=$1 specs=$2 work=$3 py=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# The full spec: 3 x 2 x 3 x 2 = 36 points.
"$invasim" sweep init "$specs/overrides.lua" --workspace full | grep -q "36 new points" || fail "full"
# --tiny: take 2 of each axis, one seed (2 x 2 x 2 = 8), the tiny.set values in every point.
"$invasim" sweep init "$specs/overrides.lua" --tiny --workspace tiny | grep -q "8 new points" || fail "tiny count"
# --take 1 plus --set on axes (kT, tau_p of a zip group) and on a fixed key: 1 point. A number
# keeps the written kind, as in a Lua spec: 10.0 is a float, 300 an integer.
"$invasim" sweep init "$specs/overrides.lua" --take 1 --set kT=5e-4 --set steps=300 --set tau_p=10.0 \
  --workspace one | grep -q "1 new points" || fail "take 1"
"$py" - <<'PY' || fail "state points"
import json, glob
def sps(ws):
    return [json.load(open(p)) for p in glob.glob(ws + "/workspace/*/signac_statepoint.json")]
tiny = sps("tiny")
assert {p["kT"] for p in tiny} == {1e-4, 1e-3}, tiny
assert {p["f0"] for p in tiny} == {0.0, 0.01}
assert {(p["tau_p"], p["beta"]) for p in tiny} == {(25.0, 0.0), (250.0, 1e-3)}
assert {p["seed"] for p in tiny} == {1}
assert all(p["steps"] == 200 and p["quench_steps"] == 10 and p["every"] == 100 and p["N_c"] == 20
           for p in tiny), tiny
meta = json.load(open("tiny/invasim_sweep.json"))
prep = meta["prep"]["set"]
assert prep["steps"] == 0 and prep["quench_steps"] == 0, prep   # prep.set wins
assert prep["N_c"] == 20 and prep["every"] == 100, prep          # tiny.set reaches the prep
(one,) = sps("one")
assert one["kT"] == 5e-4 and one["steps"] == 300 and one["tau_p"] == 10.0 and one["beta"] == 0.0, one
assert isinstance(one["steps"], int) and isinstance(one["tau_p"], float)
print("state points ok")
PY
echo PASS
