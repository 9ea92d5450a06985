#!/usr/bin/env bash
# invasim sets OMP_WAIT_POLICY=passive for itself when the user set neither it nor
# GOMP_SPINCOUNT (src/core/wait_policy.hpp), and leaves a user's choice alone.
# Usage: wait_policy.sh INVASIM
set -u
invasim=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
printf 'print("policy=" .. tostring(os.getenv("OMP_WAIT_POLICY")))\n' > "$work/p.lua"
fail=0
check() {  # check EXPECTED ENV-ARGS...
  local expected=$1
  shift
  local got
  got=$(cd "$work" && env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$@" "$invasim" run p.lua 2>&1)
  if ! grep -qx "policy=$expected" <<<"$got"; then
    echo "FAIL: with [$*] expected policy=$expected, got: $got"
    fail=1
  fi
}
check passive
check active OMP_WAIT_POLICY=active
check nil GOMP_SPINCOUNT=1000
[ $fail = 0 ] && echo "wait policy: ok"
exit $fail
