#!/bin/bash
# scripts/check_citations.sh: the repository passes; a tree with a comment citing an issue
# number and a doc citing the model notes outside the repository fails, naming both lines; a
# kept point's run record naming the machine's checkout is not prose and passes, while the
# README beside the kept points is checked.
# Usage: check_citations_test.sh REPO WORKDIR
set -euo pipefail
repo=$1 work=$2
rm -rf "$work" && mkdir -p "$work/bad/src" "$work/bad/docs"
fail() { echo "check_citations_test: FAIL: $*" >&2; exit 1; }
bash "$repo/scripts/check_citations.sh" "$repo" > "$work/repo.log" 2>&1 || { cat "$work/repo.log"; fail "the repository cites an issue or an outside file"; }
# The bad citations are assembled here, so that this file does not hold them itself.
tracker=issue notes=MODEL
bad_comment="// Fixed in $tracker 12: the wall force."
bad_doc="The model (see ../shared/$notes.md) says so."
printf '%s\nint x;\n' "$bad_comment" > "$work/bad/src/a.cpp"
printf '%s\n' "$bad_doc" > "$work/bad/docs/b.md"
printf 'The paper, Sec. 2, Eq. (3).\n' > "$work/bad/docs/ok.md"
checkout=/work/$(echo main)
point=$work/bad/docs/data/runs/sweep/0123456789abcdef0123456789abcdef
mkdir -p "$point"
printf '{"protocol": "%s/protocols/invasion.lua"}\n' "$checkout" > "$point/params.json"
printf 'Restore from %s/docs/data/runs.\n' "$checkout" > "$work/bad/docs/data/runs/README.md"
if bash "$repo/scripts/check_citations.sh" "$work/bad" > "$work/bad.log" 2>&1; then fail "a tree with bad citations passed"; fi
grep -qF "src/a.cpp:1:$bad_comment" "$work/bad.log" || { cat "$work/bad.log"; fail "the issue number was not named"; }
grep -qF "docs/b.md:1:$bad_doc" "$work/bad.log" || { cat "$work/bad.log"; fail "the outside file was not named"; }
grep -q "ok.md" "$work/bad.log" && fail "a citation of the paper was refused"
grep -q "params.json" "$work/bad.log" && fail "a kept point's run record was refused"
grep -qF "docs/data/runs/README.md:1:" "$work/bad.log" || { cat "$work/bad.log"; fail "the README beside the kept points was not checked"; }
echo "check_citations_test: the repository passes, bad citations are named"
