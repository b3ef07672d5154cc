#!/usr/bin/env bash
# Every keyword the parser dispatches (the `select case (kw%keyword)` block of
# src/deck/parser.f90, plus *INCLUDE) has a row in doc/deck-reference.md, a
# heading in doc/user-manual.md and an entry in the keyword table of
# src/deck/ccx_cards.f90 (blanks in keywords are ignored through it).
# usage: check_cards_documented.sh SOURCE_DIR
set -u
src=$1
kws=$(awk '/select case \(kw%keyword\)/ {on=1; next} on && /end select/ {exit} on' "$src/src/deck/parser.f90" |
      sed -e ':a' -e '/&$/N; s/&\n *//; ta' |
      grep -oE "case \('[A-Z -]+'(, *'[A-Z -]+')*\)" | grep -oE "'[A-Z -]+'" | tr -d "'" | sort -u)
[ -n "$kws" ] || { echo "FAIL: no keywords found in parser.f90"; exit 1; }
fail=0; n=0
while IFS= read -r kw; do
  n=$((n+1))
  grep -qE -- "^\|.*\`\*$kw" "$src/doc/deck-reference.md" || { echo "FAIL: *$kw has no row in doc/deck-reference.md"; fail=1; }
  grep -qE -- "^###.*\*$kw" "$src/doc/user-manual.md" || { echo "FAIL: *$kw has no heading in doc/user-manual.md"; fail=1; }
done <<< "$(printf '%s\nINCLUDE\n' "$kws")"
# Keywords are compared with their blanks removed (superjoin_deck_ccx_cards,
# canonical_keyword): every dispatched keyword must be in its table.
known=$(awk '/KNOWN_KEYWORDS\(NUM_KNOWN\) =/ {on=1} on {print} on && /\]/ {exit}' "$src/src/deck/ccx_cards.f90")
while IFS= read -r kw; do
  grep -qF -- "'$kw'" <<< "$known" || { echo "FAIL: *$kw is not in KNOWN_KEYWORDS of src/deck/ccx_cards.f90"; fail=1; }
done <<< "$(printf '%s\nINCLUDE\n' "$kws")"
# Part 2 of the reference is extensions.md itself (tools/deck_reference.py).
py=${PYTHON:-python3}   # the interpreter ctest found (tests/CMakeLists.txt)
if command -v "$py" >/dev/null; then "$py" "$src/tools/deck_reference.py" --check || fail=1; fi
[ $fail -eq 0 ] && echo "all $n cards documented"
exit $fail
