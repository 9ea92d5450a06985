#!/usr/bin/env bash
# Checks that the #include graph of src/ runs one way (docs/architecture.md, "Layers"): every
# quoted include "dir/file" of a file in src/<layer>/ must name its own layer or one the table
# below allows. Prints every include that goes the wrong way and exits 1 if there is one.
# Usage: check_layers.sh [SRC_DIR]   (default: the src/ next to this script)
set -euo pipefail
src=${1:-$(cd "$(dirname "$0")/../src" && pwd)}
declare -A allowed=(
  [core]=""
  [mesh]="core"
  [state]="mesh core"
  [neighbor]="state mesh core"
  [forces]="neighbor state mesh core"
  [integrate]="forces neighbor state mesh core"
  [measure]="state mesh core"
  [io]="state mesh core"
  [setup]="integrate measure forces neighbor state mesh core"
  [checkpoint]="integrate measure io forces neighbor state mesh core"
  [run]="checkpoint setup integrate measure io forces neighbor state mesh core"
  [lua]="run checkpoint setup integrate measure io forces neighbor state mesh core"
  [sweep]="lua measure io core"
  [app]="sweep lua run checkpoint setup integrate measure io forces neighbor state mesh core"
)
bad=0
while IFS= read -r line; do
  file=${line%%:*}
  from=${file#"$src"/}
  from=${from%%/*}
  [[ ${line#*:*:} =~ \#include\ \"([^\"]*)\" ]] || continue
  target=${BASH_REMATCH[1]}
  [[ $target == */* ]] || continue  # generated headers (invasim_version.hpp)
  to=${target%%/*}
  [[ $to == "$from" ]] && continue
  if [[ ! -v allowed[$from] ]]; then
    echo "unknown layer src/$from (add it to $0 and docs/architecture.md): $line"
    bad=1
  elif [[ " ${allowed[$from]} " != *" $to "* ]]; then
    echo "wrong-way include: $line ($from may include: ${allowed[$from]:-nothing})"
    bad=1
  fi
done < <(grep -rn '#include "' "$src" --include='*.cpp' --include='*.hpp')
[[ $bad == 0 ]] && echo "layers: every include of $src runs one way"
exit $bad
