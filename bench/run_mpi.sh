#!/usr/bin/env bash
# run_mpi.sh -- phase times of the MPI build on generated frames: CHOLMOD and
# MUMPS on one process, MUMPS under mpirun -np 2 (best of R runs per phase).
# usage: bench/run_mpi.sh [-r R] [SIZE...]   (SIZE for gen_frame --dofs; default 1e5)
# Needs build-mpi/ (tools/build.sh -DSUPERJOIN_MPI=ON) and build/tests/gen_frame.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${SUPERJOIN:-$ROOT/build-mpi/superjoin}
GEN=$ROOT/build-mpi/tests/gen_frame
SCRATCH=${BENCH_DIR:-$ROOT/build-mpi/bench}
R=3
if [ "${1:-}" = "-r" ]; then R=$2; shift 2; fi
[ $# -gt 0 ] || set -- 1e5
export OPENBLAS_NUM_THREADS=1
mkdir -p "$SCRATCH"
phases="assemble order factor solve health recover"
printf '%-8s %-14s %8s %8s %8s %8s %8s %8s %8s\n' size run $phases wall
for size in "$@"; do
  deck=$SCRATCH/frame_$size.deck
  "$GEN" --dofs "$size" "$deck" 2>/dev/null
  for run in cholmod mumps-np1 mumps-np2; do
    case $run in
      cholmod) cmd=("$BIN" --solver cholmod) ;;
      mumps-np1) cmd=("$BIN" --solver mumps) ;;
      mumps-np2) cmd=(mpirun --allow-run-as-root --oversubscribe --quiet -np 2 "$BIN" --solver mumps) ;;
    esac
    declare -A best=()
    for ((i = 1; i <= R; i++)); do
      t0=$(date +%s.%N)
      "${cmd[@]}" "$deck" -o "$SCRATCH/frame_$size.$run.lst" 2>"$SCRATCH/err.txt"
      t1=$(date +%s.%N)
      wall=$(echo "$t1 - $t0" | bc)
      for p in $phases wall; do
        if [ $p = wall ]; then v=$wall; else v=$(awk -v p="$p" '$2 == p {print $3}' "$SCRATCH/err.txt"); fi
        [ -n "${best[$p]:-}" ] && [ "$(echo "$v >= ${best[$p]}" | bc)" = 1 ] || best[$p]=$v
      done
    done
    printf '%-8s %-14s' "$size" "$run"
    for p in $phases wall; do printf ' %8.3f' "${best[$p]}"; done
    printf '\n'
    unset best
  done
done
