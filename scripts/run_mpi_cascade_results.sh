#!/bin/bash
# run_mpi_cascade_results.sh — regenerates results/distributed/'s cost-cascade results (cascade:N, a workload whose
# cost concentrates in space: distributed/synthetic_cost.hpp): the shared-memory calibration the simulator reads
# (calibration_np2_shm.*), frontsteal-mpi at 2 and 4 ranks on one node with
# every scheduler (np{2,4}_cascade20000_shm.*), SIMULATED ranks x 16 threads with hier's loss
# account and the workload's own limits (simulated_hier_4_256x16.*, plot in plots_simulated_hier/; 2,000,000 items,
# and 8,000,000 at 256 ranks; at 256 ranks also without lifelines, _lifelines_off, and with one owner claim per
# item instead of batch claims, _one_claim_per_item), and the simulator validated against the 2-rank runs of both
# synthetic shapes (simulator_validation_np2.*; hier with one thread per rank: 4 ranks or 2 x 2 threads share 2
# vCPUs here, which the model does not model). Needs a release build and a quiet machine. ~2 minutes. Then
# scripts/run_mpi_tcp_results.sh: its SIMULATED rows (flat ranks, and the cascade's) read both calibrations.
# --simulated-only: only the SIMULATED files and the validation, from the committed calibration and measured runs
# (deterministic: about a minute, and the machine need not be quiet).
#   scripts/run_mpi_cascade_results.sh [--simulated-only] [BUILD_DIR]   (from the repository root; default build/release)
set -eu
case "${1:-}" in -h|--help) sed -n '2,15p' "$0"; exit 0 ;; esac
simulated_only=0
if [ "${1:-}" = --simulated-only ]; then simulated_only=1; shift; fi
build=${1:-build/release}
mpi=$build/distributed/frontsteal-mpi
sim=$build/distributed/frontsteal-mpi-simulate
out=results/distributed
[ -x "$mpi" ] && [ -x "$sim" ] || { echo "run_mpi_cascade_results: build $build first (frontsteal-mpi, frontsteal-mpi-simulate)"; exit 2; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
v=$out/np2_synthetic20000_validation_shm  # the validation's second measured run
if [ $simulated_only = 0 ]; then
echo "run_mpi_cascade_results: the shared-memory calibration (calibration_np2_shm.json)"
{ uptime; timeout 300 mpirun -np 2 "$mpi" --calibrate --json $out/calibration_np2_shm.json 2>&1; } \
  > $out/calibration_np2_shm.txt
for np in 2 4; do
  f=$out/np${np}_cascade20000_shm
  echo "run_mpi_cascade_results: $np ranks"
  { uptime; timeout 600 mpirun --oversubscribe --mca mpi_yield_when_idle 1 -np $np "$mpi" --scene cascade:20000 \
      --frames 20 --schedulers rma,rma-seeded,request,central,static,static-space,hier,hier-seeded --threads 1 \
      --watchdog-s 120 \
      --json $f.json --markdown $f.md 2>&1; echo "exit status $?"; } > $f.txt
done
echo "run_mpi_cascade_results: 2 ranks, synthetic:20000 (for the validation)"
{ uptime; timeout 600 mpirun -np 2 "$mpi" --scene synthetic:20000 --frames 10 --watchdog-s 120 --json $v.json 2>&1;
  echo "exit status $?"; } > $v.txt
fi
echo "run_mpi_cascade_results: SIMULATED ranks x 16 threads (about a minute)"
h=$out/simulated_hier_4_256x16
{ $sim --shape cascade --items 2000000 --ranks 4,16,64,256 --threads 16 --limits \
    --schedulers static,static-space,hier,hier-seeded --calibration $out/calibration_np2_shm.json \
    --json $h.json --markdown $h.md --plots $out/plots_simulated_hier
  $sim --shape cascade --items 8000000 --ranks 256 --threads 16 --schedulers static,static-space,hier,hier-seeded \
    --calibration $out/calibration_np2_shm.json --json ${h}_8M.json --markdown ${h}_8M.md
  $sim --shape cascade --items 2000000 --ranks 256 --threads 16 --schedulers hier,hier-seeded --lifelines off \
    --calibration $out/calibration_np2_shm.json --json ${h}_lifelines_off.json --markdown ${h}_lifelines_off.md
  $sim --shape cascade --items 2000000 --ranks 64,256 --threads 16 --schedulers hier,hier-seeded --batch-claims off \
    --calibration $out/calibration_np2_shm.json --json ${h}_one_claim_per_item.json \
    --markdown ${h}_one_claim_per_item.md; } > $h.txt
$sim --calibration $out/calibration_np2_shm.json --validate $out/np2_cascade20000_shm.json,$v.json \
  --json $out/simulator_validation_np2.json --markdown $out/simulator_validation_np2.md > $out/simulator_validation_np2.txt
echo "run_mpi_cascade_results: done"
