#!/usr/bin/env bash
# run_calibration_2core.sh — the calibration of the main job's method on this machine, regenerated: real experiments
# (one `frontsteal --calibrate` run each), a long run to resample experiments of a default run's size from, and
# the 2-core study (every path, without and with a pinned co-runner, each a default run with the calibration arms
# in it); then frontsteal-calibration-summary over all of it. Nothing else should run on the machine meanwhile
# (~70 min on a 2-vCPU VM).
#
#   small-N      frontsteal --schedulers queue-mutex --calibrate --repeats 5 --seed N   (N = 1 … RUNS)
#                the calibration arms with their base and the serial loop only, 5 passes: as many rounds per
#                comparison as a default run (120), in shorter rounds (6 arms instead of 15-19)
#   long-full    frontsteal --calibrate --repeats 8     (every scheduler: the default run's rounds, 192 per comparison)
#   study-PATH-SETUP  frontsteal --calibrate --path PATH [--interference 50,pinned]
#                PATH orbit-then-zoom (README command 1's), walkthrough, dense-zoom; SETUP none or pinned
#
# usage: run_calibration_2core.sh BUILD_DIR OUT_DIR [RUNS]   (RUNS default 20)
set -uo pipefail
if [[ $# -lt 2 || $1 == --help || $1 == -h ]]; then
  sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$1/schedulers/frontsteal summary=$1/schedulers/frontsteal-calibration-summary out=$2 runs=${3:-20}
mkdir -p "$out"
for i in $(seq 1 "$runs"); do
  "$bin" --schedulers queue-mutex --calibrate --repeats 5 --seed "$i" --no-plot --quiet --out "$out/small-$i" \
    > "$out/small-$i.log" 2>&1 || echo "small-$i: exit $?"
done
"$bin" --calibrate --repeats 8 --seed 101 --no-plot --quiet --out "$out/long-full" > "$out/long-full.log" 2>&1
seed=110
for path in orbit-then-zoom walkthrough dense-zoom; do
  for setup in none pinned; do
    seed=$((seed + 1))
    extra=()
    [[ $setup == pinned ]] && extra=(--interference 50,pinned)
    "$bin" --calibrate --path "$path" "${extra[@]}" --seed "$seed" --out "$out/study-$path-$setup" \
      > "$out/study-$path-$setup.log" 2>&1 || echo "study-$path-$setup: exit $?"
  done
done
small=()
for i in $(seq 1 "$runs"); do small+=("$out/small-$i/frontsteal-calibration.json"); done
"$summary" "${small[@]}" --long "$out/long-full/frontsteal-calibration.json" --rounds 120 --experiments 200 \
  --out "$out/summary-small"
study=("$out"/study-*/frontsteal-calibration.json)
"$summary" "${study[@]}" --long "$out/long-full/frontsteal-calibration.json" --rounds 120 --experiments 200 \
  --out "$out/summary-study"
