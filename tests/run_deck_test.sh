#!/usr/bin/env bash
# Solve one deck and diff its listing and CSV files against the committed references.
# usage: run_deck_test.sh SUPERJOIN LSTDIFF DECK REFDIR OUTDIR
# With UPDATE_REFS=1 the references are (re)written instead.
set -u
bin=$1; lstdiff=$2; deck=$3; refdir=$4; outdir=$5
name=$(basename "$deck" .deck)
mkdir -p "$outdir"
out="$outdir/$name"
rm -rf "$out.lst" "$out.csv" "$out.2.lst"
cd "$(dirname "$deck")" || exit 1
"$bin" -q "$(basename "$deck")" -o "$out.lst" --csv "$out.csv"
rc=$?
if [ $rc -ne 0 ]; then echo "FAIL: superjoin exited with $rc on $deck"; exit 1; fi
# No result may be NaN or Inf.
if grep -qiwE 'nan|inf|infinity' "$out.lst" "$out.csv"/*.csv; then
  echo "FAIL: NaN or Inf in the results"; grep -iwnE 'nan|inf|infinity' "$out.lst" "$out.csv"/*.csv | head -5; exit 1
fi
# The same deck gives the same bytes.
"$bin" -q "$(basename "$deck")" -o "$out.2.lst"
if ! cmp -s "$out.lst" "$out.2.lst"; then echo "FAIL: listing differs between two runs"; exit 1; fi
if [ "${UPDATE_REFS:-0}" = 1 ]; then
  mkdir -p "$refdir/$name.csv"
  cp "$out.lst" "$refdir/$name.lst"
  cp "$out.csv"/*.csv "$refdir/$name.csv/"
  echo "updated references of $name"; exit 0
fi
if [ ! -f "$refdir/$name.lst" ]; then echo "FAIL: no reference $refdir/$name.lst (run with UPDATE_REFS=1)"; exit 1; fi
status=0
# Health values (residual, EPSILON, MAXRATIO, condition estimate) relatively:
# 2e-2 is two units of the third printed digit; at or below 1e-9 (the target of
# iterative refinement, REFINE_RESIDUAL) a residual or
# EPSILON is round-off, which differs between builds, and is not compared.
# A deck whose small numbers matter may ask for a relative comparison of the
# whole listing with a line "** listing-rtol: R" (absolute tolerance 1e-12 then).
# A deck whose health figures are the round-off of its formulation (PENALTY:
# eps g / k, which differs between CPUs by an order of magnitude) may raise the
# floor below which they are not compared with a line "** health-floor: F".
lstrtol=$(sed -n 's/^\*\* listing-rtol: *\([0-9.eE+-]*\).*/\1/p' "$(basename "$deck")" | head -1)
if [ -n "$lstrtol" ]; then lsttol="--rtol $lstrtol --atol 1e-12"; else lsttol="--scale-atol 1e-11"; fi
hfloor=$(sed -n 's/^\*\* health-floor: *\([0-9.eE+-]*\).*/\1/p' "$(basename "$deck")" | head -1)
"$lstdiff" $lsttol --health-rtol 2e-2 --health-floor "${hfloor:-1e-9}" "$refdir/$name.lst" "$out.lst" ||
  { echo "FAIL: listing differs from reference"; status=1; }
# Under TRANSFORM every step is in equilibrium to round-off: in every direction
# of every EQUILIBRIUM block, |applied + reactions| is at most 1e-9 times the
# step's scale: the largest resultant or single support reaction (SUPPORT
# REACTIONS, or the RF table of *NODE PRINT when the deck asks for it). (The
# listing's own "relative" column divides by the resultants alone, which are
# round-off when a step has only prescribed displacements.)
if grep -q '^  formulation  *TRANSFORM' "$out.lst"; then
  bad=$(awk 'function abs(x) { return x < 0 ? -x : x }
             function scale(v) { if (abs(v + 0) > big[k]) big[k] = abs(v + 0) }
             /^STEP [0-9]+/ {k = $2 + 0; next}
             /^REQUESTED OUTPUT .* of step [0-9]+/ {k = $NF + 0; next}
             /^SUPPORT REACTIONS/ {rc = 1; next}
             rc && NF == 0 {rc = 0}
             rc && $NF ~ /^[-+]?[0-9.]+E[-+][0-9]+$/ {scale($NF)}
             /^    RF  reaction forces/ {rf = 1; next}
             rf && $1 != "substructure" && $2 !~ /^[0-9]+$/ {rf = 0}
             rf && $2 ~ /^[0-9]+$/ {for (i = 3; i <= NF; i++) scale($i)}
             /^EQUILIBRIUM/ {eq = 1; next}
             eq && $1 ~ /^[FM][XYZ]$/ {n++; row[n] = $0; s[n] = $4 + 0; step[n] = k; scale($2); scale($3)}
             eq && NF == 0 {eq = 0}
             END {for (i = 1; i <= n; i++) if (big[step[i]] > 0 && abs(s[i]) > 1e-9 * big[step[i]]) print "  " row[i]}' "$out.lst")
  if [ -n "$bad" ]; then echo "FAIL: equilibrium imbalance above 1e-9:"; echo "$bad"; status=1; fi
fi
# A deck may widen the CSV tolerance for its conditioning with a line
# "** csv-tolerance: X" (relative, and relative to the file's largest value).
csvtol=$(sed -n 's/^\*\* csv-tolerance: *\([0-9.eE+-]*\).*/\1/p' "$(basename "$deck")" | head -1)
rtol=${csvtol:-1e-9}; satol=${csvtol:-1e-12}
for f in "$refdir/$name.csv"/*.csv; do
  "$lstdiff" --rtol "$rtol" --atol 1e-12 --scale-atol "$satol" "$f" "$out.csv/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; status=1; }
done
[ $status -eq 0 ] && echo "deck $name: listing and CSV match the references"
exit $status
