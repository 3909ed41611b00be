#!/bin/bash
# run_mpi_tcp_results.sh — regenerates results/distributed/'s TCP results (two network namespaces, every byte over TCP):
# the one-sided latencies (calibration_np2_tcp.*), frontsteal-mpi at 2, 3 and 4 ranks with all four schedulers (np{2,3,4}_synthetic20000_tcp.*, plots in
# plots_np{2,3,4}_tcp/), the --owner-progress sweep (owner_progress_sweep_tcp.txt), the remote steal's latency
# in frames with the thief's one-Get view against word-by-word reads (5 interleaved rounds, steal_latency_tcp_np2.md),
# and the SIMULATED 2-256 ranks from the committed calibrations (simulated_ranks_2_256.*, plots in plots_simulated/;
# the cost cascade's 4-256, simulated_cascade_4_256.*, plot in plots_simulated_cascade/). Run it after
# scripts/run_mpi_cascade_results.sh, which regenerates the shared-memory calibration.
# Needs root and ip(8) (tests/distributed/two_namespaces_tcp.sh) and a release build. ~2 minutes.
#   scripts/run_mpi_tcp_results.sh [BUILD_DIR]      (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,10p' "$0"; exit 0 ;; esac
build=${1:-build/release}
mpi=$build/distributed/frontsteal-mpi
sim=$build/distributed/frontsteal-mpi-simulate
ns=tests/distributed/two_namespaces_tcp.sh
out=results/distributed
[ -x "$mpi" ] && [ -x "$sim" ] || { echo "run_mpi_tcp_results: build $build first (frontsteal-mpi, frontsteal-mpi-simulate)"; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
echo "run_mpi_tcp_results: the TCP calibration (calibration_np2_tcp.json)"
NS_RANKS=1,1 timeout 300 $ns mpirun "$mpi" --calibrate --json $out/calibration_np2_tcp.json > $out/calibration_np2_tcp.txt 2>&1
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
echo "run_mpi_tcp_results: remote steal latency, view against words (5 interleaved rounds)"
lat=$(mktemp -d)
for round in 1 2 3 4 5; do
  for reads in view words; do
    NS_RANKS=1,1 timeout 300 $ns mpirun "$mpi" --scene cascade:20000 --frames 30 --schedulers rma,hier --threads 1 \
      --quiet --watchdog-s 120 --thief-reads $reads --json $lat/${reads}_$round.json > $lat/${reads}_$round.txt 2>&1
  done
done
python3 - "$lat" > $out/steal_latency_tcp_np2.md <<'PY'
import glob, json, statistics, subprocess, sys
d = sys.argv[1]
print("# Remote steal latency over TCP: the thief's view against word-by-word reads (measured)\n")
first = json.load(open(sorted(glob.glob(d + "/view_*.json"))[0]))
models = [l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")]
cpu = f"{len(models)} x {models[0]}" if models else "unknown"
print(f"2 ranks x 1 thread in two network namespaces (TCP only, osc/pt2pt), cascade:20000, 30 frames, 5 rounds, "
      f"the two arms interleaved in each; commit {first.get('commit', '?')}; machine: {cpu}. "
      "Each cell: the median over the runs' per-rank medians (range in brackets); one-sided operations per "
      "successful steal as counted by the window. Regenerate: scripts/run_mpi_tcp_results.sh.\n")
print("| scheduler | reads | median steal (ms) | one-sided ops / steal | median frame (ms) |")
print("|---|---|---:|---:|---:|")
for sched in ("rma", "hier"):
    for reads in ("view", "words"):
        lat, ops, frame = [], [], []
        for f in sorted(glob.glob(f"{d}/{reads}_*.json")):
            for s in json.load(open(f))["schedulers"]:
                if s["name"] != sched:
                    continue
                frame.append(s["median_frame_ms"])
                for r in s["per_rank"]:
                    if r["steals"] > 0:
                        lat.append(r["steal_latency_median_us"] / 1000)
                        ops.append(r["one_sided_operations_per_steal"])
        if not lat:
            print(f"| {sched} | {reads} | no steal | | |")
            continue
        print(f"| {sched} | {reads} | {statistics.median(lat):.2f} [{min(lat):.2f}, {max(lat):.2f}] | "
              f"{statistics.median(ops):.1f} [{min(ops):.1f}, {max(ops):.1f}] | "
              f"{statistics.median(frame):.2f} [{min(frame):.2f}, {max(frame):.2f}] |")
PY
rm -rf "$lat"
echo "run_mpi_tcp_results: SIMULATED"
$sim --calibration $out/calibration_np2_shm.json,$out/calibration_np2_tcp.json --json $out/simulated_ranks_2_256.json \
  --markdown $out/simulated_ranks_2_256.md --plots $out/plots_simulated > $out/simulated_ranks_2_256.txt
$sim --shape cascade --ranks 4,16,64,256 --calibration $out/calibration_np2_shm.json,$out/calibration_np2_tcp.json \
  --json $out/simulated_cascade_4_256.json --markdown $out/simulated_cascade_4_256.md \
  --plots $out/plots_simulated_cascade > $out/simulated_cascade_4_256.txt
echo "run_mpi_tcp_results: done"
