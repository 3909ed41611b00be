#!/bin/bash
# die_post_mortem.sh — runs an MPI job with --ledger in a directory of its own (the job is expected to end
# because a rank dies, so its exit status is printed, not checked), then frontsteal-mpi --post-mortem on that
# directory; prints both. The directory is removed by a trap. run_mpi_case.sh checks the output.
#   die_post_mortem.sh FRONTSTEAL_MPI -- MPIEXEC ARGS...      (--ledger DIR is appended to ARGS)
set -u
prog=$1; shift
[ "${1:-}" = "--" ] && shift
dir=$(mktemp -d -t fs-ledger.XXXXXX)
trap 'rm -rf "$dir"' EXIT INT TERM
"$@" --ledger "$dir"
echo "die_post_mortem: the job exited with status $?"
"$prog" --post-mortem "$dir"
