#!/bin/bash
# run_mpi_paired_results.sh — regenerates results/distributed/paired_*: frontsteal-mpi's schedulers on the
# cost cascade (cascade:20000) at 2 and 4 ranks on one node, decided by paired rounds (distributed/paired_rounds.hpp:
# 16 rounds of 8 frames per arm, arms in a random order per round, an A/A twin and a +10 % planted arm of the
# reference in the same run), once against static by space and once against static round robin; then 2 and 4 ranks
# split over two network namespaces (every byte over TCP, tests/distributed/two_namespaces_tcp.sh; needs root and
# ip(8)) against static by space. Needs a release build and a quiet machine; ~6 minutes on 2 vCPUs.
#   scripts/run_mpi_paired_results.sh [BUILD_DIR]      (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,7p' "$0"; exit 0 ;; esac
build=${1:-build/release}
mpi=$build/distributed/frontsteal-mpi
out=results/distributed
[ -x "$mpi" ] || { echo "run_mpi_paired_results: build $build first (frontsteal-mpi)"; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
for np in 2 4; do
  for ref in static-space static; do
    f=$out/paired_np${np}_cascade20000_vs_${ref}
    echo "run_mpi_paired_results: $np ranks against $ref"
    { uptime; timeout 900 mpirun --oversubscribe --mca mpi_yield_when_idle 1 -np $np "$mpi" --scene cascade:20000 \
        --frames 8 --rounds 16 --reference $ref --schedulers rma,rma-seeded,request,central,static,static-space \
        --watchdog-s 120 --json $f.json --markdown $f.md 2>&1; echo "exit status $?"; } > $f.txt
    sed -n '/^paired rounds/,/^$/p' $f.txt
  done
done
ns=tests/distributed/two_namespaces_tcp.sh
for spec in 2:1,1 4:2,2; do
  np=${spec%%:*}; f=$out/paired_np${np}_cascade20000_tcp_vs_static-space
  echo "run_mpi_paired_results: $np ranks over TCP (namespaces ${spec#*:}) against static-space"
  { uptime; NS_RANKS=${spec#*:} timeout 900 $ns mpirun "$mpi" --scene cascade:20000 --frames 8 --rounds 10 \
      --reference static-space --schedulers rma,request,central,static,static-space --watchdog-s 120 \
      --json $f.json --markdown $f.md 2>&1; echo "exit status $?"; } > $f.txt
  sed -n '/^paired rounds/,/^$/p' $f.txt
done
echo "run_mpi_paired_results: done"
