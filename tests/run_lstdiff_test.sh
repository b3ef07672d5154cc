#!/usr/bin/env bash
# The listing comparison's own rules (tools/lstdiff.f90), each case with the
# answer it must give: numbers within tolerance, a word after a round-off zero
# (an envelope's step of an extreme that round-off decided), and the cases that
# must still differ.
# usage: run_lstdiff_test.sh LSTDIFF WORKDIR
set -u
lstdiff=$1; work=$2
mkdir -p "$work" && cd "$work" || exit 1
fail=0
# expect STATUS "reference line" "output line" [options...]
expect() {
  local want=$1 a=$2 b=$3; shift 3
  printf 'STEP 1  STIFF\nSTEP 2  SOFTER\n  scale   1.000000E+006\n%s\n' "$a" > ref.lst
  printf 'STEP 1  STIFF\nSTEP 2  SOFTER\n  scale   1.000000E+006\n%s\n' "$b" > out.lst
  "$lstdiff" "$@" ref.lst out.lst > /dev/null 2>&1
  local got=$?
  if [ "$got" -ne "$want" ]; then
    echo "FAIL: expected status $want, got $got: '$a' against '$b' ($*)"; fail=1
  fi
}
row='  SPLICE  4  4  1 force'
# a step name after a value that is zero but for round-off in both files
expect 0 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF" --scale-atol 1e-11
expect 0 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  0.000000E+000  STIFF   0.000000E+000  SOFTER" --scale-atol 1e-11
# ... but not after a value above the tolerance, equal or not
expect 1 "$row  5.000000E+002  STIFF   0.000000E+000  STIFF" "$row  5.000000E+002  SOFTER  0.000000E+000  STIFF" --scale-atol 1e-11
expect 1 "$row  5.000000E+002  STIFF   0.000000E+000  STIFF" "$row  5.000000001E+002  SOFTER  0.000000E+000  STIFF" --scale-atol 1e-11
expect 1 "$row  1.000000E-003  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF" --scale-atol 1e-11
# ... nor after an integer (an id, a step number) however large the tolerance, nor a word
# that is not a step's name
expect 1 "  STEP 2  STIFF" "  STEP 2  SOFTER" --atol 10
expect 1 "  3  STIFF  4.0" "  3  SOFTER  4.0" --atol 10
expect 0 "  0.0  STIFF  4.0" "  0.0  SOFTER  4.0" --atol 10
expect 1 "$row  0.000000E+000  B23" "$row  0.000000E+000  B31" --scale-atol 1e-11
expect 1 "$row  0.000000E+000  STIFF" "$row  0.000000E+000  HINGE" --scale-atol 1e-11
# the zero is judged against the absolute tolerance: without --scale-atol 9.5e-7 is not zero
expect 1 "$row  0.000000E+000  STIFF   0.000000E+000  STIFF" "$row  9.536743E-007  SOFTER  0.000000E+000  STIFF"
# only one word is skipped, and only a word against a word
expect 1 "$row  0.000000E+000  STIFF A  0.0  STIFF" "$row  0.000000E+000  SOFTER B  0.0  STIFF" --scale-atol 1e-11
expect 1 "$row  0.000000E+000  STIFF" "$row  0.000000E+000  2.0" --scale-atol 1e-11
# numbers within and beyond the tolerance
expect 0 "  x  1.000000E+000" "  x  1.000000001E+000"
expect 1 "  x  1.000000E+000" "  x  1.000100E+000"
[ $fail -eq 0 ] && echo "lstdiff: all cases as expected"
exit $fail
