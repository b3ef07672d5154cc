#!/usr/bin/env bash
# run_schur.sh -- what a condensation costs (issue 24, route 2): K* of one
# part by MUMPS's Schur complement (ICNTL(19)) against the default route (a_ii
# factored, 2 nb triangular solves) and against a_ii factored alone, the
# three interleaved (bench/schur_parts.f90: medians of REPS), on one process
# and on two (mpirun -np 2: each process condenses its own copy at the same
# time on its own MUMPS instance, as the distributed path condenses the
# parts it owns). Parts: a plane panel, a shell panel, a frame (see
# schur_parts.f90). usage: bench/run_schur.sh [SOLVER] [REPS]
# Needs build-mpi/ (tools/build.sh -DSUPERJOIN_MPI=ON).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${SCHUR_COST:-$ROOT/build-mpi/tests/schur_parts}
SOLVER=${1:-mumps}
REPS=${2:-5}
export OPENBLAS_NUM_THREADS=1
mpi=(mpirun --allow-run-as-root --oversubscribe --quiet -np 2)
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
for part in "plane 150" "plane 150 bolts" "shell 70" "shell 70 bolts" "frame 12 40"; do
  # shellcheck disable=SC2086
  "$BIN" "$SOLVER" "$REPS" $part
  # shellcheck disable=SC2086
  "${mpi[@]}" "$BIN" "$SOLVER" "$REPS" $part
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
