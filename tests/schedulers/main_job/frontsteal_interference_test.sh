#!/bin/sh
# frontsteal_interference_test.sh — the main job's --interference end to end:
#   1. a short run with the co-runner pinned says so (stdout, JSON) and leaves no co-runner behind;
#   2. frontsteal killed with SIGKILL mid-run (no destructor runs) still takes its co-runner with it
#      (PR_SET_PDEATHSIG): after the kill the co-runner's pid is gone or a zombie (state Z: dead, waiting for
#      whoever inherited it to reap it), never running.
# No timing assertions: the kill happens once the co-runner has started, whenever that is.
#
# usage: frontsteal_interference_test.sh FRONTSTEAL_BINARY OUT_DIR
set -u
bin=$1
out=$2
mkdir -p "$out"
bgpid=""
cleanup() { [ -n "$bgpid" ] && kill -9 "$bgpid" 2>/dev/null; }
trap cleanup EXIT
trap 'exit 130' INT TERM HUP

# A process is alive when /proc/<pid>/stat exists and its state (the field after the ')') is not Z or X.
alive() {
  [ -r "/proc/$1/stat" ] || return 1
  state=$(sed 's/.*) \([A-Za-z]\).*/\1/' "/proc/$1/stat" 2>/dev/null)
  [ -n "$state" ] && [ "$state" != Z ] && [ "$state" != X ]
}

# 1. A short pinned run.
"$bin" --scene plant:300 --schedulers round-robin,stealing/Fenced --threads 2 --frames 2 --repeats 1 --path dense-zoom \
  --interference 50,pinned --no-plot --out "$out/short" > "$out/short.log" 2>&1
rc=$?
tail -n 20 "$out/short.log"
[ $rc -eq 0 ] || { echo "FAIL: the run with --interference exited with $rc"; exit 1; }
grep -q 'interference: ON, a co-runner child process busy-looping 50 % of one core, pinned' "$out/short.log" \
  || { echo "FAIL: the table does not say interference was on and pinned"; exit 1; }
grep -q 'round-robin cost spread' "$out/short.log" || { echo "FAIL: no round-robin cost spread line"; exit 1; }
grep -q '"setup": "pinned"' "$out/short/frontsteal.json" || { echo "FAIL: JSON lacks the interference set-up"; exit 1; }
grep -q '"path": "dense-zoom"' "$out/short/frontsteal.json" || { echo "FAIL: JSON lacks the path"; exit 1; }
cpid=$(sed -n 's/.*interference on: co-runner pid \([0-9]*\).*/\1/p' "$out/short.log" | head -n 1)
[ -n "$cpid" ] || { echo "FAIL: the co-runner's pid was not printed"; exit 1; }
if alive "$cpid"; then echo "FAIL: co-runner $cpid still runs after frontsteal exited"; exit 1; fi
echo "ok: co-runner $cpid reaped after a normal run"

# 2. SIGKILL mid-run: a long run in the background, killed once its co-runner has started.
"$bin" --scene plant:300 --schedulers round-robin --threads 2 --frames 50 --repeats 1000 --interference 100 \
  --no-plot --out "$out/killed" > "$out/killed.log" 2>&1 &
bgpid=$!
cpid=""
for i in $(seq 1 600); do  # up to 60 s on a loaded machine
  cpid=$(sed -n 's/.*interference on: co-runner pid \([0-9]*\).*/\1/p' "$out/killed.log" | head -n 1)
  [ -n "$cpid" ] && break
  sleep 0.1
done
[ -n "$cpid" ] || { echo "FAIL: the long run never started its co-runner"; exit 1; }
alive "$cpid" || { echo "FAIL: co-runner $cpid not running before the kill"; exit 1; }
kill -9 "$bgpid"
wait "$bgpid" 2>/dev/null
bgpid=""
for i in $(seq 1 100); do  # the kernel delivers PDEATHSIG at once; allow 10 s for a loaded machine
  alive "$cpid" || break
  sleep 0.1
done
if alive "$cpid"; then kill -9 "$cpid"; echo "FAIL: co-runner $cpid survived its parent's SIGKILL"; exit 1; fi
echo "PASS: the co-runner dies with frontsteal, also when frontsteal is killed"
