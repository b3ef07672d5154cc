#!/usr/bin/env bash
# ab_bare.sh -- two superjoin binaries and bare CHOLMOD in turn on one deck and
# its exported matrix: the superjoin side of a change (A B) and the yardstick
# (bare) in the same rounds, so each round's ratio to bare is taken under the
# same load. BARE_HUGE=1 adds a second bare run per round with all of glibc's
# allocations on transparent huge pages (GLIBC_TUNABLES=glibc.malloc.hugetlb=1),
# the yardstick on the same footing as superjoin's --huge-pages yes. One line
# per run: superjoin's phase times (-v), wall clock, user and system CPU, peak
# resident set and minor page faults (GNU time); for bare CHOLMOD its
# analyze, factorize and solve times, their sum and their CPU time.
#
# usage: bench/ab_bare.sh [-r N] OLD_BINARY NEW_BINARY DECK MATRIX.mtx
#   -r N   rounds (default 2)
# MATRIX.mtx: `superjoin DECK --export-matrix MATRIX.mtx`. Extra superjoin
# options: SUPERJOIN_ARGS (e.g. "--condense no"). Each superjoin run replaces
# the listing of the same side's run before (from the second round on), as a
# rerun in place does; FRESH_LISTING=1 removes it first, outside the timing,
# as in a fresh checkout: replacing a file makes the kernel free the old
# file's pages (30-45 ms for the bolted panels' 61 MB listing; doc/performance.md,
# "The listing's tables on two threads"). Needs
# build/cholmod_bare (bench/run_frame.sh builds it) and /usr/bin/time.
set -euo pipefail
rounds=2
while getopts "r:" opt; do
  case $opt in
    r) rounds=$OPTARG ;;
    *) sed -n '2,21p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ $# -eq 4 ] || { sed -n '2,21p' "$0"; exit 2; }
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bare=$root/build/cholmod_bare
a=$(realpath "$1"); b=$(realpath "$2"); deck=$(realpath "$3"); mtx=$(realpath "$4")
[ -x "$bare" ] || { echo "ab_bare.sh: no $bare (run bench/run_frame.sh once)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
gnu() { awk -v k="$1" 'index($0, k) { print $NF; exit }' "$2"; }
for ((i = 1; i <= rounds; i++)); do
  for side in A B; do
    bin=$a; [ $side = B ] && bin=$b
    [ "${FRESH_LISTING:-0}" = 1 ] && rm -f "$work/$side.lst"
    # shellcheck disable=SC2086
    (cd "$(dirname "$deck")" && /usr/bin/time -v "$bin" -v "$(basename "$deck")" ${SUPERJOIN_ARGS:-} \
        -o "$work/$side.lst" >/dev/null 2>"$work/err") || true
    phases=$(awk '$1 == "superjoin:" && $3 ~ /^[0-9.]+$/ { printf "%s %s ", $2, $3 }' "$work/err")
    echo "$side $i load $(cut -d' ' -f1 /proc/loadavg) | $phases| wall $(gnu Elapsed "$work/err")" \
         "user $(gnu 'User time' "$work/err") sys $(gnu 'System time' "$work/err")" \
         "maxrss_kB $(gnu 'Maximum resident' "$work/err") minflt $(gnu Minor "$work/err")"
  done
  for side in bare ${BARE_HUGE:+bare-huge}; do
    if [ $side = bare ]; then
      /usr/bin/time -v "$bare" "$mtx" >"$work/bare.out" 2>"$work/err"
    else
      GLIBC_TUNABLES=glibc.malloc.hugetlb=1 /usr/bin/time -v "$bare" "$mtx" >"$work/bare.out" 2>"$work/err"
    fi
    echo "$side $i load $(cut -d' ' -f1 /proc/loadavg) |" \
         "$(awk '$1 == "time" && $2 != "read" { printf "%s %s ", $2, $3; s += $3 } $1 == "cpu" { printf "cpu %s ", $3 } END { printf "a+f+s %.3f ", s }' "$work/bare.out")|" \
         "user $(gnu 'User time' "$work/err") sys $(gnu 'System time' "$work/err")" \
         "maxrss_kB $(gnu 'Maximum resident' "$work/err") minflt $(gnu Minor "$work/err")"
  done
done
