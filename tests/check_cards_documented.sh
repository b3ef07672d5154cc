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
# Every parameter name with a blank that a card takes (its check_params list)
# is in SPACED_PARAMS of src/deck/lexer.f90, so that CalculiX's spelling
# without the blank (REFNODE=) is read as it.
spaced=$(awk '/SPACED_PARAMS\(\*\) =/ {on=1} on {print} on && /\]/ {exit}' "$src/src/deck/lexer.f90")
while IFS= read -r p; do
  [ -n "$p" ] || continue
  grep -qF -- "'$p'" <<< "$spaced" || { echo "FAIL: parameter '$p' has a blank and is not in SPACED_PARAMS of src/deck/lexer.f90"; fail=1; }
done <<< "$(awk '/check_params\(/ {on=1} on {print} on && !/&[[:space:]]*$/ {on=0}' "$src"/src/deck/*.f90 |
            grep -oE "'[A-Z0-9-]+( [A-Z0-9-]+)+'" | tr -d "'" | sort -u)"
# Every element type of src/model/types.f90 (ELEMENT_TYPE_NAMES, in the order of
# their numbers) has a row in the element tables of doc/deck-reference.md
# (section 4) and doc/user-manual.md, is named in the *ELEMENT row of the
# reference, and has its number in the VTK output's element_type list.
types=$(awk '/ELEMENT_TYPE_NAMES\(NUM_ELEMENT_TYPES\) =/ {on=1} on {print} on && /\]/ {exit}' \
        "$src/src/model/types.f90" | grep -oE "'[A-Z0-9]+ *'" | tr -d "' ")
[ -n "$types" ] || { echo "FAIL: no element types found in src/model/types.f90"; fail=1; }
ref_table=$(awk '/^## 4\. Elements/ {on=1; next} on && /^## / {exit} on' "$src/doc/deck-reference.md" | grep -E '^\| `')
man_table=$(grep -E '^\| `[A-Z0-9]+`.*\| (`\*[A-Z ]+ SECTION`|`\*SOLID SECTION`)' "$src/doc/user-manual.md")
element_row=$(grep -E -- '^\| `\*ELEMENT, TYPE=' "$src/doc/deck-reference.md")
vtk_list=$(grep -E -- '`element_type` \(' "$src/doc/deck-reference.md")
code=0; nt=0
while IFS= read -r t; do
  code=$((code+1)); nt=$((nt+1))
  grep -qE -- "\`$t\`" <<< "$ref_table" || { echo "FAIL: element type $t has no row in section 4 of doc/deck-reference.md"; fail=1; }
  grep -qE -- "\`$t\`" <<< "$man_table" || { echo "FAIL: element type $t has no row in the element table of doc/user-manual.md"; fail=1; }
  grep -qE -- "[ (]$t[,;) ]" <<< "$element_row" || { echo "FAIL: element type $t is not named in the *ELEMENT row of doc/deck-reference.md"; fail=1; }
  grep -qE -- "[ (]$code $t[,;) ]" <<< "$vtk_list" || { echo "FAIL: element type $t (number $code) is not in the VTK element_type list of doc/deck-reference.md"; fail=1; }
done <<< "$types"
# Part 2 of the reference is extensions.md itself (tools/deck_reference.py).
py=${PYTHON:-python3}   # the interpreter ctest found (tests/CMakeLists.txt)
if command -v "$py" >/dev/null; then "$py" "$src/tools/deck_reference.py" --check || fail=1; fi
[ $fail -eq 0 ] && echo "all $n cards and $nt element types documented"
exit $fail
