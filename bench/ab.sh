#!/usr/bin/env bash
# ab.sh -- two superjoin binaries on the same decks, alternately, in one run:
# is a change (a refactor) slower? Machines are shared and noisy, so the
# binaries take turns (A B A B ...) and the figure is the ratio of the medians
# of each deck's wall times, with user CPU beside it; the listings of the two
# are compared too (they must be identical but for the version line and times).
#
# usage: bench/ab.sh [-r N] OLD_BINARY NEW_BINARY DECK [DECK...]
#   -r N   runs of each binary per deck (default 3)
# Extra superjoin options: SUPERJOIN_ARGS (e.g. "--condense no").
# Prints one row per deck: median wall A, B, B/A, median CPU (user + sys) A, B,
# B/A, listings identical or not. On a loaded machine the CPU ratio is the
# steadier one (wall time includes waiting for a core). Exit 1 when a run fails or listings differ.
set -euo pipefail
runs=3
while getopts "r:" opt; do
  case $opt in
    r) runs=$OPTARG ;;
    *) sed -n '2,12p' "$0"; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
[ $# -ge 3 ] || { sed -n '2,12p' "$0"; exit 2; }
a=$(realpath "$1"); b=$(realpath "$2"); shift 2
[[ $runs =~ ^[1-9][0-9]*$ ]] || { echo "ab.sh: -r needs a positive integer" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
status=0

median() { sort -g | awk '{v[NR]=$1} END {print (NR % 2) ? v[(NR+1)/2] : (v[NR/2]+v[NR/2+1])/2}'; }

printf '%-28s %9s %9s %7s %9s %9s %7s  %s\n' deck wall_A wall_B B/A cpu_A cpu_B B/A listings
for deck in "$@"; do
  dir=$(cd "$(dirname "$deck")" && pwd); name=$(basename "$deck")
  : >"$work/wa"; : >"$work/wb"; : >"$work/ua"; : >"$work/ub"
  for ((i = 1; i <= runs; i++)); do
    for side in a b; do
      bin=$a; [ $side = b ] && bin=$b
      # shellcheck disable=SC2086
      if ! (cd "$dir" && /usr/bin/time -f '%e %U %S' -o "$work/t" "$bin" -q $name ${SUPERJOIN_ARGS:-} \
              -o "$work/$side.lst" >/dev/null 2>"$work/err"); then
        rc=$?; [ $rc -eq 5 ] || { echo "ab.sh: $bin $name failed (exit $rc)" >&2; cat "$work/err" >&2; status=1; }
      fi
      read -r wall user sys <"$work/t"
      echo "$wall" >>"$work/w$side"; echo "$user + $sys" | bc -l >>"$work/u$side"
    done
  done
  same=identical
  if ! diff -q <(grep -v -E 'superjoin [0-9]|seconds|[0-9]+\.[0-9]+ s\b' "$work/a.lst") \
                <(grep -v -E 'superjoin [0-9]|seconds|[0-9]+\.[0-9]+ s\b' "$work/b.lst") >/dev/null; then
    same=DIFFER; status=1
  fi
  wa=$(median <"$work/wa"); wb=$(median <"$work/wb"); ua=$(median <"$work/ua"); ub=$(median <"$work/ub")
  printf '%-28s %9.2f %9.2f %7.3f %9.2f %9.2f %7.3f  %s\n' "$name" "$wa" "$wb" \
         "$(echo "$wb / $wa" | bc -l)" "$ua" "$ub" "$(echo "$ub / $ua" | bc -l)" "$same"
done
exit $status
