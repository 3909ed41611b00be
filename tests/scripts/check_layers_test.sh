#!/bin/sh
# The layer picture of docs/architecture.md against the include graph (scripts/check_layers.py):
#   match     the tree as it is passes;
#   planted   a copy of the tree with one real file of core/ including schedulers/ (the wrong way) fails, and
#             the message names that include; so does one of the scheduler library including the main job above
#             it (a sub-layer the picture names: schedulers/main_job/).
# Usage: check_layers_test.sh match|planted SOURCE_DIR
set -eu
mode=$1
src=$2
if [ "$mode" = match ]; then
  exec python3 "$src/scripts/check_layers.py" --root "$src"
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/docs"
cp "$src/docs/architecture.md" "$tmp/docs/"
(cd "$src" && find core measure reporting tessellate schedulers papers render distributed stress models_check \
  \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) -print | tar -cf - -T -) | tar -xf - -C "$tmp"
python3 "$src/scripts/check_layers.py" --root "$tmp" >/dev/null || { echo "FAIL: the unplanted copy fails"; exit 1; }
# plant FILE INCLUDE WHY MESSAGE: FILE (in the copy) includes INCLUDE; the check must fail and say MESSAGE.
plant() {
  printf '#pragma once\n#include "%s"  // planted: %s\n' "$2" "$3" >"$tmp/$1"
  if python3 "$src/scripts/check_layers.py" --root "$tmp" >"$tmp/out"; then
    echo "FAIL: the planted include of $2 in $1 passed"; exit 1
  fi
  grep -q "$4" "$tmp/out" || { cat "$tmp/out"; exit 1; }
  rm "$tmp/$1"
}
plant core/planted_wrong_way.hpp schedulers/registry.hpp "the protocol must not know the schedulers" \
  "FAIL: core/ includes schedulers/ (core/planted_wrong_way.hpp:2)"
plant schedulers/planted_upward.hpp schedulers/main_job/run.hpp "the library must not know the main job" \
  "FAIL: schedulers/ includes schedulers/main_job/ (schedulers/planted_upward.hpp:2)"
echo "PASS: both planted wrong-way includes are caught"
