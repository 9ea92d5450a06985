#!/usr/bin/env bash
# `invasim --version` names the git revision the binary was built from (the version header is
# rewritten at every build, third_party/WriteVersion.cmake), "-dirty" when tracked files have
# uncommitted changes. Outside a git checkout or without git: skipped (77), or a failure under
# INVASIM_REQUIRE_ALL_TESTS=1 (tests/support/prerequisites.sh).
# Usage: version_revision.sh INVASIM SOURCE_DIR
set -u
invasim=$1
src=$2
source "$(dirname "$0")/../support/prerequisites.sh"
command -v git >/dev/null || skip_test "git is not installed" "git"
[ -e "$src/.git" ] || skip_test "$src is not a git checkout" "git"
expected=$(git -C "$src" rev-parse --short HEAD) || skip_test "git rev-parse fails in $src" "git"
[ -n "$(git -C "$src" status --porcelain --untracked-files=no)" ] && expected="$expected-dirty"
got=$("$invasim" --version | head -1)
if [[ "$got" != *"(git $expected)"* ]]; then
  echo "FAIL: expected the revision (git $expected) in: $got"
  exit 1
fi
echo "version revision: ok ($got)"
