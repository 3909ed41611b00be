#!/bin/bash
# run_mpi_case.sh — runs one frontsteal-mpi command (usually under mpirun) and checks its exit status, its
# wall time and its output, for the ctest entries of distributed/ (tests/CMakeLists.txt).
#   run_mpi_case.sh [--rc N | --rc nonzero] [--max-s S] [--grep ERE]... [--not-grep ERE]... [--co-runners N]
#                   -- command...
# --co-runners N: N busy loops (shell processes, not children of the command) run from before the command
# starts until it ends, so that the machine is busy for certain (the noise monitor's negative control).
# The command is killed after max-s + 30 s (so a hang fails the test instead of waiting for ctest's TIMEOUT),
# its output is printed in full, and the script exits 1 naming the first expectation that failed.
set -u
want_rc=0
max_s=120
greps=()
not_greps=()
co_runners=0
while [ $# -gt 0 ]; do
  case "$1" in
    --rc) want_rc=$2; shift 2 ;;
    --max-s) max_s=$2; shift 2 ;;
    --grep) greps+=("$2"); shift 2 ;;
    --not-grep) not_greps+=("$2"); shift 2 ;;
    --co-runners) co_runners=$2; shift 2 ;;
    --) shift; break ;;
    *) echo "run_mpi_case.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
loops=()
for _ in $(seq 1 "$co_runners"); do
  sh -c 'while :; do :; done' &
  loops+=($!)
done
stop_loops() { [ ${#loops[@]} -gt 0 ] && kill "${loops[@]}" 2>/dev/null; wait 2>/dev/null; }
trap stop_loops EXIT
start=$(date +%s%N)
out=$(timeout --kill-after=5 $((max_s + 30)) "$@" 2>&1)
rc=$?
stop_loops
loops=()
took=$(awk -v a="$start" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
echo "$out"
echo "run_mpi_case.sh: exit status $rc after ${took} s"
fail() { echo "run_mpi_case.sh: FAILED: $*"; exit 1; }
[ $rc -eq 77 ] && { echo "run_mpi_case.sh: skipped (exit status 77)"; exit 77; }
if [ "$want_rc" = nonzero ]; then
  [ $rc -ne 0 ] || fail "expected a non-zero exit status, got 0"
  [ $rc -ne 124 ] && [ $rc -ne 137 ] || fail "the command hung and was killed (status $rc)"
else
  [ $rc -eq "$want_rc" ] || fail "expected exit status $want_rc, got $rc"
fi
awk -v t="$took" -v m="$max_s" 'BEGIN { exit !(t <= m) }' || fail "took ${took} s, the limit is ${max_s} s"
for g in "${greps[@]+"${greps[@]}"}"; do
  echo "$out" | grep -Eq -- "$g" || fail "output lacks /$g/"
done
for g in "${not_greps[@]+"${not_greps[@]}"}"; do
  echo "$out" | grep -Eq -- "$g" && fail "output has /$g/"
done
echo "run_mpi_case.sh: passed"
