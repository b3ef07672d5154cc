#!/usr/bin/env bash
# The orderings of MUMPS's analysis (SUPERJOIN_MUMPS_ORDERING, issue 14) give
# the same solution: under mpirun -np 2 with each of amd (the default), ptscotch
# (parallel analysis) and metis (superjoin's METIS on the gathered pattern of
# the processes' terms, handed in as PERM_IN), the listing equals the one of
# one process with the default (--solver mumps --condense yes) within its
# printed digits (tools/lstdiff, as tests/mpi/run_mpi_listings.sh), except the
# lines that name the ordering and count the factor's entries (they depend on
# the ordering), the PARTITION block, the counts that differ between one
# and two processes, and the place of the largest MAXRATIO: its value is
# compared, but where several DOFs tie (identical instances, a symmetric
# frame) the round-off of (K^-1)_jj, which depends on the ordering, picks
# one. Also: the ordering line names the ordering asked for
# (the switch took effect), a frame whose two substructures are not condensed
# (a sparse matrix that is the sum of the two processes' terms) reports the
# pattern gathered to the host for metis, and an unknown name ends both
# processes with status 2 and one message.
# usage: run_orderings.sh SUPERJOIN LSTDIFF GEN_FRAME SOURCE_DIR OUTDIR
set -u
bin=$1; lstdiff=$2; gen=$3; src=$4; outdir=$5
mkdir -p "$outdir"; outdir=$(cd "$outdir" && pwd)
export OPENBLAS_NUM_THREADS=1
mpi=(timeout 300 mpirun --allow-run-as-root --oversubscribe --quiet -np 2 -x SUPERJOIN_MUMPS_ORDERING)
fail=0; n=0
"$gen" --dofs 1e3 "$outdir/frame.deck" 2>/dev/null || { echo "FAIL: gen_frame"; exit 1; }
"${PYTHON:-python3}" "$src/bench/gen_strip.py" --panels 4 --mesh 8 >"$outdir/strip.deck" || { echo "FAIL: gen_strip"; exit 1; }
# verification decks whose interface is left to MUMPS on two processes (on
# the others every unknown is condensed), the modules of the MPI tests, a
# strip of condensed panels (dense K* blocks) and a frame not condensed
decks="$src/tests/decks/quadratic_plane_bending.deck $src/tests/decks/b32_beams.deck
 $src/tests/decks/folded_plate.deck $src/tests/decks/mixed_loop.deck $src/tests/decks/parts_portal.deck
 $src/tests/decks/offset_stiffener.deck $src/tests/decks/master_after_slave.deck $src/tests/decks/timoshenko_frame.deck
 $src/tests/mpi/modules_row.deck $src/tests/mpi/modules_tower.deck $outdir/strip.deck $outdir/frame.deck"
maxratio='s/^\(  MAXRATIO  *[^ ]*\)  at .*/\1/'
# (the twins and by-level notes depend on the processes too: run_mpi_listings.sh)
skip='^  ordering \|^  factor nonzeros \|^  condensations: \|^  joint study \|^  matrix nonzeros (upper) \|^  identical parts share a condensation \|^  condensation by level: '
name_of() {
  case $1 in
    amd) echo 'AMD (MUMPS)' ;;
    ptscotch) echo 'PT-SCOTCH (MUMPS, parallel analysis)' ;;
    ptscotch-small) echo '\(PT-SCOTCH (MUMPS, parallel analysis)\|SCOTCH (MUMPS)\)' ;;
    metis) echo 'METIS nested dissection (superjoin)' ;;
  esac
}
for deck in $decks; do
  name=$(basename "$deck" .deck)
  condense=yes
  [ "$name" = frame ] && condense=no
  (cd "$(dirname "$deck")" && env -u SUPERJOIN_MUMPS_ORDERING "$bin" -q --solver mumps --condense $condense "$name.deck" \
     -o "$outdir/$name.1.lst") || { echo "FAIL: $name: one process"; fail=1; continue; }
  grep -v -e "$skip" "$outdir/$name.1.lst" | sed "$maxratio" >"$outdir/$name.1.cmp"
  for ordering in amd ptscotch metis; do
    n=$((n + 1))
    out=$outdir/$name.$ordering
    (cd "$(dirname "$deck")" && SUPERJOIN_MUMPS_ORDERING=$ordering "${mpi[@]}" "$bin" --solver mumps --condense $condense \
       "$name.deck" -o "$out.lst" 2>"$out.err") || { echo "FAIL: $name: $ordering on two processes"; fail=1; continue; }
    awk '/^PARTITION \(/{skip=1} !skip{print} skip&&/^$/{skip=0}' "$out.lst" | grep -v -e "$skip" | sed "$maxratio" >"$out.cmp"
    "$lstdiff" --scale-atol 1e-11 --health-rtol 2e-2 --health-floor 1e-9 "$outdir/$name.1.cmp" "$out.cmp" >"$out.diff" ||
      { echo "FAIL: $name: $ordering: the listing on two processes differs"; head -5 "$out.diff"; fail=1; }
    # MUMPS analyses a small matrix sequentially (SCOTCH) even when asked
    # for the parallel analysis: the strip and the frame must get PT-SCOTCH
    expect=$(name_of $ordering)
    [ $ordering = ptscotch ] && [ $name != strip ] && [ $name != frame ] && expect=$(name_of ptscotch-small)
    grep -q "^  ordering  *$expect; 2 processes" "$out.lst" ||
      { echo "FAIL: $name: $ordering: the ordering line is not '$expect'"; grep '^  ordering' "$out.lst"; fail=1; }
    if [ "$ordering" = metis ] && [ "$name" = frame ]; then
      bytes=$(sed -n 's/^superjoin: METIS ordering by superjoin: .* pattern gathered \([0-9]*\) bytes$/\1/p' "$out.err")
      [ "${bytes:-0}" -gt 0 ] || { echo "FAIL: frame: metis: no pattern gathered from the other process"; fail=1; }
      # the permutation handed in is a fill-reducing one of the whole (summed)
      # pattern: its factor within 1.5 times AMD's (1.2 times measured; the
      # inverse permutation, or the host's term alone, gives several times)
      amd=$(sed -n 's/^  factor nonzeros  *\([0-9]*\)$/\1/p' "$outdir/$name.amd.lst")
      nd=$(sed -n 's/^  factor nonzeros  *\([0-9]*\)$/\1/p' "$out.lst")
      [ -n "$amd" ] && [ -n "$nd" ] && [ $((2 * nd)) -le $((3 * amd)) ] ||
        { echo "FAIL: frame: metis: factor nonzeros ${nd:-?} beyond 1.5 times AMD's ${amd:-?}"; fail=1; }
      echo "frame: factor nonzeros with AMD $amd, with superjoin's METIS $nd; pattern gathered $bytes bytes"
    fi
  done
done
# an unknown ordering: status 2 on both processes, one message
SUPERJOIN_MUMPS_ORDERING=nonsense "${mpi[@]}" "$bin" -q --solver mumps "$src/tests/mpi/modules_row.deck" \
  -o "$outdir/bad.lst" 2>"$outdir/bad.err"
s=$?
[ $s -eq 2 ] || { echo "FAIL: unknown ordering: status $s, expected 2"; fail=1; }
[ "$(grep -c 'error: SUPERJOIN_MUMPS_ORDERING: unknown ordering' "$outdir/bad.err")" -eq 1 ] ||
  { echo "FAIL: unknown ordering: not one message"; cat "$outdir/bad.err"; fail=1; }
[ $fail -eq 0 ] && echo "orderings: $n runs on 2 processes (amd, ptscotch, metis) as one process with the default"
exit $fail
