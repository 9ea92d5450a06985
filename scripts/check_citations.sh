#!/usr/bin/env bash
# Checks that comments and docs speak of the repository as it is (docs/architecture.md,
# "Tests and benchmarks"): no tracked file cites a tracker's issue number or a file outside the
# repository (the model notes, the machine's own paths); `pattern` below lists the forms. The
# paper is cited by section, figure and equation; history lives in the git log.
# Prints every offending line and exits 1 if there is one.
# Usage: check_citations.sh [REPO]   (default: the repository holding this script)
# Files that must name such paths to test their refusal are listed in ALLOWED. A kept point's
# files (docs/data/runs/<workspace>/<32-hex id>/, written by the program, not by an author)
# record where the run happened, so they are not prose and RUN_RECORDS skips them.
set -euo pipefail
repo=${1:-$(cd "$(dirname "$0")/.." && pwd)}
cd "$repo"
ALLOWED='^(tests/analysis/check_validation\.py|scripts/invasim_analysis/validation/citations\.py|scripts/check_citations\.sh|tests/app/check_citations_test\.sh)$'
RUN_RECORDS='^docs/data/runs/[^/]+/[0-9a-f]{32}/'
pattern='\b[Ii]ssues? #?[0-9]+|\b[Ii]ssue #[0-9]+|MODEL\.md|ARCHITECTURE\.md|SLURM\.md|\.\./shared/|/work/shared|/work/main|/work/wt/'
# The tracked files of a git checkout; any other tree (or a directory inside one): all files.
if [ "$(git rev-parse --show-toplevel 2>/dev/null)" = "$(pwd -P)" ]; then
  files=$(git ls-files)
else
  files=$(find . -type f ! -path './build*' ! -path './.git/*' | sed 's|^\./||')
fi
bad=$(printf '%s\n' "$files" | grep -Ev "$ALLOWED" | grep -Ev "$RUN_RECORDS" | grep -Ev '\.(png|svg|ckpt|bin)$' \
      | tr '\n' '\0' | xargs -0 grep -nIE "$pattern" 2>/dev/null || true)
if [ -n "$bad" ]; then
  printf '%s\n' "$bad"
  echo "check_citations: the lines above cite an issue number or a file outside the repository" >&2
  exit 1
fi
echo "check_citations: no tracked file cites an issue number or a file outside the repository"
