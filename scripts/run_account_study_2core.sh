#!/usr/bin/env bash
# run_account_study_2core.sh — the measured loss accounts the simulator's per-term validation reads
# (`frontsteal-paper scale --study OUT_DIR`): the main job on three camera paths, with the schedulers the simulator
# models (round-robin, queue-mutex, stealing/Fenced, chase-lev) at P = 1 and 2 and the limit arm, rounds in random
# order, --repeats auto within --budget. One folder per path, PATH-none, each with frontsteal.json (schema 4: the
# account of every row). Nothing else should run on the machine meanwhile (~3 min per path on a 2-vCPU VM).
#
# usage: run_account_study_2core.sh BUILD_DIR OUT_DIR [BUDGET_S]   (BUDGET_S default 120)
set -uo pipefail
if [[ $# -lt 2 || $1 == --help || $1 == -h ]]; then
  sed -n '2,8p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$1/schedulers/frontsteal out=$2 budget=${3:-120}
[[ -x $bin ]] || { echo "run_account_study_2core.sh: $bin is not built" >&2; exit 2; }
mkdir -p "$out"
seed=210
for path in orbit-then-zoom walkthrough dense-zoom; do
  seed=$((seed + 1))
  "$bin" --schedulers round-robin,queue-mutex,stealing/Fenced,chase-lev --threads 1,2 --path "$path" \
    --budget "$budget" --seed "$seed" --no-plot --quiet --out "$out/$path-none" > "$out/$path-none.log" 2>&1 ||
    echo "$path-none: exit $?"
  echo "$path-none: $(grep -c . "$out/$path-none.log") lines of log, $(ls "$out/$path-none" | wc -l) files"
done
