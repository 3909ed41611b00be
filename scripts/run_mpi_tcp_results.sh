#!/bin/bash
# run_mpi_tcp_results.sh — regenerates results/distributed/'s TCP results (two network namespaces, every byte over TCP):
# the one-sided latencies (calibration_np2_tcp.*; over osc/ucx with a progress thread, calibration_np2_tcp_ucx.*), frontsteal-mpi at 2, 3 and 4 ranks with all four schedulers (np{2,3,4}_synthetic20000_tcp.*, plots in
# plots_np{2,3,4}_tcp/), the --owner-progress sweep (owner_progress_sweep_tcp.txt), the remote steal's latency
# in frames: the thief's one-Get view against word-by-word reads, and osc/pt2pt against osc/ucx with and without
# a progress thread (5 interleaved rounds, steal_latency_tcp_np2.md),
# and the SIMULATED 2-256 ranks from the committed calibrations (simulated_ranks_2_256.*, plots in plots_simulated/;
# the cost cascade's 4-256, simulated_cascade_4_256.*, plot in plots_simulated_cascade/). Run it after
# scripts/run_mpi_cascade_results.sh, which regenerates the shared-memory calibration.
# Needs root and ip(8) (tests/distributed/two_namespaces_tcp.sh) and a release build. ~6 minutes.
# --simulated-only: only the SIMULATED files, from the committed calibrations (deterministic; under a minute).
#   scripts/run_mpi_tcp_results.sh [--simulated-only] [BUILD_DIR]   (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,12p' "$0"; exit 0 ;; esac
simulated_only=0
if [ "${1:-}" = --simulated-only ]; then simulated_only=1; shift; fi
build=${1:-build/release}
mpi=$build/distributed/frontsteal-mpi
sim=$build/distributed/frontsteal-mpi-simulate
ns=tests/distributed/two_namespaces_tcp.sh
out=results/distributed
[ -x "$mpi" ] && [ -x "$sim" ] || { echo "run_mpi_tcp_results: build $build first (frontsteal-mpi, frontsteal-mpi-simulate)"; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
if [ $simulated_only = 0 ]; then
echo "run_mpi_tcp_results: the TCP calibration (calibration_np2_tcp.json)"
NS_RANKS=1,1 timeout 300 $ns mpirun "$mpi" --calibrate --json $out/calibration_np2_tcp.json > $out/calibration_np2_tcp.txt 2>&1
echo "run_mpi_tcp_results: the TCP calibration over osc/ucx with a progress thread (calibration_np2_tcp_ucx.json)"
NS_RANKS=1,1 NS_OSC=ucx timeout 300 $ns mpirun "$mpi" --calibrate --progress-thread 0 \
  --json $out/calibration_np2_tcp_ucx.json > $out/calibration_np2_tcp_ucx.txt 2>&1
for spec in 2:1,1 3:2,1 4:2,2; do
  np=${spec%%:*}; f=$out/np${np}_synthetic20000_tcp
  echo "run_mpi_tcp_results: $np ranks (namespaces ${spec#*:})"
  { uptime; NS_RANKS=${spec#*:} timeout 300 $ns mpirun "$mpi" --scene synthetic:20000 --frames 10 --watchdog-s 120 \
      --json $f.json --markdown $f.md --plots $out/plots_np${np}_tcp 2>&1; echo "exit status $?"; } > $f.txt
done
echo "run_mpi_tcp_results: --owner-progress sweep"
{
  echo "# 2 ranks over TCP (two namespaces), synthetic:40000 --work-ns 1000 --skew 20, 10 frames, rma and static"
  echo "# per --owner-progress value; measured $(date -u +%F) on $(nproc) CPUs; $(uptime)"
  for op in 0 10 25 50 100 200 off; do
    echo "== --owner-progress $op"
    timeout 300 $ns mpirun "$mpi" --scene synthetic:40000 --work-ns 1000 --skew 20 --quiet --frames 10 \
      --watchdog-s 120 --owner-progress $op --schedulers rma,static 2>&1 | grep -E "^(frontsteal-mpi: 2|sched|rma|static|  |medians| *\()"
  done
} > $out/owner_progress_sweep_tcp.txt
echo "run_mpi_tcp_results: remote steal latency: the thief's reads and the target's progress (5 interleaved rounds)"
lat=$(mktemp -d)
# Each arm: name | NS_OSC | frontsteal-mpi options. The owner's progress calls (auto: every 50 us) run in every arm.
arms=("view|pt2pt|--thief-reads view" "words|pt2pt|--thief-reads words" "ucx|ucx|" "ucx-thread-yield|ucx|--progress-thread 0"
      "ucx-thread-sleep50|ucx|--progress-thread 50")
for round in 1 2 3 4 5; do
  for arm in "${arms[@]}"; do
    IFS='|' read -r name osc args <<< "$arm"
    # shellcheck disable=SC2086  # args is a list of options
    NS_RANKS=1,1 NS_OSC=$osc timeout 300 $ns mpirun "$mpi" --scene cascade:20000 --frames 30 --schedulers rma,hier \
      --threads 1 --quiet --watchdog-s 30 $args --json $lat/${name}_$round.json > $lat/${name}_$round.txt 2>&1 || true
  done
done
python3 - "$lat" > $out/steal_latency_tcp_np2.md <<'PY'
import glob, json, statistics, sys
d = sys.argv[1]
print("# Remote steal latency over TCP: the thief's reads and the target's progress (measured)\n")
first = json.load(open(sorted(glob.glob(d + "/view_*.json"))[0]))
models = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")]
cpu = f"{len(models)} x {models[0]}" if models else "unknown"
print(f"2 ranks x 1 thread in two network namespaces (TCP only), cascade:20000, 30 frames, 5 rounds, the arms "
      f"interleaved in each; commit {first.get('commit', '?')}; machine: {cpu}. Every arm has the busy owner's "
      "MPI_Iprobe at most every 50 us. Each cell: the median over the runs' per-rank medians (range in brackets); "
      "one-sided operations per successful steal as counted by the window; runs: those that ended, and those "
      "the watchdog ended after 30 s without progress (hung). Regenerate: scripts/run_mpi_tcp_results.sh.\n")
arms = {
    "view": "osc/pt2pt, the thief's view (default)",
    "words": "osc/pt2pt, word-by-word reads",
    "ucx": "osc/ucx (UCX over TCP), no progress thread",
    "ucx-thread-yield": "osc/ucx, progress thread yielding between calls",
    "ucx-thread-sleep50": "osc/ucx, progress thread sleeping 50 us between calls",
}
print("| scheduler | arm | median steal (ms) | steals / run | one-sided ops / steal | median frame (ms) | runs |")
print("|---|---|---:|---:|---:|---:|---:|")
rng = lambda v, f: f"{statistics.median(v):{f}} [{min(v):{f}}, {max(v):{f}}]"
for sched in ("rma", "hier"):
    for arm, label in arms.items():
        lat, ops, frame, steals = [], [], [], []
        files = sorted(glob.glob(f"{d}/{arm}_*.txt"))
        ended = hung = 0
        for t in files:
            try:
                doc = json.load(open(t[:-4] + ".json"))
            except (OSError, ValueError):
                hung += "WATCHDOG" in open(t, errors="replace").read()
                continue
            ended += 1
            for s in doc["schedulers"]:
                if s["name"] != sched:
                    continue
                frame.append(s["median_frame_ms"])
                steals.append(sum(r["steals"] for r in s["per_rank"]))
                for r in s["per_rank"]:
                    if r["steals"] > 0:
                        lat.append(r["steal_latency_median_us"] / 1000)
                        ops.append(r["one_sided_operations_per_steal"])
        failed = len(files) - ended - hung
        runs = f"{ended} of {len(files)}" + (f"; {hung} hung" if hung else "") + (f"; {failed} failed" if failed else "")
        if not lat:
            print(f"| {sched} | {label} | no steal | | | | {runs} |")
            continue
        print(f"| {sched} | {label} | {rng(lat, '.2f')} | {rng(steals, '.0f')} | {rng(ops, '.1f')} | "
              f"{rng(frame, '.2f')} | {runs} |")
PY
rm -rf "$lat"
fi
echo "run_mpi_tcp_results: SIMULATED"
$sim --calibration $out/calibration_np2_shm.json,$out/calibration_np2_tcp.json --json $out/simulated_ranks_2_256.json \
  --markdown $out/simulated_ranks_2_256.md --plots $out/plots_simulated > $out/simulated_ranks_2_256.txt
$sim --shape cascade --ranks 4,16,64,256 --calibration $out/calibration_np2_shm.json,$out/calibration_np2_tcp.json \
  --json $out/simulated_cascade_4_256.json --markdown $out/simulated_cascade_4_256.md \
  --plots $out/plots_simulated_cascade > $out/simulated_cascade_4_256.txt
echo "run_mpi_tcp_results: done"
