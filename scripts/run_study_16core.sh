#!/usr/bin/env bash
# run_study_16core.sh — the P = 1 … 16 study in rounds, on a machine with 16 or more cores, in one bounded pass: the main
# job with its calibration arms (every scheduler, P = 1, 2, 4, 8, 16; random order within rounds; verdicts
# against the margin; the limit arm, P serial loops at once, and every row's loss account are part of every run),
# then P = 16 beside a co-runner pinned to worker 0's core. Each step under its own time limit; results land in
# OUT_DIR, one folder per step, with machine.txt and steps.txt (exit status, seconds). The prediction it is
# compared with is committed before the run (results/schedulers/study-16core-rounds/prediction-scale.md).
#
# Written for a borrowed machine with none of the project's packages: BIN_DIR holds the release executables
# (frontsteal, frontsteal-llvm-openmp) and, in BIN_DIR/lib, the shared libraries they need from this project's
# Debian 12 build. On a Debian 12 machine that ran bootstrap.sh, BIN_DIR can be a folder of links to
# build/release's executables. Plots: run with --no-plot there; `gnuplot frontsteal.gp` in each folder draws them.
#
# usage: run_study_16core.sh BIN_DIR OUT_DIR [--passes N] [--threads L] [--round-frames F]
#        (defaults: 3 passes, P = 1,2,4,8,16, rounds of 2 frames: ~6 min for the main step with the limit arm's
#        16 copies grown in the warm-up pass, within the device's 15 minutes with the start and the co-runner step)
set -uo pipefail

if [[ $# -lt 2 || $1 == --help || $1 == -h ]]; then
  sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$(cd "$1" && pwd) || { echo "run_study_16core.sh: BIN_DIR $1 does not exist" >&2; exit 2; }
out=$2
shift 2
passes=3 threads=1,2,4,8,16 round_frames=2
while [[ $# -gt 0 ]]; do
  case $1 in
    --passes) passes=$2; shift 2 ;;
    --round-frames) round_frames=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    *) echo "run_study_16core.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
done
mkdir -p "$out"
out=$(cd "$out" && pwd)
[[ -d $bin/lib ]] && export LD_LIBRARY_PATH="$bin/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
[[ -x $bin/frontsteal-llvm-openmp ]] && export FRONTSTEAL_LLVM_OPENMP="$bin/frontsteal-llvm-openmp"
{
  echo "date: $(date -u +%FT%TZ)"
  echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //')"
  echo "online cpus: $(nproc --all), usable here: $(nproc)"
  echo "kernel: $(uname -r)"
  echo "memory: $(grep MemTotal /proc/meminfo | awk '{print $2 / 1048576 " GiB"}')"
  echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
  command -v lscpu > /dev/null && lscpu | grep -E 'Model name|Socket|Core|Thread|NUMA node|L3|MHz' | sed 's/^/lscpu: /'
} > "$out/machine.txt" 2>&1
cat "$out/machine.txt"
"$bin/frontsteal" --help > /dev/null || { echo "run_study_16core.sh: $bin/frontsteal does not start" >&2; exit 3; }

step() {
  local name=$1 limit=$2
  shift 2
  local start=$SECONDS
  echo "== $name: limit ${limit} s, started $(date -u +%T)"
  timeout --kill-after=10 "$limit" "$@" > "$out/$name.log" 2>&1
  local rc=$?
  echo "$name rc=$rc seconds=$((SECONDS - start)) limit=$limit command: $*" | tee -a "$out/steps.txt"
  tail -n 40 "$out/$name.log"
  return 0
}

step main 420 "$bin/frontsteal" --threads "$threads" --calibrate --round-frames "$round_frames" --repeats "$passes" \
  --no-plot --out "$out/main"
step main-interference-pinned 120 "$bin/frontsteal" --threads 16 --interference 50,pinned --repeats 5 --no-plot \
  --out "$out/main-interference-pinned"
