#!/bin/sh
# clang-tidy (clang-tidy-14, from bootstrap.sh) with the repository's .clang-tidy:
#   match     the protocol core, the measurement engine and the simulation core, through the sources that
#             compile them (measure/*.cpp and their tests), have no finding;
#   planted   a use after move planted in a copy of a small source is found, and the message names it.
# Usage: check_tidy_test.sh match|planted SOURCE_DIR BUILD_DIR (BUILD_DIR holds compile_commands.json)
set -eu
mode=$1
src=$2
build=$3
tidy=$(command -v clang-tidy-14 || command -v clang-tidy) || { echo "FAIL: clang-tidy-14 not installed (bootstrap.sh)"; exit 1; }
[ -f "$build/compile_commands.json" ] || { echo "FAIL: no $build/compile_commands.json"; exit 1; }
if [ "$mode" = match ]; then
  cd "$src"
  files=$(ls measure/*.cpp tests/core/*.cpp tests/measure/*.cpp tests/papers/simulation/*.cpp)
  if ! "$tidy" -p "$build" --quiet $files >"${TMPDIR:-/tmp}/check_tidy.$$" 2>&1; then
    grep -E "(warning|error):" "${TMPDIR:-/tmp}/check_tidy.$$" | head -40
    rm -f "${TMPDIR:-/tmp}/check_tidy.$$"
    echo "FAIL: clang-tidy findings above (.clang-tidy)"; exit 1
  fi
  rm -f "${TMPDIR:-/tmp}/check_tidy.$$"
  echo "PASS: $(echo "$files" | wc -l) sources, no finding"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$src/.clang-tidy" "$tmp/"
cat >"$tmp/planted.cpp" <<'CPP'
#include <utility>
#include <vector>

#include "core/id_range.hpp"

std::size_t planted(std::vector<frontsteal::ItemId> ids) {
  std::vector<frontsteal::ItemId> kept = std::move(ids);
  return kept.size() + ids.size();  // planted: ids was moved from
}
CPP
if "$tidy" --quiet "$tmp/planted.cpp" -- -std=c++20 -I"$src" >"$tmp/out" 2>&1; then
  cat "$tmp/out"; echo "FAIL: the planted use after move passed"; exit 1
fi
grep -q "planted.cpp:.*bugprone-use-after-move" "$tmp/out" || { cat "$tmp/out"; echo "FAIL: not reported as a use after move"; exit 1; }
echo "PASS: the planted use after move is caught"
