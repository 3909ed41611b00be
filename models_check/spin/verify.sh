#!/bin/sh
# verify.sh — one SPIN verification of stealing.pml: generate pan, compile it with gcc, run it, check the verdict.
#
#   verify.sh WORKDIR KIND EXPECT [-DNAME=VALUE ...]
#     WORKDIR  where pan.c, pan, out.txt and the trail go (created; one per run, so runs can go in parallel)
#     KIND     safety            assertions and invalid end states (-DSAFETY, DFS, -DCOLLAPSE)
#              acceptance:NAME   LTL property NAME (compiled with -DLIVENESS=1), pan -a, no fairness
#              fair:NAME         LTL property NAME, pan -a -f (weak fairness)
#     EXPECT   pass              "errors: 0" and a complete search ("max search depth too small" absent)
#              fail              at least one error (a counterexample trail is written)
#   Prints one line: verdict, states stored, memory, time. Exits 0 when the result is the expected one.
#   Environment: PAN_DEPTH (default 3000000), PAN_MEMLIM in MB (default 4000), SPIN (default spin), CC (gcc),
#   PAN_EXTRA (more pan options, e.g. -i for the shortest counterexample).
set -eu

here=$(cd "$(dirname "$0")" && pwd)
work=$1 kind=$2 expect=$3
shift 3
spin_bin=${SPIN:-spin}
cc=${CC:-gcc}
depth=${PAN_DEPTH:-3000000}
memlim=${PAN_MEMLIM:-4000}

if ! command -v "$spin_bin" >/dev/null 2>&1; then
  echo "verify.sh: '$spin_bin' not found (Debian package spin; ./bootstrap.sh installs it)" >&2
  exit 2
fi

mkdir -p "$work"
cp "$here/stealing.pml" "$work/stealing.pml"
cd "$work"
rm -f stealing.pml.trail pan pan.c out.txt

case $kind in
  safety)
    "$spin_bin" -a "$@" stealing.pml >spin.txt 2>&1
    "$cc" -O2 -w -DSAFETY -DCOLLAPSE -DMEMLIM="$memlim" -o pan pan.c
    pan_args="-m$depth"
    ;;
  acceptance:* | fair:*)
    name=${kind#*:}
    "$spin_bin" -a -DLIVENESS=1 "$@" stealing.pml >spin.txt 2>&1
    "$cc" -O2 -w -DCOLLAPSE -DMEMLIM="$memlim" -DNOREDUCE -DNFAIR=8 -o pan pan.c
    pan_args="-m$depth -a -N $name"
    case $kind in fair:*) pan_args="$pan_args -f" ;; esac
    ;;
  *) echo "verify.sh: unknown kind '$kind'" >&2; exit 2 ;;
esac

# pan exits non-zero on some errors; the verdict is read from its report.
# shellcheck disable=SC2086
./pan $pan_args ${PAN_EXTRA:-} >out.txt 2>&1 || true

errors=$(sed -n 's/.*errors: \([0-9]*\).*/\1/p' out.txt | tail -1)
states=$(sed -n 's/^ *\([0-9.e+]*\) states, stored.*/\1/p' out.txt | tail -1)
memory=$(sed -n 's/^ *\([0-9.]*\).total actual memory usage.*/\1/p' out.txt | tail -1)
seconds=$(sed -n 's/^pan: elapsed time \([0-9.e+-]*\) seconds.*/\1/p' out.txt | tail -1)
truncated=no
if grep -q "max search depth too small" out.txt; then truncated=yes; fi
if grep -q "out of memory\|pan: reached -DMEMLIM bound" out.txt; then truncated=yes; fi
what=$(grep -m1 "^pan:1:" out.txt | sed "s/^pan:1: //" || true)

if [ -z "$errors" ]; then
  verdict=incomplete
elif [ "$errors" = 0 ] && [ "$truncated" = no ]; then
  verdict=pass
elif [ "$errors" = 0 ]; then
  verdict=incomplete
else
  verdict=fail
fi

echo "verdict=$verdict expected=$expect states=${states:-?} memory_mb=${memory:-?} seconds=${seconds:-?} truncated=$truncated ${what:+($what)}"
if [ "$verdict" = "$expect" ]; then exit 0; fi
echo "verify.sh: unexpected verdict (see $work/out.txt)" >&2
tail -n 40 out.txt >&2
exit 1
