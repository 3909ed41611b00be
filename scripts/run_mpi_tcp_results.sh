#!/bin/bash
# run_mpi_tcp_results.sh — regenerates results/distributed/'s TCP results (two network namespaces, every byte over TCP):
# the one-sided latencies (calibration_np2_tcp.*), frontsteal-mpi at 2, 3 and 4 ranks with all four schedulers (np{2,3,4}_synthetic20000_tcp.*, plots in
# plots_np{2,3,4}_tcp/), the --owner-progress sweep (owner_progress_sweep_tcp.txt), and the SIMULATED
# 2-256 ranks from the committed calibrations (simulated_ranks_2_256.*, plots in plots_simulated/).
# Needs root and ip(8) (tests/distributed/two_namespaces_tcp.sh) and a release build. ~2 minutes.
#   scripts/run_mpi_tcp_results.sh [BUILD_DIR]      (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,7p' "$0"; exit 0 ;; esac
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
echo "run_mpi_tcp_results: SIMULATED"
$sim --calibration $out/calibration_np2_shm.json,$out/calibration_np2_tcp.json --json $out/simulated_ranks_2_256.json \
  --markdown $out/simulated_ranks_2_256.md --plots $out/plots_simulated > $out/simulated_ranks_2_256.txt
echo "run_mpi_tcp_results: done"
