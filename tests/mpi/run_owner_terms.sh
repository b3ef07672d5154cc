#!/usr/bin/env bash
# Owner terms (issue 14): on two processes with MUMPS no process assembles the
# whole reduced matrix. For each deck, the number of entries of K_red (the
# listing's 'matrix nonzeros (upper)' of one process, --solver mumps
# --condense yes) against the MPI summary on stderr of mpirun -np 2: every
# process must report 'matrix assembled N entries' with N below that total
# (a process that assembled the whole matrix reports the total), MUMPS input
# equal to what it assembled (it hands MUMPS its own term, all of it), and
# the processes' inputs together at least the total (the terms cover K_red;
# entries several processes hold are counted once per process).
# usage: run_owner_terms.sh SUPERJOIN OUTDIR DECK...
set -u
bin=$1; outdir=$2; shift 2
mkdir -p "$outdir"; outdir=$(cd "$outdir" && pwd)
export OPENBLAS_NUM_THREADS=1
mpi=(timeout 300 mpirun --allow-run-as-root --oversubscribe --quiet -np 2)
fail=0
for deck in "$@"; do
  name=$(basename "$deck" .deck)
  (cd "$(dirname "$deck")" && "$bin" -q --solver mumps --condense yes "$name.deck" -o "$outdir/$name.1.lst") ||
    { echo "FAIL: $name: one process"; fail=1; continue; }
  total=$(sed -n 's/^  matrix nonzeros (upper)  *\([0-9][0-9]*\)$/\1/p' "$outdir/$name.1.lst")
  [ -n "$total" ] || { echo "FAIL: $name: no matrix nonzeros on one process"; fail=1; continue; }
  (cd "$(dirname "$deck")" && "${mpi[@]}" "$bin" "$name.deck" -o "$outdir/$name.2.lst" 2>"$outdir/$name.2.err") ||
    { echo "FAIL: $name: two processes"; fail=1; continue; }
  lines=$(grep -c '^superjoin: MPI process [01]: .* matrix assembled [0-9]* entries, MUMPS input [0-9]* entries' "$outdir/$name.2.err")
  [ "$lines" -eq 2 ] || { echo "FAIL: $name: $lines MPI summary lines, expected 2"; cat "$outdir/$name.2.err"; fail=1; continue; }
  sum=0
  while read -r held input; do
    if [ "$held" -ge "$total" ]; then
      echo "FAIL: $name: a process assembled $held entries, the whole matrix has $total"; fail=1
    fi
    [ "$held" -eq "$input" ] || { echo "FAIL: $name: assembled $held entries but handed MUMPS $input"; fail=1; }
    [ "$held" -gt 0 ] || { echo "FAIL: $name: a process holds no term"; fail=1; }
    sum=$((sum + input))
  done < <(sed -n 's/^superjoin: MPI process [01]: .* matrix assembled \([0-9]*\) entries, MUMPS input \([0-9]*\) entries.*/\1 \2/p' "$outdir/$name.2.err")
  [ "$sum" -ge "$total" ] || { echo "FAIL: $name: the terms hold $sum entries, fewer than the $total of the matrix"; fail=1; }
  echo "$name: K_red $total entries; per process: $(sed -n 's/^superjoin: MPI process \([01]\): .* matrix assembled \([0-9]*\) entries.*/\1: \2/p' "$outdir/$name.2.err" | tr '\n' ' ')"
done
[ $fail -eq 0 ] && echo "owner terms: no process assembled the whole matrix"
exit $fail
