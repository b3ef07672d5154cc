#!/usr/bin/env bash
# run_mpi_order.sh -- the orderings of MUMPS's analysis compared (issue 14),
# SUPERJOIN_MUMPS_ORDERING = amd (sequential analysis, AMD: the default),
# ptscotch (parallel analysis, PT-SCOTCH), metis (METIS nested dissection by
# superjoin on the host, handed in as PERM_IN), on one process and under
# mpirun -np 2.
# Per run: wall clock, the phases 'order' (MUMPS's analysis, with superjoin's
# METIS and the gather of the pattern for metis) and 'factor', then from the
# ordering line on stderr the factor entries (INFOG(29)), the factorization's
# flops (RINFOG(3)), MUMPS's estimated memory of the largest process
# (INFOG(21), MB), superjoin's seconds on the host for metis and the bytes of
# pattern gathered to it, and the peak resident memory of every process
# (/usr/bin/time, MB).
# Models (MODEL arguments):
#   frame:SIZE   gen_frame --dofs SIZE (tower), --condense no: its two
#                substructures (columns, girders) not condensed, MUMPS gets the
#                whole sparse stiffness (on two processes each the term of the
#                substructure it owns)
#   strip:M      bench/gen_strip.py --panels 8 --mesh M: eight condensed panels,
#                an interface of dense K* blocks (owner terms on two processes)
#   modules:M    bench/gen_modules.py --row --mesh M --storeys 20: twenty
#                instances of one part (the identical-parts model)
#   explicit:M   the same with --storeys 16 --explicit: sixteen distinct
#                substructures (many parts, sixteen condensations)
# usage: bench/run_mpi_order.sh MODEL...   (default: frame:1e5 strip:40 modules:40)
# Needs build-mpi/ (tools/build.sh -DSUPERJOIN_MPI=ON).
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
BIN=${SUPERJOIN:-$ROOT/build-mpi/superjoin}
GEN=$ROOT/build-mpi/tests/gen_frame
SCRATCH=${BENCH_DIR:-$ROOT/build-mpi/bench_order}
ORDERINGS=${ORDERINGS:-amd ptscotch metis}
[ $# -gt 0 ] || set -- frame:1e5 strip:40 modules:40
export OPENBLAS_NUM_THREADS=1
mkdir -p "$SCRATCH"
mpi=(mpirun --allow-run-as-root --oversubscribe --quiet -np 2 -x SUPERJOIN_MUMPS_ORDERING)
timed=(bash -c '/usr/bin/time -f "%M" -o "$0.${OMPI_COMM_WORLD_RANK:-0}" "$@"')
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-14s %8s %-12s %2s %7s %7s %7s %12s %10s %7s %7s %9s %11s\n' model equations ordering np wall order factor \
  'factor nnz' flops 'est MB' 'host s' 'gathered' 'peak MB'
for spec in "$@"; do
  kind=${spec%%:*}; size=${spec#*:}
  deck=$SCRATCH/${kind}_$size.deck
  case $kind in
    frame) "$GEN" --dofs "$size" "$deck" 2>/dev/null; one=(--solver mumps --condense no) ;;
    strip) python3 "$ROOT/bench/gen_strip.py" --panels 8 --mesh "$size" >"$deck"; one=(--solver mumps --condense yes) ;;
    modules) python3 "$ROOT/bench/gen_modules.py" --row --mesh "$size" --storeys 20 >"$deck"
             one=(--solver mumps --condense yes) ;;
    explicit) python3 "$ROOT/bench/gen_modules.py" --row --mesh "$size" --storeys 16 --explicit >"$deck"
              one=(--solver mumps --condense yes) ;;
    *) echo "unknown model $spec" >&2; exit 2 ;;
  esac
  for ordering in $ORDERINGS; do
    export SUPERJOIN_MUMPS_ORDERING=$ordering
    for np in 1 2; do
      out=$SCRATCH/$kind.$size.$ordering.$np
      rm -f "$out".mem.*
      t0=$(date +%s.%N)
      if [ $np = 1 ]; then
        "${timed[@]}" "$out.mem" "$BIN" "${one[@]}" "$deck" -o "$out.lst" 2>"$out.err"
      else
        "${mpi[@]}" "${timed[@]}" "$out.mem" "$BIN" "${one[@]}" "$deck" -o "$out.lst" 2>"$out.err"
      fi
      t1=$(date +%s.%N)
      line=$(grep '^superjoin: MUMPS ordering ' "$out.err" || true)
      host=$(sed -n 's/^superjoin: METIS ordering by superjoin: \([0-9.]*\) s on the host, pattern gathered \([0-9]*\) bytes$/\1 \2/p' "$out.err")
      eq=$(awk '$2 == "assemble" {print $6}' "$out.err" | tr -d ,)
      printf '%-14s %8s %-12s %2s %7.2f %7s %7s %12s %10s %7s %7s %9s %11s\n' "$kind:$size" "$eq" "$ordering" $np \
        "$(echo "$t1 - $t0" | bc)" "$(awk '$2 == "order" {print $3}' "$out.err")" \
        "$(awk '$2 == "factor" {print $3}' "$out.err")" \
        "$(echo "$line" | sed -n 's/.*: factor entries \([0-9]*\) .*/\1/p')" \
        "$(echo "$line" | sed -n 's/.*, flops \([^,]*\),.*/\1/p')" \
        "$(echo "$line" | sed -n 's/.*estimated memory largest \([0-9]*\) MB.*/\1/p')" \
        "${host%% *}" "${host##* }" \
        "$(for f in "$out".mem.*; do echo $(( $(tail -1 "$f") / 1024 )); done | paste -sd/)"
    done
  done
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
