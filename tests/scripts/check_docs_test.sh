#!/bin/sh
# The docs cannot rot (scripts/check_docs.py):
#   pages     README.md, docs/*.md and every folder's README.md pass against the build;
#   planted   a page with a dead link, a path in backticks that does not exist, a flag the program does not have, a preset that does not exist and a
#             ctest filter that selects nothing fails, and each of the five is named.
# Usage: check_docs_test.sh pages|planted SOURCE_DIR BUILD_DIR
set -eu
mode=$1
src=$2
build=$3
if [ "$mode" = pages ]; then
  exec python3 "$src/scripts/check_docs.py" --root "$src" --build "$build"
fi
page="$src/docs/.planted-defects-$$.md"
trap 'rm -f "$page"' EXIT
cat >"$page" <<'PAGE'
[nowhere](no/such/file.md) and `core/no_such_header.hpp`
```sh
./build/release/schedulers/frontsteal --no-such-flag 3
cmake --workflow --preset no-such-preset
ctest --preset fast -R no_such_test_anywhere
```
PAGE
if python3 "$src/scripts/check_docs.py" --root "$src" --build "$build" "$page" >"$page.out"; then
  echo "FAIL: a page with five planted defects passed"; rm -f "$page.out"; exit 1
fi
status=0
for expected in "link to no/such/file.md" "core/no_such_header.hpp\` does not exist" "--no-such-flag is not in its --help" \
                "preset no-such-preset is not in CMakePresets.json" "no_such_test_anywhere selects no test"; do
  grep -q -- "$expected" "$page.out" || { echo "FAIL: not caught: $expected"; status=1; }
done
rm -f "$page.out"
[ $status = 0 ] && echo "PASS: all five planted defects caught"
exit $status
