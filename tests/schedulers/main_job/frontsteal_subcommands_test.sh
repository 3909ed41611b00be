#!/bin/sh
# `frontsteal <subcommand>` for real: --help lists every subcommand; each subcommand whose program is built
# runs it (its --help is the program's own, byte for byte; exit 0); `calibrate --help` is the main job's help;
# an unknown subcommand exits 2 with a message; the bash completion offers the subcommands.
# Usage: frontsteal_subcommands_test.sh FRONTSTEAL SOURCE_DIR
set -eu
frontsteal=$1
src=$2
build=$(dirname "$(dirname "$frontsteal")")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

"$frontsteal" --help >"$tmp/help"
names=$(sed -n '/subcommands (/,/^$/p' "$tmp/help" | awk 'NR > 1 && NF { print $1 }')
[ "$(echo "$names" | wc -l)" -ge 11 ] || { echo "FAIL: --help lists too few subcommands:"; cat "$tmp/help"; exit 1; }
grep -q -- '--repeats' "$tmp/help" || { echo "FAIL: --help lacks the main job's options"; exit 1; }

for name in $names; do
  case $name in
    run|calibrate)
      "$frontsteal" "$name" --help >"$tmp/out" || { echo "FAIL: frontsteal $name --help"; exit 1; }
      cmp -s "$tmp/out" "$tmp/help" || { echo "FAIL: frontsteal $name --help is not the main job's"; exit 1; }
      ;;
    *)
      program=$(find "$build" -maxdepth 3 -type f -name "frontsteal-$name" -perm -u+x | head -n 1)
      [ "$name" = simulate ] && program=$(find "$build" -maxdepth 3 -type f -name frontsteal-paper | head -n 1)
      if [ -z "$program" ]; then
        echo "note: frontsteal-$name is not built here; frontsteal $name must say so"
        if "$frontsteal" "$name" --help >/dev/null 2>"$tmp/err"; then echo "FAIL: $name ran without its program"; exit 1; fi
        grep -q "not built here" "$tmp/err" || { echo "FAIL: $name: no clear message"; cat "$tmp/err"; exit 1; }
        continue
      fi
      "$frontsteal" "$name" --help >"$tmp/out" 2>&1 || { echo "FAIL: frontsteal $name --help exited $?"; exit 1; }
      if [ "$name" = simulate ]; then
        "$program" simulate --help >"$tmp/expected" 2>&1 || true
      else
        "$program" --help >"$tmp/expected" 2>&1 || true
      fi
      cmp -s "$tmp/out" "$tmp/expected" || { echo "FAIL: frontsteal $name --help differs from $program's"; exit 1; }
      ;;
  esac
done

if "$frontsteal" nosuch 2>"$tmp/err"; then echo "FAIL: an unknown subcommand ran"; exit 1; fi
grep -q "not a subcommand" "$tmp/err" || { echo "FAIL: unknown subcommand message"; cat "$tmp/err"; exit 1; }

# The completion offers subcommands from the command's own --help.
PATH=$(dirname "$frontsteal"):$PATH
export PATH
offered=$(bash -c ". '$src/completions/frontsteal.bash'; COMP_WORDS=(frontsteal pa); COMP_CWORD=1; _frontsteal; echo \"\${COMPREPLY[*]}\"")
[ "$offered" = paper ] || { echo "FAIL: completion of 'pa' offered '$offered'"; exit 1; }
offered=$(bash -c ". '$src/completions/frontsteal.bash'; COMP_WORDS=(frontsteal --rep); COMP_CWORD=1; _frontsteal; echo \"\${COMPREPLY[*]}\"")
[ "$offered" = --repeats ] || { echo "FAIL: completion of '--rep' offered '$offered'"; exit 1; }
echo "PASS: $(echo "$names" | wc -l) subcommands"
