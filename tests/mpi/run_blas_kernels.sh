#!/usr/bin/env bash
# OpenBLAS's kernels under mpirun (utils/blas_core.c: the first thing main
# does, before MPI starts, is to start the program once more with
# OPENBLAS_CORETYPE set where Debian's OpenBLAS fell back to kernels without
# AVX2 on a CPU with AVX-512 or AVX2 and FMA). The serial run is checked by
# cli.usage (tests/run_cli_tests.sh); here mpirun -np 2, OPENBLAS_CORETYPE
# unset unless said:
#  - the solve of decks/demo.deck: exit 0, the listing that of one process
#    (tools/lstdiff, less the lines the processes change, as mpi.listings);
#  - -v: one BLAS line (rank 0 alone prints it), no advice to set
#    OPENBLAS_CORETYPE (the new start was made), never kernels older than
#    AVX2 where /proc/cpuinfo has avx2 and fma (that part skipped, and said,
#    elsewhere or for an OpenBLAS built for one CPU type);
#  - a user's OPENBLAS_CORETYPE=Haswell stands;
#  - every rank, not only rank 0 (which alone prints): each rank's deck is a
#    FIFO of its own (mpirun's MPMD form, one deck path per rank), so each
#    waits there, after its start-up and MPI's, until the deck is written;
#    meanwhile its environment (/proc/PID/environ, as the process was
#    started) shows the OPENBLAS_CORETYPE its OpenBLAS was loaded with and
#    whether superjoin started it again (SUPERJOIN_BLAS_CORE_FROM): the same
#    on every rank as on rank 0, whose -v line names its kernels; where
#    superjoin started it again, that line's origin, and the process keeps
#    its name; with the user's Haswell, Haswell everywhere and no new start.
# usage: run_blas_kernels.sh SUPERJOIN LSTDIFF SOURCE_DIR OUTDIR
set -u
bin=$(readlink -f "$1"); lstdiff=$(readlink -f "$2"); src=$(readlink -f "$3"); outdir=$4
rm -rf "$outdir" && mkdir -p "$outdir" && cd "$outdir" || exit 1
export OPENBLAS_NUM_THREADS=1
unset SUPERJOIN_BLAS_CORE_FROM
mpi=(timeout 300 mpirun --allow-run-as-root --oversubscribe --quiet)
deck=$src/decks/demo.deck
fail=0
bad() { echo "FAIL: $*"; fail=1; }
line='^superjoin: BLAS: OpenBLAS kernels '

# the solve on two processes against one
env -u OPENBLAS_CORETYPE "$bin" -q --solver mumps --condense yes "$deck" -o one.lst 2>one.err ||
  bad "one process: status $?"
env -u OPENBLAS_CORETYPE "${mpi[@]}" -np 2 "$bin" -v "$deck" -o two.lst 2>two.err
s=$?
[ $s -eq 0 ] || { bad "two processes: status $s"; cat two.err; }
counts='^  condensations: \|^  matrix nonzeros (upper) '
grep -v -e '^  ordering ' -e "$counts" one.lst >one.cmp
# same_as_one NAME: NAME.lst, from two processes, is one.lst (round-off apart: the kernels may differ)
same_as_one() {
  awk '/^PARTITION \(/{skip=1} !skip{print} skip&&/^$/{skip=0}' "$1.lst" | grep -v -e '^  ordering ' -e "$counts" >"$1.cmp"
  grep -q '^PARTITION (2 processes; ' "$1.lst" || bad "$1: no PARTITION block: not solved on two processes"
  "$lstdiff" --scale-atol 1e-11 --health-rtol 2e-2 --health-floor 1e-9 one.cmp "$1.cmp" >"$1.diff" ||
    { bad "$1: the listing on two processes differs from one process's"; head -5 "$1.diff"; }
}
same_as_one two

env -u OPENBLAS_CORETYPE "$bin" -v --check "$deck" 2>serial.err >/dev/null || bad "one process, -v --check: status $?"
if ! grep -q "$line" serial.err; then
  echo "skipped: the BLAS is not OpenBLAS (no BLAS line under -v on one process)"
  [ $fail -eq 0 ] && echo "blas kernels under mpirun: the solve as on one process"
  exit $fail
fi
one_type=0
grep -q 'built for this one CPU type' two.err && one_type=1
[ "$(grep -c "$line" two.err)" -eq 1 ] || { bad "not one BLAS line on two processes"; grep BLAS two.err; }
! grep -q 'set OPENBLAS_CORETYPE=' two.err ||
  { bad "superjoin did not start again with OpenBLAS's kernels for this CPU:"; grep BLAS two.err; }
if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo && [ $one_type -eq 0 ]; then
  older='Katmai|Coppermine|Northwood|Prescott|Banias|Atom|Core2|Penryn|Dunnington|Nehalem|Athlon|Opteron|Opteron_SSE3|Barcelona|Nano|Sandybridge|Bobcat|Bulldozer|Piledriver|Steamroller|Unknown'
  ! grep -qiE "${line}($older)( |$)" two.err || { bad "kernels older than this CPU's AVX2:"; grep BLAS two.err; }
else
  echo "skipped: the kernels' age (no avx2 and fma in /proc/cpuinfo, or an OpenBLAS built for one CPU type)"
fi
OPENBLAS_CORETYPE=Haswell "${mpi[@]}" -np 2 "$bin" -v --check "$deck" 2>haswell.err >/dev/null ||
  bad "OPENBLAS_CORETYPE=Haswell --check: status $?"
[ $one_type -eq 1 ] || grep -q "${line}Haswell (OPENBLAS_CORETYPE)\$" haswell.err ||
  { bad "OPENBLAS_CORETYPE=Haswell is not what runs on two processes"; grep BLAS haswell.err; }

# Every rank: the environment its OpenBLAS was loaded with. run_ranks NAME MODE ENV...:
# mpirun -np 1 on NAME/r0/demo.deck : -np 1 on NAME/r1/demo.deck (FIFOs), both
# held before their decks are written; NAME.ranks: "rank OPENBLAS_CORETYPE FROM comm".
# MODE solve: the listing as one process's; check: --check (a user's kernels,
# which this CPU may lack, never run).
cp "$bin" ./sjrank || exit 1
exe=$(pwd -P)/sjrank   # -P: /proc/PID/exe names the real path, not one through a symbolic link
run_ranks() {
  local name=$1 mode=$2 r pid k opt=()
  shift 2
  [ "$mode" = check ] && opt=(--check)
  mkdir -p "$name/r0" "$name/r1" && mkfifo "$name/r0/demo.deck" "$name/r1/demo.deck" ||
    { bad "$name: cannot make the decks' FIFOs"; return 1; }
  local writers=()
  for r in 0 1; do
    timeout 120 bash -c '{ touch "$1.open"; for _ in $(seq 1200); do [ -e "$3" ] && break; sleep 0.05; done; cat "$2"; } >"$1"' \
      _ "$name/r$r/demo.deck" "$deck" "$name/go" &
    writers+=($!)
  done
  env "$@" "${mpi[@]}" -np 1 "$exe" -v "${opt[@]}" "$name/r0/demo.deck" -o "$name.lst" : \
    -np 1 "$exe" -v "${opt[@]}" "$name/r1/demo.deck" -o "$name.lst" 2>"$name.err" >/dev/null &
  pid=$!
  for _ in $(seq 1200); do   # until both ranks have opened their decks (or mpirun ended)
    [ -e "$name/r0/demo.deck.open" ] && [ -e "$name/r1/demo.deck.open" ] && break
    kill -0 $pid 2>/dev/null || break
    sleep 0.05
  done
  : >"$name.ranks"
  for k in /proc/[0-9]*; do
    [ "$(readlink "$k/exe" 2>/dev/null)" = "$exe" ] || continue
    tr '\0' '\n' <"$k/environ" | awk -v comm="$(cat "$k/comm")" -F= '
      $1 == "OMPI_COMM_WORLD_RANK" {r = $2} $1 == "OPENBLAS_CORETYPE" {t = $2} $1 == "SUPERJOIN_BLAS_CORE_FROM" {f = $2}
      END {print r, (t == "" ? "-" : t), (f == "" ? "-" : f), comm}' >>"$name.ranks"
  done
  touch "$name/go"
  wait $pid
  k=$?
  kill "${writers[@]}" 2>/dev/null   # a rank that never opened its deck leaves its writer waiting
  wait "${writers[@]}" 2>/dev/null
  sort -o "$name.ranks" "$name.ranks"
  echo "$name: $(tr '\n' ';' <"$name.ranks")"
  [ $k -eq 0 ] || bad "$name: mpirun with a FIFO deck per rank: status $k"
  [ "$(cut -d' ' -f1 "$name.ranks" | tr '\n' ' ')" = "0 1 " ] ||
    { bad "$name: ranks 0 and 1 not both found waiting for their decks"; return 1; }
  [ "$mode" = check ] || same_as_one "$name"
}
# OPENBLAS_CORETYPE unset: every rank as rank 0
if run_ranks unset solve -u OPENBLAS_CORETYPE; then
  k0=$(sed -n "s/${line}\\([^ ]*\\).*/\\1/p" unset.err)
  [ -n "$k0" ] || bad "unset: no BLAS line"
  read -r _ t0 f0 _ < <(head -1 unset.ranks)
  [ "$(cut -d' ' -f2,3 unset.ranks | sort -u | wc -l)" -eq 1 ] ||
    bad "unset: the ranks were loaded with different OPENBLAS_CORETYPE or starts"
  from=$(sed -n "s/${line}.* (set by superjoin: OpenBLAS took this CPU for \\(.*\\))\$/\\1/p" unset.err)
  if [ -n "$from" ]; then
    while read -r r t f c; do
      [ "$t" != "-" ] || bad "unset: rank $r: not started again with OPENBLAS_CORETYPE (rank 0 runs $k0)"
      [ "$f" = "$from" ] || bad "unset: rank $r: started again from '$f', rank 0 says OpenBLAS took the CPU for $from"
      [ "$c" = sjrank ] || bad "unset: rank $r: after its new start named '$c', not sjrank"
    done <unset.ranks
  else
    [ "$t0 $f0" = "- -" ] || bad "unset: a rank started again (OPENBLAS_CORETYPE=$t0 from $f0), rank 0's line does not say so"
  fi
fi
# the user's OPENBLAS_CORETYPE=Haswell on every rank, no new start
if run_ranks haswell check OPENBLAS_CORETYPE=Haswell; then
  while read -r r t f _; do
    [ "$t $f" = "Haswell -" ] || bad "haswell: rank $r runs with OPENBLAS_CORETYPE=$t (started again from '$f'), not the user's Haswell"
  done <haswell.ranks
fi
if [ $fail -eq 0 ]; then
  echo "blas kernels under mpirun: $(sed -n "s/${line}//p" two.err) on every rank; the solve as on one process"
  rm -rf sjrank unset haswell   # the binary's copy and the FIFOs (kept when a check failed)
fi
exit $fail
