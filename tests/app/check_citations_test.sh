#!/bin/bash
# scripts/check_citations.sh: the repository passes; a tree with a comment citing an issue
# number and a doc citing the model notes outside the repository fails, naming both lines.
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
if bash "$repo/scripts/check_citations.sh" "$work/bad" > "$work/bad.log" 2>&1; then fail "a tree with bad citations passed"; fi
grep -qF "src/a.cpp:1:$bad_comment" "$work/bad.log" || { cat "$work/bad.log"; fail "the issue number was not named"; }
grep -qF "docs/b.md:1:$bad_doc" "$work/bad.log" || { cat "$work/bad.log"; fail "the outside file was not named"; }
grep -q "ok.md" "$work/bad.log" && fail "a citation of the paper was refused"
echo "check_citations_test: the repository passes, bad citations are named"
