#!/bin/bash
# run_mpi_paired_results.sh — regenerates results/distributed/paired_*: frontsteal-mpi's schedulers on the cost
# cascade (cascade:20000, 2 us per mean item), decided by paired rounds (distributed/paired_rounds.hpp: 16 rounds
# of 8 frames per arm, arms in a random order per round, an A/A twin and a +10 % planted arm of the reference in
# the same run). On one node (osc/sm): 2 and 4 ranks, hier with 1 and 2 threads per rank (every other scheduler
# one thread per rank), against static by space and against hier itself. Over TCP (two network namespaces,
# tests/distributed/two_namespaces_tcp.sh; needs root and ip(8)): 2 and 4 ranks against static by space.
# Ranks are not bound to cores (--bind-to none: hier's threads need the cores of the node). Needs a release build
# and a quiet machine; ~12 minutes on 2 vCPUs.
#   scripts/run_mpi_paired_results.sh [BUILD_DIR]      (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,10p' "$0"; exit 0 ;; esac
build=${1:-build/release}
mpi=$build/distributed/frontsteal-mpi
out=results/distributed
[ -x "$mpi" ] || { echo "run_mpi_paired_results: build $build first (frontsteal-mpi)"; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
all=hier,hier-seeded,rma,rma-seeded,request,central,static,static-space
for cell in 2:1:static-space 2:1:hier 2:2:static-space 2:2:hier 4:1:static-space 4:1:hier 4:2:static-space; do
  IFS=: read -r np threads ref <<< "$cell"
  f=$out/paired_np${np}_t${threads}_cascade20000_vs_${ref}
  echo "run_mpi_paired_results: $np ranks, hier with $threads threads, against $ref"
  { uptime; timeout 900 mpirun --oversubscribe --bind-to none --mca mpi_yield_when_idle 1 -np $np "$mpi" \
      --scene cascade:20000 --frames 8 --rounds 16 --reference $ref --schedulers $all --threads $threads \
      --watchdog-s 120 --json $f.json --markdown $f.md 2>&1; echo "exit status $?"; } > $f.txt
  sed -n '/^paired rounds/,/^$/p' $f.txt
done
ns=tests/distributed/two_namespaces_tcp.sh
for spec in 2:1,1 4:2,2; do
  np=${spec%%:*}; f=$out/paired_np${np}_t1_cascade20000_tcp_vs_static-space
  echo "run_mpi_paired_results: $np ranks over TCP (namespaces ${spec#*:}) against static-space"
  { uptime; NS_RANKS=${spec#*:} timeout 900 $ns mpirun "$mpi" --scene cascade:20000 --frames 8 --rounds 10 \
      --reference static-space --schedulers hier,hier-seeded,rma,request,central,static,static-space --threads 1 \
      --watchdog-s 120 --json $f.json --markdown $f.md 2>&1; echo "exit status $?"; } > $f.txt
  sed -n '/^paired rounds/,/^$/p' $f.txt
done
echo "run_mpi_paired_results: done"
