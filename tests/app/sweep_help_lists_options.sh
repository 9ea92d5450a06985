#!/bin/bash
# Every option a sweep verb accepts is in that verb's block of `invasim sweep --help`: the
# options are read from the verb's own "unknown option" message ("it takes --a, --b and --c"),
# so an option added to a parser and not to the help text fails here.
# Usage: sweep_help_lists_options.sh INVASIM
set -euo pipefail
invasim=$1
help=$("$invasim" sweep --help)
checked=0
for verb in init run status collect submit job; do
  # The verb's block: from its usage line to the next "  invasim sweep" line. Every reader
  # below takes a here-string, not a pipe: a reader that stops early (awk's exit, grep -q's
  # first match) would leave printf writing into a closed pipe, and under pipefail that
  # SIGPIPE reads as a failed search, now and then, by timing alone.
  block=$(awk -v v="  invasim sweep $verb " '
    index($0, v) == 1 { on = 1; print; next }
    on && /^  invasim sweep / { exit }
    on { print }' <<< "$help")
  [ -n "$block" ] || { echo "no block for 'sweep $verb' in sweep --help"; exit 1; }
  message=$("$invasim" sweep "$verb" ws --no-such-option 2>&1 >/dev/null || true)
  takes=$(sed -n "s/.*unknown option '--no-such-option' (it takes \([^)]*\)).*/\1/p" <<< "$message")
  [ -n "$takes" ] || { echo "sweep $verb: no option list in: $message"; exit 1; }
  [ "$takes" = none ] && continue
  for option in $(tr ',' ' ' <<< "$takes" | sed 's/ and / /g'); do
    if ! grep -q -- "\[$option\b\|^ *invasim sweep $verb .*$option" <<< "$block"; then
      echo "sweep $verb accepts $option, but its block of sweep --help does not list it:"
      printf '%s\n' "$block"
      exit 1
    fi
    checked=$((checked + 1))
  done
done
[ "$checked" -ge 20 ] || { echo "only $checked options checked"; exit 1; }
echo "sweep help lists all $checked options"
