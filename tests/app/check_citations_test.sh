#!/bin/bash
# scripts/check_citations.sh: the repository passes; a tree with a comment citing an issue
# number and a doc citing the model notes outside the repository fails, naming both lines.
# Usage: check_citations_test.sh REPO WORKDIR
set -euo pipefail
repo=$1 work=$2
rm -rf "$work" && mkdir -p "$work/bad/src" "$work/bad/docs"
fail() { echo "check_citations_test: FAIL: $*" >&2; exit 1; }
bash "$repo/scripts/check_citations.sh" "$repo" > "$work/repo.log" 2>&1 || { cat "$work/repo.log"; fail "the repository cites an issue or an outside file"; }
printf '// Fixed in issue 12: the wall force.\nint x;\n' > "$work/bad/src/a.cpp"
printf 'The model (see ../shared/MODEL.md) says so.\n' > "$work/bad/docs/b.md"
printf 'The paper, Sec. 2, Eq. (3).\n' > "$work/bad/docs/ok.md"
if bash "$repo/scripts/check_citations.sh" "$work/bad" > "$work/bad.log" 2>&1; then fail "a tree with bad citations passed"; fi
grep -q "src/a.cpp:1:// Fixed in issue 12" "$work/bad.log" || { cat "$work/bad.log"; fail "the issue number was not named"; }
grep -q "docs/b.md:1:The model (see ../shared/MODEL.md)" "$work/bad.log" || { cat "$work/bad.log"; fail "the outside file was not named"; }
grep -q "ok.md" "$work/bad.log" && fail "a citation of the paper was refused"
echo "check_citations_test: the repository passes, bad citations are named"
