#!/usr/bin/env bash
# Tip deflection of VM18 (curved bar) with N = 9, 18, 36, 72 straight B33
# elements against Timoshenko's formula: the table of doc/verification.md.
# usage: tests/vm/vm18_convergence.sh [SUPERJOIN]
set -eu
here=$(cd "$(dirname "$0")" && pwd)
bin=${1:-$here/../../build/superjoin}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
exact=$(python3 -c "import math; E=30e6; G=E/2.6; I=math.pi/4; F=50; r=100; print(F*r**3/(E*I)*math.pi/4 + F*r**3/(G*2*I)*(3*math.pi/4-2))")
printf '%4s %12s %10s\n' N delta rel_error
for n in 9 18 36 72; do
  python3 "$here/vm18_deck.py" "$n" > "$work/vm18_$n.deck"
  "$bin" -q "$work/vm18_$n.deck" -o "$work/vm18_$n.lst" --csv "$work/csv_$n"
  d=$(awk -F, -v node=$((n + 1)) '$3 == node {print -$6}' "$work/csv_$n/displacements.csv")
  python3 -c "print('%4d %12.6f %10.2e' % ($n, $d, abs($d - $exact)/$exact))"
done
echo "exact $exact (published 2.648)"
