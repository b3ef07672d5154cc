#!/usr/bin/env bash
# The MPI build under mpirun -np 2 against the same binary on one process
# (--solver mumps on both sides):
#  - every verification deck (tests/decks, and tests/pins/boundary_fixed.deck:
#    *BOUNDARY, FIXED fills values from an earlier step on every process): exit 0, the listing equal to the
#    one-process listing within its printed digits (tools/lstdiff, as the deck
#    tests), except the 'ordering' line, which names the processes, and the
#    PARTITION block, which only runs on several processes print (present
#    on two, absent on one), and the 'matrix nonzeros' line: on two
#    processes each hands MUMPS its own term of the matrix and nobody
#    assembles it, the line says n/a (checked here);
#  - every singular deck (tests/singular): the same exit status and the same
#    stderr, printed once (hinge_chain: the singular part B is condensed by
#    process 1, A having the larger estimated cost (greedy rule): the
#    failure of one process's condensation reaches the other, no hang);
#  - a few bad decks (tests/bad: number, name, reference, contact, step
#    errors): the same exit status and the same stderr, once;
#  - a failure on rank 0 alone (the listing cannot be written): every process
#    ends with status 4 and one message, no hang (timeout).
# usage: run_mpi_listings.sh SUPERJOIN LSTDIFF SOURCE_DIR OUTDIR
set -u
bin=$1; lstdiff=$2; src=$3; outdir=$4
mkdir -p "$outdir"; outdir=$(cd "$outdir" && pwd)
export OPENBLAS_NUM_THREADS=1
mpi=(timeout 300 mpirun --allow-run-as-root --oversubscribe --quiet -np 2)
fail=0; n=0
# Several processes condense every part that has interior DOFs, each its own
# (--condense yes on one process gives the same system); instances of one part
# on different processes are condensed once on each, so the counts of
# condensations computed and reused differ and are not compared.
# Likewise which condensations identical parts share (--twins: found among
# the parts a process condenses, so the note names the pairs that meet on one
# process) and the condensation by level, which several processes do not do
# (the note gives that reason where one process gives its own).
# A kept factorization is reused for a next set of supports that changes only
# prescribed values when the assembled matrix is the same entry for entry; on
# several processes each hands MUMPS its own term and no process has the
# matrix to compare, so every set is factored (the count of reuses differs).
counts='^  condensations: \|^  joint study \|^  matrix nonzeros (upper) \|^  identical parts share a condensation \|^  condensation by level: \|^  boundary conditions (\*BOUNDARY in steps): '
# A turned instance reuses its part's condensation on one process (turned) but
# is condensed in its own axes on another process, so the pivots, and MAXRATIO
# (the largest k_jj / D_jj, with its place), differ: that line is not compared
# when the one-process listing says a condensation was turned.
turned='turned by their instance.s placement'
for deck in "$src"/tests/decks/*.deck "$src"/tests/pins/boundary_fixed.deck; do
  name=$(basename "$deck" .deck); n=$((n + 1))
  (cd "$(dirname "$deck")" && "$bin" -q --solver mumps --condense yes "$name.deck" -o "$outdir/$name.1.lst" 2>"$outdir/$name.1.err")
  s1=$?
  (cd "$(dirname "$deck")" && "${mpi[@]}" "$bin" -q "$name.deck" -o "$outdir/$name.2.lst" 2>"$outdir/$name.2.err")
  s2=$?
  if [ $s1 -ne $s2 ]; then echo "FAIL: $name: status $s1 on one process, $s2 on two"; fail=1; continue; fi
  skip="$counts"
  grep -q "$turned" "$outdir/$name.1.lst" && skip="$counts\\|^  MAXRATIO "
  grep -v -e '^  ordering ' -e "$skip" "$outdir/$name.1.lst" >"$outdir/$name.1.cmp"
  # the PARTITION block (up to its blank line) is the other difference
  awk '/^PARTITION \(/{skip=1} !skip{print} skip&&/^$/{skip=0}' "$outdir/$name.2.lst" | grep -v -e '^  ordering ' -e "$skip" >"$outdir/$name.2.cmp"
  grep -q '^PARTITION (' "$outdir/$name.1.lst" && { echo "FAIL: $name: PARTITION block on one process"; fail=1; }
  grep -q '^PARTITION (2 processes; ' "$outdir/$name.2.lst" || { echo "FAIL: $name: no PARTITION block on two processes"; fail=1; }
  "$lstdiff" --scale-atol 1e-11 --health-rtol 2e-2 --health-floor 1e-9 "$outdir/$name.1.cmp" "$outdir/$name.2.cmp" >"$outdir/$name.diff" ||
    { echo "FAIL: $name: listing on two processes differs"; head -5 "$outdir/$name.diff"; fail=1; }
  grep -q '^  matrix nonzeros (upper)  *n/a (summed by MUMPS from each MPI process.s own terms)$' "$outdir/$name.2.lst" ||
    { echo "FAIL: $name: the matrix nonzeros line on two processes is not n/a"; fail=1; }
  grep -q '^  ordering  *none$' "$outdir/$name.1.lst" ||   # every unknown condensed: no MUMPS
  grep -q '^  ordering .*2 processes, matrix entries per process' "$outdir/$name.2.lst" ||
    { echo "FAIL: $name: no distribution in the ordering line"; fail=1; }
  cmp -s "$outdir/$name.1.err" "$outdir/$name.2.err" || { echo "FAIL: $name: stderr differs"; fail=1; }
done
bad="bad_exponent bad_name bad_reference contact_self change_contact_outside_step boundary_bad_dof"
for deck in "$src"/tests/singular/*.deck $(for b in $bad; do echo "$src/tests/bad/$b.deck"; done); do
  name=$(basename "$deck" .deck); n=$((n + 1))
  (cd "$(dirname "$deck")" && "$bin" -q --solver mumps --condense yes "$name.deck" -o "$outdir/$name.1.lst" 2>"$outdir/$name.1.err")
  s1=$?
  (cd "$(dirname "$deck")" && "${mpi[@]}" "$bin" -q "$name.deck" -o "$outdir/$name.2.lst" 2>"$outdir/$name.2.err")
  s2=$?
  [ $s1 -ne 0 ] || { echo "FAIL: $name: solved"; fail=1; }
  [ $s1 -eq $s2 ] || { echo "FAIL: $name: status $s1 on one process, $s2 on two"; fail=1; }
  cmp -s "$outdir/$name.1.err" "$outdir/$name.2.err" ||
    { echo "FAIL: $name: stderr differs"; diff "$outdir/$name.1.err" "$outdir/$name.2.err" | head -6; fail=1; }
done
# rank 0 alone fails (cannot write the listing): status 4 everywhere, one message
deck="$src/tests/decks/l_frame.deck"
"${mpi[@]}" "$bin" -q "$deck" -o "$outdir/missing/dir/x.lst" 2>"$outdir/rank0.err"
s=$?
[ $s -eq 4 ] || { echo "FAIL: rank-0 write failure: status $s, expected 4"; fail=1; }
[ "$(grep -c 'error:' "$outdir/rank0.err")" -eq 1 ] || { echo "FAIL: rank-0 write failure: not one message"; cat "$outdir/rank0.err"; fail=1; }
[ $fail -eq 0 ] && echo "mpi: $n decks on 2 processes as on one, and a rank-0 failure ends both"
exit $fail
