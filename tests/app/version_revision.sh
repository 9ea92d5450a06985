#!/usr/bin/env bash
# `invasim --version` names the git revision the binary was built from (the version header is
# rewritten at every build, third_party/WriteVersion.cmake), "-dirty" when tracked files have
# uncommitted changes. Skipped (77) outside a git checkout or without git.
# Usage: version_revision.sh INVASIM SOURCE_DIR
set -u
invasim=$1
src=$2
command -v git >/dev/null && [ -e "$src/.git" ] || { echo "not a git checkout: skipped"; exit 77; }
expected=$(git -C "$src" rev-parse --short HEAD) || exit 77
[ -n "$(git -C "$src" status --porcelain --untracked-files=no)" ] && expected="$expected-dirty"
got=$("$invasim" --version | head -1)
if [[ "$got" != *"(git $expected)"* ]]; then
  echo "FAIL: expected the revision (git $expected) in: $got"
  exit 1
fi
echo "version revision: ok ($got)"
