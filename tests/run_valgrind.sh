#!/usr/bin/env bash
# Run superjoin under valgrind memcheck on the verification decks and on
# decks that fail (deck error, mechanism), so the error paths are checked too.
# Any memcheck error (invalid read/write, use of uninitialised values, invalid
# free) and any leak "definitely lost", "indirectly lost" or "possibly lost"
# fails the test.
# usage: run_valgrind.sh SUPERJOIN SOURCE_DIR WORK_DIR [GROUP]
#   decks[:K/N]  every deck of tests/decks with the default backend (auto:
#                LAPACK, dense or band, at these sizes); with K/N only the
#                decks K, K+N, K+2N, ... of the sorted list (ctest runs N parts)
#   cholmod      CHOLMOD on the representative decks below (ordinary solve,
#                factor reuse across steps, a new factor per step, several
#                right-hand sides, iterative refinement, the transform, shells,
#                the largest and widest-band decks) and on the singular decks
#                that reach the factorization or the mechanism search
#   umfpack      UMFPACK on the same decks
#   backends     cholmod + umfpack
#   failing      one PENALTY run with a Matrix Market export, four decks with
#                errors and every singular deck (default backend)
#   all          decks + cholmod + umfpack + failing (the default)
#   full         every deck with every backend (auto, cholmod, umfpack), then
#                failing: the run before the suite was split (on demand)
# Suppressions: tests/valgrind/superjoin.supp (only code outside superjoin).
# Each ctest part has its own WORK_DIR (the directory is emptied first).
set -u
if [ $# -lt 3 ] || [ $# -gt 4 ]; then
  echo "usage: run_valgrind.sh SUPERJOIN SOURCE_DIR WORK_DIR [decks[:K/N]|cholmod|umfpack|backends|failing|all|full]"; exit 2
fi
bin=$1; src=$(cd "$2" && pwd); work=$3; group=${4:-all}
case "$bin" in /*) ;; *) bin="$(pwd)/$bin" ;; esac
command -v valgrind >/dev/null || { echo "valgrind not found"; exit 1; }
rm -rf "$work"; mkdir -p "$work"; work=$(cd "$work" && pwd)
VG_ERR=99
vg=(valgrind -q --tool=memcheck --leak-check=full --show-leak-kinds=definite,indirect,possible
    --errors-for-leak-kinds=definite,indirect,possible --track-origins=no
    --suppressions="$src/tests/valgrind/superjoin.supp" --error-exitcode=$VG_ERR)
# The decks CHOLMOD and UMFPACK run under valgrind (groups cholmod, umfpack), and why:
representative=(
  cantilever_joint     # beams and a contact, two steps: the plain path
  load_combinations    # load cases solved with one factor (several right-hand sides) and combined
  step_boundaries      # eight steps: factor kept and reused, refactored when supports change
  parts_portal         # *CHANGE CONTACT and SWEEP: a new matrix per step
  stiff_soft_loop      # springs 1e14 apart in a RIGID loop: iterative refinement with the factor
  rigid_support_loop   # RIGID loop through a support: the transform removes unknowns
  equation_knee        # *EQUATION terms in the transform
  prescribed_truss     # prescribed displacements: the load from the prescribed values
  thick_shell_stress   # S4R/S3R shells, six DOFs a node
  thermal_plates       # the largest plane deck (LAPACK band 35 under auto)
  nafems_le5           # shell Z-section, the widest band (56)
  quadratic_edge_loads # CPS8/CPS6 quadratic plane elements
)
# singular decks that reach the factorization (a breakdown, or the mechanism search)
singular_backends=(free_part free_part_penalty hinge_three_parts no_support)
fail=0; runs=0; t0=$SECONDS
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
deck_run() {  # deck_run NAME SOLVER
  run 0 "$1.$2" "$src/tests/decks" -- "$1.deck" --solver "$2" -o "$work/$1.$2.lst" --csv "$work/$1.$2.csv"
}
singular_run() {  # singular_run NAME [SOLVER]
  local deck="$src/tests/singular/$1.deck" want
  # the expected status is on the deck's first line ('** expect: STATUS ...')
  want=$(head -n 1 "$deck" | sed 's/^\*\* expect: \([0-9]*\).*/\1/')
  run "$want" "singular.$1.${2:-auto}" "$src/tests/singular" -- "$1.deck" --solver "${2:-auto}" \
      -o "$work/singular.$1.${2:-auto}.lst"
}
group_decks() {  # group_decks SOLVERS [K N]
  local solvers=$1 k=${2:-1} n=${3:-1} i=0 deck name solver
  for deck in "$src"/tests/decks/*.deck; do
    i=$((i + 1))
    [ $(( (i - k) % n )) -eq 0 ] || continue
    name=$(basename "$deck" .deck)
    for solver in $solvers; do deck_run "$name" "$solver"; done
  done
}
group_backend() {  # group_backend SOLVER
  local name
  for name in "${representative[@]}"; do deck_run "$name" "$1"; done
  for name in "${singular_backends[@]}"; do singular_run "$name" "$1"; done
}
group_failing() {
  local name deck
  run 0 "penalty" "$src/tests/decks" -- mixed_loop.deck --formulation penalty -o "$work/pen.lst" \
      --export-matrix "$work/k.mtx"
  for name in include_error too_many_errors contact_duplicate set_cycle; do
    run 1 "bad.$name" "$src/tests/bad" -- "$name.deck" -o "$work/bad.$name.lst"
  done
  for deck in "$src"/tests/singular/*.deck; do singular_run "$(basename "$deck" .deck)"; done
}
case "$group" in
  decks) group_decks auto ;;
  decks:*/*)
    part=${group#decks:}; k=${part%/*}; n=${part#*/}
    if ! [[ "$k" =~ ^[0-9]+$ && "$n" =~ ^[0-9]+$ ]] || [ "$k" -lt 1 ] || [ "$k" -gt "$n" ]; then
      echo "run_valgrind.sh: bad part '$group' (decks:K/N, 1 <= K <= N)"; exit 2
    fi
    group_decks auto "$k" "$n" ;;
  cholmod|umfpack) group_backend "$group" ;;
  backends) group_backend cholmod; group_backend umfpack ;;
  failing) group_failing ;;
  all) group_decks auto; group_backend cholmod; group_backend umfpack; group_failing ;;
  full) group_decks "auto cholmod umfpack"; group_failing ;;
  *) echo "run_valgrind.sh: unknown group '$group'"; exit 2 ;;
esac
echo "valgrind ($group): $runs runs, $fail failed, $((SECONDS - t0)) s"
[ $runs -gt 0 ] && [ $fail -eq 0 ]
