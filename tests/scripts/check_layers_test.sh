#!/bin/sh
# The layer picture of docs/architecture.md against the include graph (scripts/check_layers.py):
#   match     the tree as it is passes;
#   planted   a copy of the tree with one real file of core/ including schedulers/ (the wrong way) fails, and
#             the message names that include.
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
printf '#pragma once\n#include "schedulers/registry.hpp"  // planted: the protocol must not know the schedulers\n' \
  >"$tmp/core/planted_wrong_way.hpp"
if python3 "$src/scripts/check_layers.py" --root "$tmp" >"$tmp/out"; then
  echo "FAIL: a planted core/ -> schedulers/ include passed"; exit 1
fi
grep -q "FAIL: core/ includes schedulers/ (core/planted_wrong_way.hpp:2)" "$tmp/out" || { cat "$tmp/out"; exit 1; }
echo "PASS: the planted wrong-way include is caught"
