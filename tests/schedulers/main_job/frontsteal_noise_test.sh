#!/bin/sh
# frontsteal_noise_test.sh — positive control of the main job's noise monitor, end to end: two CPU-bound
# children load the machine (two cores' worth) while a short main-job run measures; the run must print the
# noise warning and mark its verdicts unreliable.
#
# The children are always reaped: killed by PID on every exit path (trap), and each also dies by itself
# after 120 s (timeout) in case this shell is killed with SIGKILL and cannot run its trap.
# The negative control is deterministic and lives in noise_monitor_test.cpp (synthetic /proc samples): a
# "quiet" end-to-end run cannot be promised on a shared machine.
#
# usage: frontsteal_noise_test.sh FRONTSTEAL_BINARY OUT_DIR
set -u
bin=$1
out=$2
pids=""
cleanup() {
  for p in $pids; do kill "$p" 2>/dev/null; done
  for p in $pids; do wait "$p" 2>/dev/null; done
}
trap cleanup EXIT
trap 'exit 130' INT TERM HUP
for i in 1 2; do
  timeout 120 sh -c 'while :; do :; done' &
  pids="$pids $!"
done
sleep 0.5  # let the hogs reach the run queue before the "before" window opens
log=$("$bin" --scene plant:1201 --schedulers stealing/Fenced,queue-mutex --threads 1,2 --frames 8 --repeats 3 \
      --no-plot --quiet --out "$out" 2>&1)
rc=$?
echo "$log" | tail -n 12
[ $rc -eq 0 ] || { echo "FAIL: the run exited with $rc"; exit 1; }
echo "$log" | grep -q 'WARNING: [0-9]* of [0-9]* verdicts are marked unreliable' || { echo "FAIL: no noise warning under load"; exit 1; }
echo "$log" | grep -q 'unreliable (' || { echo "FAIL: no verdict marked unreliable"; exit 1; }
grep -q '"unreliable_verdicts": [1-9]' "$out/frontsteal.json" || { echo "FAIL: JSON does not count unreliable verdicts"; exit 1; }
echo "PASS: the loaded run was flagged"
