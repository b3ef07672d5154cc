#!/usr/bin/env bash
# Which decks of the CalculiX test suite (Debian package calculix-ccx-test) that
# contain *STATIC superjoin reads unchanged, and for the others the first
# refusal, grouped by reason: one line per reason with the decks it stops.
# usage: survey_suite.sh SUPERJOIN [SUITE_DIR]
set -u
bin=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
suite=${2:-/usr/share/doc/calculix-ccx-test/examples/test}
[ -d "$suite" ] || { echo "no $suite: apt-get install calculix-ccx-test"; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for f in "$suite"/*.inp "$suite"/*.inp.gz; do
  b=$(basename "$f")
  case $b in *.gz) zcat "$f" > "$work/${b%.gz}" ;; *) cp "$f" "$work/" ;; esac
done
cd "$work" || exit 2
for f in $(grep -li '^\*static' *.inp | sort); do
  msg=$(timeout 30 "$bin" -q --check "$f" 2>&1 | head -n 1)
  if [ -z "$msg" ]; then
    echo "reads: ${f%.inp}"
  else
    # the reason without file:line, element types and numbers kept
    echo "${msg#*: error: }|${f%.inp}"
  fi
done | sed -E 's/ \(supported: [^)]*\)//; s/got [0-9]+ fields/got more fields/' |
  awk -F'|' '/^reads: /{r = r " " substr($0, 8); next}
             {n[$1]++; d[$1] = d[$1] " " $2}
             END {print n_r "reads unchanged:" r;
                  for (k in n) printf "%d | %s |%s\n", n[k], k, d[k]}' | sort -t'|' -k1,1nr
