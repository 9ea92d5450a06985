#!/usr/bin/env bash
# Each parameter's facts are written once (lib/declare.lua): in the repository's protocols and
# engine sources, checkpoint_every is declared only by the production stage, beta's range and
# help only by invasim.Contacts (src/lua/bind_contacts.cpp), the beta < alpha rule only in
# ContactParams::validate, and no protocol or stage declares its own range for a key that sets
# an engine field (beta, alpha, tau_p, f0, gamma, dt, P: lib/declare.lua; sweep specs, which
# list values, aside).
# Usage: one_declaration.sh SOURCE_DIR
set -euo pipefail
root=$1
cd "$root"
fail() { echo "FAILED: $1"; [ -n "${2:-}" ] && echo "$2"; exit 1; }
found=$(grep -rnE '^\s*checkpoint_every\s*=\s*\{' protocols || true)
[ "$(echo "$found" | grep -c .)" -eq 1 ] && echo "$found" | grep -q '^protocols/lib/production.lua:' ||
  fail "checkpoint_every is not declared once, by the production stage" "$found"
found=$(grep -rnE --exclude-dir=sweeps '^\s*(beta|alpha|tau_p|beta_cv|alpha_cv|f0|gamma|dt|P)\s*=\s*\{.*range = ' protocols || true)
[ -z "$found" ] || fail "a protocol declares an engine field's range itself" "$found"
found=$(grep -rn 'cohesion depth' src protocols || true)
[ "$(echo "$found" | grep -c .)" -eq 1 ] && echo "$found" | grep -q '^src/lua/bind_contacts.cpp:' ||
  fail "beta's help is not written once, in bind_contacts.cpp" "$found"
found=$(grep -rn 'must be smaller than alpha = ' src protocols || true)
[ "$(echo "$found" | grep -c .)" -eq 1 ] && echo "$found" | grep -q '^src/forces/contact_force.cpp:' ||
  fail "the beta < alpha rule is not written once, in contact_force.cpp" "$found"
echo "one_declaration: checkpoint_every, beta and tau_p declared once; beta < alpha checked once"
