#!/usr/bin/env bash
# run_mpi_owner.sh -- owner terms (issue 14) against the broadcast of every K*
# (the previous increment, SUPERJOIN_BROADCAST_KSTAR=1) on the modules models
# of bench/gen_modules.py --row: distinct parts (--explicit, one substructure
# per module: the frame with many parts) and identical instances of one part.
# Per run: wall clock, the assemble phase (it holds the condensations), peak
# resident memory of every process (/usr/bin/time), and from the MPI summary
# on stderr the bytes each process passed to collectives and the entries of
# the reduced matrix it assembled. One process: --solver mumps --condense yes
# (what the MPI runs are compared with in the tests).
# With --strip instead: bench/gen_strip.py, N panels joined edge to edge
# (parts whose boundaries are large, so K* outweighs their interiors).
# usage: bench/run_mpi_owner.sh [--strip] [-n MODULES] M...   (M: elements per slab side)
# Needs build-mpi/ (tools/build.sh -DSUPERJOIN_MPI=ON).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${SUPERJOIN:-$ROOT/build-mpi/superjoin}
SCRATCH=${BENCH_DIR:-$ROOT/build-mpi/bench_owner}
N=16
kinds="explicit instances"
if [ "${1:-}" = "--strip" ]; then kinds=strip; shift; fi
if [ "${1:-}" = "-n" ]; then N=$2; shift 2; fi
[ $# -gt 0 ] || set -- 40
export OPENBLAS_NUM_THREADS=1
mkdir -p "$SCRATCH"
mpi=(mpirun --allow-run-as-root --oversubscribe --quiet -np 2)
timed=(bash -c '/usr/bin/time -f "%M" -o "$0.${OMPI_COMM_WORLD_RANK:-0}" "$@"')
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-10s %-4s %8s %-10s %7s %9s %10s %14s %16s\n' model M DOFs run wall assemble 'peak MB' 'collectives B' 'matrix entries'
for m in "$@"; do
  for kind in $kinds; do
    deck=$SCRATCH/modules_${kind}_$m.deck
    if [ $kind = strip ]; then
      python3 "$ROOT/bench/gen_strip.py" --panels "$N" --mesh "$m" >"$deck"
    elif [ $kind = explicit ]; then
      python3 "$ROOT/bench/gen_modules.py" --row --mesh "$m" --storeys "$N" --explicit >"$deck"
    else
      python3 "$ROOT/bench/gen_modules.py" --row --mesh "$m" --storeys "$N" >"$deck"
    fi
    for run in np1 np2-bcast np2-owner; do
      out=$SCRATCH/$kind.$m.$run
      rm -f "$out".mem.*
      t0=$(date +%s.%N)
      case $run in
        np1) "${timed[@]}" "$out.mem" "$BIN" --solver mumps --condense yes "$deck" -o "$out.lst" 2>"$out.err" ;;
        np2-bcast) SUPERJOIN_BROADCAST_KSTAR=1 "${mpi[@]}" -x SUPERJOIN_BROADCAST_KSTAR "${timed[@]}" "$out.mem" \
                     "$BIN" "$deck" -o "$out.lst" 2>"$out.err" ;;
        np2-owner) "${mpi[@]}" "${timed[@]}" "$out.mem" "$BIN" "$deck" -o "$out.lst" 2>"$out.err" ;;
      esac
      t1=$(date +%s.%N)
      dofs=$(sed -n 's/^  active DOFs  *\([0-9]*\)$/\1/p' "$out.lst")
      asm=$(awk '$2 == "assemble" {print $3}' "$out.err")
      mem=$(for f in "$out".mem.*; do echo $(( $(tail -1 "$f") / 1024 )); done | paste -sd/)
      coll=$(sed -n 's/^superjoin: MPI process [0-9]*: collectives \([0-9]*\) bytes.*/\1/p' "$out.err" | paste -sd/)
      held=$(sed -n 's/^superjoin: MPI process [0-9]*: .* matrix assembled \([0-9]*\) entries.*/\1/p' "$out.err" | paste -sd/)
      [ -n "$held" ] || held=$(sed -n 's/^  matrix nonzeros (upper)  *\([0-9]*\)$/\1/p' "$out.lst")
      printf '%-10s %-4s %8s %-10s %7.2f %9s %10s %14s %16s\n' "$kind" "$m" "$dofs" "$run" \
        "$(echo "$t1 - $t0" | bc)" "$asm" "$mem" "${coll:--}" "$held"
    done
  done
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
