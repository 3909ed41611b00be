#!/usr/bin/env bash
# run_study.sh — issue 17's P = 1 … 16 study on a machine with 16 or more cores, in one bounded pass: the main
# job (every scheduler, P = 1, 2, 4, 8, 12, 16; then at P = cores beside a co-runner, pinned and unpinned),
# Fig. 8 measured (P = 1 … cores) and simulated, and greedy rendering on the machine's GPU (frontsteal-render,
# then frontsteal-paper table2), each step under its own time limit so that one slow step cannot take the
# others' time. Results land in OUT_DIR, one folder per step, plus
# machine.txt (CPU, cores, GPU, kernel) and steps.txt (each step's exit status and seconds).
#
# It was written for a borrowed machine that has none of the project's packages: BIN_DIR holds the release
# executables and, in BIN_DIR/lib, the shared libraries they need from this project's Debian 12 build (oneTBB,
# libgomp, libomp, libglvnd's EGL/GL front ends, libpng, ...). On a Debian 12 machine that ran bootstrap.sh,
# BIN_DIR can simply be a folder with links to build/release's executables.
#
# usage: run_study.sh BIN_DIR OUT_DIR [--main-budget S] [--threads L] [--fig8-repeats R] [--fig8-scenes L]
#                     [--skip-gpu]   (defaults: 150 s, 1,2,4,8,12,16, 3 repeats, the three stand-ins)
# Plots: gnuplot need not be on the machine; every step writes its .gp script and .dat files, and
# `gnuplot NAME.gp` in the step's folder draws them afterwards.
set -uo pipefail

if [[ $# -lt 2 || $1 == --help || $1 == -h ]]; then
  sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$(cd "$1" && pwd) || { echo "run_study.sh: BIN_DIR $1 does not exist" >&2; exit 2; }
out=$2
shift 2
main_budget=150 threads=1,2,4,8,12,16 fig8_repeats=3 fig8_scenes=() gpu=1
while [[ $# -gt 0 ]]; do
  case $1 in
    --main-budget) main_budget=$2; shift 2 ;;
    --threads) threads=$2; shift 2 ;;
    --fig8-repeats) fig8_repeats=$2; shift 2 ;;
    --fig8-scenes) IFS=, read -r -a fig8_scenes <<< "$2"; shift 2 ;;
    --skip-gpu) gpu=0; shift ;;
    *) echo "run_study.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
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
  command -v nvidia-smi > /dev/null && nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader |
    sed 's/^/gpu: /'
} > "$out/machine.txt" 2>&1
cat "$out/machine.txt"

# Fail fast: every executable must start (a missing library shows here, in seconds, not after a long step).
for exe in frontsteal frontsteal-paper frontsteal-render; do
  if ! "$bin/$exe" --help > /dev/null 2> "$out/$exe-start.err"; then
    echo "run_study.sh: $bin/$exe does not start:" >&2
    cat "$out/$exe-start.err" >&2
    exit 3
  fi
  rm -f "$out/$exe-start.err"
done

# step NAME LIMIT_S COMMAND...: runs COMMAND under `timeout`, its output in NAME.log, one line in steps.txt.
step() {
  local name=$1 limit=$2
  shift 2
  local start=$SECONDS
  echo "== $name: limit ${limit} s, started $(date -u +%T)"
  timeout --kill-after=10 "$limit" "$@" > "$out/$name.log" 2>&1
  local rc=$?
  local line="$name rc=$rc seconds=$((SECONDS - start)) limit=$limit command: $*"
  echo "$line" | tee -a "$out/steps.txt"
  tail -n 25 "$out/$name.log"
  [[ -n ${STEP_HOOK:-} ]] && eval "$STEP_HOOK"
  return 0
}

# 1. The main job: every scheduler at P = 1, 2, 4, 8, 12, 16 (the default plant:15906, orbit-then-zoom).
step main $((main_budget + 120)) "$bin/frontsteal" --threads "$threads" --repeats auto --budget "$main_budget" \
  --no-plot --out "$out/main"
if [[ $gpu == 1 ]]; then
  # 2. Greedy rendering on the GPU: the default run (plant:4101, 30 updates/s), then as fast as it can draw.
  step render-default 60 "$bin/frontsteal-render" --out "$out/render-default"
  step render-p15906-max 60 "$bin/frontsteal-render" --scene plant:15906 --rate 0 --updates 300 --out "$out/render-p15906-max"
fi
# 3. Interference at P = cores (issue 17 §3): a co-runner child spinning 50 % of each 10 ms on one core, pinned
#    beside worker 0 (the asymmetric slowdown static lists cannot absorb), then unpinned (the OS places it).
cores=$(nproc)
step main-interference-pinned 120 "$bin/frontsteal" --threads "$cores" --repeats 10 --interference 50,pinned \
  --no-plot --out "$out/main-interference-pinned"
step main-interference-unpinned 120 "$bin/frontsteal" --threads "$cores" --repeats 10 --interference 50,unpinned \
  --no-plot --out "$out/main-interference-unpinned"
# 4. Fig. 8: static, queue, stealing, Chase-Lev measured at P = 1 ... cores, simulated to P = 64 with this
#    machine's calibration and traces; one step per stand-in (on the 16-core VM one run of all three with 5
#    repeats did not finish in 240 s; one stand-in with 3 repeats took 37-73 s).
[[ ${#fig8_scenes[@]} -eq 0 ]] && fig8_scenes=(plant:5302 plant:10604 plant:15906)
for scene in "${fig8_scenes[@]}"; do
  step "fig8-${scene//:/-}" 150 "$bin/frontsteal-paper" fig8 --repeats "$fig8_repeats" --scenes "$scene" --no-plot \
    --out "$out/fig8-${scene//:/-}"
done
if [[ $gpu == 1 ]]; then
  # 5. Table 2 (natural and tessellation-bound rows) with the GPU drawing.
  step table2 150 "$bin/frontsteal-paper" table2 --no-plot --out "$out/table2"
fi
echo "== done $(date -u +%T)"
cat "$out/steps.txt"
