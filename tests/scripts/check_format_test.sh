#!/bin/sh
# Every C++ source of the repository formatted as .clang-format says (clang-format-14, the version Debian 12
# ships; bootstrap.sh installs it):
#   match     the tree as it is passes;
#   planted   a copy of one real source with a line misformatted fails, and the message names that file.
# Usage: check_format_test.sh match|planted SOURCE_DIR
set -eu
mode=$1
src=$2
fmt=$(command -v clang-format-14 || command -v clang-format) || { echo "FAIL: clang-format-14 not installed (bootstrap.sh)"; exit 1; }
if [ "$mode" = match ]; then
  cd "$src"
  files=$(find core measure reporting tessellate schedulers papers render distributed stress models_check tests examples \
    \( -name '*.hpp' -o -name '*.cpp' -o -name '*.h' \) -print | sort)
  if ! "$fmt" --dry-run --Werror $files 2>"${TMPDIR:-/tmp}/check_format.$$"; then
    grep -o '^[^:]*\.[ch]pp' "${TMPDIR:-/tmp}/check_format.$$" | sort -u | sed 's/^/not formatted: /'
    echo "FAIL: run $fmt -i on the files above"; rm -f "${TMPDIR:-/tmp}/check_format.$$"; exit 1
  fi
  rm -f "${TMPDIR:-/tmp}/check_format.$$"
  echo "PASS: $(echo "$files" | wc -l) sources formatted"
  exit 0
fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cp "$src/.clang-format" "$tmp/"
cp "$src/core/id_range.hpp" "$tmp/id_range.hpp"
"$fmt" --dry-run --Werror "$tmp/id_range.hpp" || { echo "FAIL: the unplanted copy is not formatted"; exit 1; }
printf 'int   planted_misformatted ( ) {return 0 ;}\n' >>"$tmp/id_range.hpp"
if "$fmt" --dry-run --Werror "$tmp/id_range.hpp" 2>"$tmp/out"; then
  echo "FAIL: a misformatted line passed"; exit 1
fi
grep -q "id_range.hpp" "$tmp/out" || { cat "$tmp/out"; exit 1; }
echo "PASS: the planted misformatted line is caught"
