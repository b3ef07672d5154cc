#!/usr/bin/env bash
# Run `superjoin --check` on a deck that must be rejected and check the outcome.
# usage: run_bad_deck.sh SUPERJOIN DECK OUTDIR
#
# The deck's first line states what is expected:
#   ** expect: STATUS SUBSTRING
# and any number of following lines may add substrings that must appear too:
#   ** also: SUBSTRING
# A line `** errors: N` requires exactly N error lines (one error per mistake).
# The binary runs in the deck's directory on NAME.deck, so messages name
# `NAME.deck:LINE`. The test passes when the exit status is STATUS, stderr
# contains every substring, nothing looks like a crash and no listing is written.
set -u
if [ $# -ne 3 ]; then echo "usage: run_bad_deck.sh SUPERJOIN DECK OUTDIR"; exit 2; fi
bin=$1; deck=$2; outdir=$3
name=$(basename "$deck" .deck)
deckdir=$(cd "$(dirname "$deck")" && pwd) || { echo "FAIL: no directory for $deck"; exit 1; }
mkdir -p "$outdir" || { echo "FAIL: cannot create $outdir"; exit 1; }
outdir=$(cd "$outdir" && pwd)
case "$bin" in /*) ;; *) bin="$(pwd)/$bin" ;; esac

header=$(head -n 1 "$deck" | tr -d '\r')
case "$header" in
  "** expect: "*) ;;
  *) echo "FAIL: $deck: first line must be '** expect: STATUS MESSAGE'"; exit 1 ;;
esac
spec=${header#"** expect: "}
want_status=${spec%% *}
want_msg=${spec#* }
case "$want_status" in ''|*[!0-9]*) echo "FAIL: $deck: bad expected status '$want_status'"; exit 1 ;; esac

lst="$outdir/$name.lst"
out="$outdir/$name.out"
err="$outdir/$name.err"
rm -f "$lst" "$out" "$err"
(cd "$deckdir" && "$bin" -q --check "$name.deck" -o "$lst" >"$out" 2>"$err")
status=$?

fail=0
if [ "$status" -ne "$want_status" ]; then
  echo "FAIL: exit status $status, expected $want_status"; fail=1
fi
check_substring() {
  if ! grep -qF -- "$1" "$err"; then
    echo "FAIL: stderr lacks: $1"; fail=1
  fi
}
check_substring "$want_msg"
while IFS= read -r line; do
  line=${line%$'\r'}
  case "$line" in
    "** also: "*) check_substring "${line#"** also: "}" ;;
  esac
done < <(tail -n +2 "$deck")
want_errors=$(grep -m1 -E '^\*\* errors: [0-9]+' "$deck" | tr -dc '0-9')
if [ -n "$want_errors" ]; then
  got_errors=$(grep -c ': error: ' "$err")
  [ "$got_errors" -eq "$want_errors" ] || { echo "FAIL: $got_errors error lines, expected $want_errors"; fail=1; }
fi
if grep -qiE 'runtime error|backtrace|segmentation' "$out" "$err"; then
  echo "FAIL: output looks like a crash"; fail=1
fi
if [ -e "$lst" ]; then
  echo "FAIL: a listing was written: $lst"; fail=1
fi
if [ $fail -ne 0 ]; then
  echo "--- stderr of superjoin -q --check $name.deck:"; cat "$err"
  exit 1
fi
echo "bad deck $name: rejected as expected (status $status)"
exit 0
