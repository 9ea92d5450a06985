#!/bin/bash
# scripts/bath_table.py at its quick size (two state points, a few hundred steps, every
# reading of the vertex bath): it writes one CSV row per reading and point and replaces
# exactly the tables between the markers of the page it is given (docs/model.md in use),
# keeping the text around them; a page without the markers is refused, naming them.
# Usage: bath_table_quick.sh PYTHON INVASIM REPO WORKDIR
set -euo pipefail
python=$1 invasim=$2 repo=$3 work=$4
rm -rf "$work" && mkdir -p "$work"
fail() { echo "bath_table_quick: FAIL: $*" >&2; exit 1; }

page="$work/page.md"
printf 'before\n<!-- bath_table.py: begin -->\nOLD TABLE\n<!-- bath_table.py: end -->\nafter\n' > "$page"
(cd "$repo" && "$python" scripts/bath_table.py --quick --bin "$invasim" --runs "$work/runs" \
   --csv "$work/bath.csv" --model "$page") > "$work/log" 2>&1 || { cat "$work/log"; fail "the quick table did not run"; }

readings=$(grep -c '' <("$python" - "$repo" <<'PY'
from invasim_analysis import bath_table
for r in bath_table.readings(4.4):
    print(r[0])
PY
))
[ "$readings" -ge 10 ] || fail "only $readings readings declared"
rows=$(($(wc -l < "$work/bath.csv") - 1))
[ "$rows" -eq $((2 * readings)) ] || fail "$rows CSV rows, expected 2 x $readings readings"
grep -q '^before$' "$page" && grep -q '^after$' "$page" || fail "the text around the tables was not kept"
grep -q 'OLD TABLE' "$page" && fail "the old table was not replaced"
grep -q '^| a_r1 (background, T_act/T_0 = 1)' "$page" || fail "no summary row of reading a_r1"
grep -q '^| d_measured (' "$page" || fail "no summary row of reading d_measured"
grep -q '^| passive, 2kT/P = 0.3 |' "$page" || fail "no passive row in the tables"
grep -q '^| tau_p = 25, beta = 0.01, f0 = 0.0105 |' "$page" || fail "no active row in the tables"

printf 'no markers here\n' > "$work/bare.md"
if (cd "$repo" && "$python" scripts/bath_table.py --quick --bin "$invasim" --runs "$work/runs" \
      --csv "$work/bath2.csv" --model "$work/bare.md") > "$work/log2" 2>&1; then
  fail "a page without the markers was accepted"
fi
grep -q "needs one line '<!-- bath_table.py: begin -->'" "$work/log2" || { cat "$work/log2"; fail "the refusal does not name the markers"; }
grep -q '^no markers here$' "$work/bare.md" || fail "the refused page was changed"
echo "bath_table_quick: $rows rows for $readings readings, tables replaced between the markers"
