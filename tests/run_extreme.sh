#!/usr/bin/env bash
# Solve a deck with extreme numbers (tests/extreme) and check the outcome.
# usage: run_extreme.sh SUPERJOIN DECK OUTDIR
# First line of the deck: '** expect: STATUS SUBSTRING' (SUBSTRING must appear on
# stderr; the run is not quiet, so warnings and phase reports are there), then
# any '** also: SUBSTRING' lines. Whatever the status: no NaN or Inf in any
# output (listing, CSV, stderr), no crash report, no temporary file; a
# failed run writes no listing.
set -u
bin=$1; deck=$2; outdir=$3
name=$(basename "$deck" .deck)
mkdir -p "$outdir"; outdir=$(cd "$outdir" && pwd)
case "$bin" in /*) ;; *) bin="$(pwd)/$bin" ;; esac
header=$(head -n 1 "$deck")
spec=${header#"** expect: "}
want_status=${spec%% *}; want_msg=${spec#* }
lst="$outdir/$name.lst"; csv="$outdir/$name.csv"; err="$outdir/$name.err"
rm -rf "$lst" "$csv" "$err"
(cd "$(dirname "$deck")" && "$bin" "$name.deck" -o "$lst" --csv "$csv" >/dev/null 2>"$err")
status=$?
fail=0
[ "$status" -eq "$want_status" ] || { echo "FAIL: exit status $status, expected $want_status"; fail=1; }
grep -qF -- "$want_msg" "$err" || { echo "FAIL: stderr lacks: $want_msg"; fail=1; }
while IFS= read -r m; do
  grep -qF -- "$m" "$err" || { echo "FAIL: stderr lacks: $m"; fail=1; }
done < <(grep -E '^\*\* also: ' "$deck" | sed 's/^\*\* also: //')
grep -qiE 'runtime error|backtrace|segmentation|sanitizer|floating.point exception' "$err" && { echo "FAIL: crash output"; fail=1; }
outputs=("$err")
[ -e "$lst" ] && outputs+=("$lst")
[ -d "$csv" ] && outputs+=("$csv"/*.csv)
if grep -qiwE 'nan|inf|infinity' "${outputs[@]}"; then
  echo "FAIL: NaN or Inf in the output:"; grep -iwnE 'nan|inf|infinity' "${outputs[@]}" | head -5; fail=1
fi
# 5: solved, listing written, results judged inaccurate
if [ "$status" -ne 0 ] && [ "$status" -ne 5 ] && [ -e "$lst" ]; then echo "FAIL: a failed run wrote a listing"; fail=1; fi
if { [ "$status" -eq 0 ] || [ "$status" -eq 5 ]; } && ! grep -q 'END OF LISTING' "$lst"; then echo "FAIL: listing incomplete"; fail=1; fi
ls "$outdir/$name".*.tmp "$lst.tmp" "$csv"/*.tmp >/dev/null 2>&1 && { echo "FAIL: temporary file left"; fail=1; }
[ $fail -eq 0 ] && echo "extreme $name: status $status as expected"
[ $fail -eq 0 ] || cat "$err"
exit $fail
