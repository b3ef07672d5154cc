#!/usr/bin/env bash
# The listing comparison's own rules (tools/lstdiff.f90), each case with the
# answer it must give: numbers within tolerance, a step's name after a
# round-off zero (an envelope's step of an extreme that round-off decided),
# and the cases that must still differ.
# usage: run_lstdiff_test.sh LSTDIFF WORKDIR
set -u
lstdiff=$1; work=$2
mkdir -p "$work" && cd "$work" || exit 1
fail=0
# expect STATUS "reference line" "output line" [options...]: the two lines under the same
# header (two steps, STIFF and SOFTER; the largest result 2e9, as a reaction of a listing)
head='STEP 1  STIFF\nSTEP 2  SOFTER\n  reaction   2.000000E+009\n'
expect() {
  local want=$1 a=$2 b=$3; shift 3
  printf "$head%s\n" "$a" > ref.lst
  printf "$head%s\n" "$b" > out.lst
  "$lstdiff" "$@" ref.lst out.lst > /dev/null 2>&1
  local got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAIL: expected status $want, got $got: '$a' against '$b' ($*)"; fail=1
  fi
}
row='  SPLICE  4  4  1 force'
s='--scale-atol 1e-11'   # the deck tests' tolerance: 0.02 here
# a step's name after a value that is zero but for round-off (at most 1e-13 of the largest
# result, 2e-4 here) and printed differently in the two files: not compared
expect 0 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF" $s
expect 0 "$row  -0.000000E+000  STIFF" "$row  0.000000E+000  SOFTER" $s
expect 0 "  0.0  STIFF" "  1.0E-005  SOFTER" --atol 10
# ... but printed alike (the envelope's first-on-a-tie rule), it is compared
expect 1 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  0.000000E+000  STIFF   0.000000E+000  SOFTER" $s
expect 1 "  0.0  STIFF  4.0" "  0.0  SOFTER  4.0" --atol 10
# ... and after a value above the round-off bound, though within the tolerance
expect 1 "$row  5.000000E+002  STIFF   0.000000E+000  STIFF" "$row  5.000000E+002  SOFTER  0.000000E+000  STIFF" $s
expect 1 "$row  5.000000E+002  STIFF   0.000000E+000  STIFF" "$row  5.000000001E+002  SOFTER  0.000000E+000  STIFF" $s
expect 1 "  LEFT  1  6  -3.281250E-003  STIFF" "  LEFT  1  6  -3.281251E-003  SOFTER" $s
expect 1 "$row  1.000000E-003  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF" $s
# ... and after an integer (an id, a step number) however large the tolerance
expect 1 "  STEP 2  STIFF" "  STEP 2  SOFTER" --atol 10
expect 1 "  3  STIFF  4.0" "  3  SOFTER  4.0" --atol 10
# a word that is not a step's name is compared
expect 1 "$row  0.000000E+000  B23" "$row  1.000000E-007  B31" $s
expect 1 "$row  0.000000E+000  STIFF" "$row  1.000000E-007  HINGE" $s
# the bound is within the absolute tolerance: without --scale-atol 9.5e-7 is not zero
expect 1 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF"
# only one word is skipped
expect 1 "$row  0.000000E+000  STIFF A  0.0  STIFF" "$row  1.000000E-007  SOFTER B  0.0  STIFF" $s
# the health lines do not set the round-off bound: a condition estimate of 6.7e7 beside
# results of order 1 (the tolerance is 6.7e-4, the bound 1e-13)
printf 'STEP 1  STIFF\nSTEP 2  SOFTER\n  condition estimate (1-norm)    6.72E+007\n  u   1.000000E+000\n  U1  0.000000E+000  STIFF\n' > ref.lst
printf 'STEP 1  STIFF\nSTEP 2  SOFTER\n  condition estimate (1-norm)    6.72E+007\n  u   1.000000E+000\n  U1  3.000000E-006  SOFTER\n' > out.lst
"$lstdiff" $s ref.lst out.lst > /dev/null 2>&1
[ $? -eq 1 ] || { echo "FAIL: a health line's condition estimate set the round-off bound"; fail=1; }
# numbers within and beyond the tolerance
expect 0 "  x  1.000000E+000" "  x  1.000000001E+000"
expect 1 "  x  1.000000E+000" "  x  1.000100E+000"
[ $fail -eq 0 ] && echo "lstdiff: all cases as expected"
exit $fail
