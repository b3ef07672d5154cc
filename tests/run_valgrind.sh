#!/usr/bin/env bash
# Run superjoin under valgrind memcheck on the verification decks (every
# solver backend) and on a few decks that fail (deck error, mechanism), so the
# error paths are checked too. Any memcheck error (invalid read/write, use of
# uninitialised values, invalid free) and any leak "definitely lost",
# "indirectly lost" or "possibly lost" fails the test.
# usage: run_valgrind.sh SUPERJOIN SOURCE_DIR WORK_DIR
# Suppressions: tests/valgrind/superjoin.supp (only code outside superjoin).
set -u
if [ $# -ne 3 ]; then echo "usage: run_valgrind.sh SUPERJOIN SOURCE_DIR WORK_DIR"; exit 2; fi
bin=$1; src=$(cd "$2" && pwd); work=$3
case "$bin" in /*) ;; *) bin="$(pwd)/$bin" ;; esac
command -v valgrind >/dev/null || { echo "valgrind not found"; exit 1; }
rm -rf "$work"; mkdir -p "$work"; work=$(cd "$work" && pwd)
VG_ERR=99
vg=(valgrind -q --tool=memcheck --leak-check=full --show-leak-kinds=definite,indirect,possible
    --errors-for-leak-kinds=definite,indirect,possible --track-origins=no
    --suppressions="$src/tests/valgrind/superjoin.supp" --error-exitcode=$VG_ERR)
fail=0; runs=0
run() {  # run WANT_STATUS LABEL DIR -- superjoin arguments...
  local want=$1 label=$2 dir=$3; shift 4
  local log="$work/$label.log"
  (cd "$dir" && "${vg[@]}" --log-file="$log" "$bin" -q "$@" >"$work/$label.out" 2>"$work/$label.err")
  local rc=$?
  runs=$((runs + 1))
  if [ "$rc" -ne "$want" ] || [ -s "$log" ]; then
    fail=$((fail + 1))
    echo "FAIL: $label: status $rc (want $want)"; cat "$log" "$work/$label.err"
  fi
}
for deck in "$src"/tests/decks/*.deck; do
  name=$(basename "$deck" .deck)
  for solver in auto cholmod umfpack; do
    run 0 "$name.$solver" "$src/tests/decks" -- "$name.deck" --solver $solver \
        -o "$work/$name.$solver.lst" --csv "$work/$name.$solver.csv"
  done
done
run 0 "penalty" "$src/tests/decks" -- mixed_loop.deck --formulation penalty -o "$work/pen.lst" \
    --export-matrix "$work/k.mtx"
for name in include_error too_many_errors contact_duplicate set_cycle; do
  run 1 "bad.$name" "$src/tests/bad" -- "$name.deck" -o "$work/bad.$name.lst"
done
for deck in "$src"/tests/singular/*.deck; do
  name=$(basename "$deck" .deck)
  # the expected status is on the deck's first line ('** expect: STATUS ...')
  want=$(head -n 1 "$deck" | sed 's/^\*\* expect: \([0-9]*\).*/\1/')
  run "$want" "singular.$name" "$src/tests/singular" -- "$name.deck" -o "$work/singular.$name.lst"
done
echo "valgrind: $runs runs, $fail failed"
[ $fail -eq 0 ]
