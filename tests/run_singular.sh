#!/usr/bin/env bash
# Solve a deck that must fail in the solution phase (exit 3) and check the
# message names the location, nothing crashes, no listing is written, and
# every backend (--solver lapack, cholmod, umfpack; mumps and mumps-ldlt when
# built in) prints the same message.
# usage: run_singular.sh SUPERJOIN DECK OUTDIR
# The deck's first line: '** expect: STATUS SUBSTRING'; more '** also: SUBSTRING' lines may follow.
set -u
bin=$1; deck=$2; outdir=$3
name=$(basename "$deck" .deck)
mkdir -p "$outdir"; outdir=$(cd "$outdir" && pwd)
header=$(head -n 1 "$deck")
spec=${header#"** expect: "}
want_status=${spec%% *}; want_msg=${spec#* }
lst="$outdir/$name.lst"; rm -f "$lst"
(cd "$(dirname "$deck")" && "$bin" -q "$name.deck" -o "$lst" >"$outdir/$name.out" 2>"$outdir/$name.err")
status=$?
fail=0
[ "$status" -eq "$want_status" ] || { echo "FAIL: exit status $status, expected $want_status"; fail=1; }
grep -qF -- "$want_msg" "$outdir/$name.err" || { echo "FAIL: stderr lacks: $want_msg"; fail=1; }
grep -E '^\*\* also: ' "$deck" | sed 's/^\*\* also: //' | while IFS= read -r m; do
  grep -qF -- "$m" "$outdir/$name.err" || { echo "FAIL: stderr lacks: $m"; exit 1; }
done || fail=1
grep -qiE 'runtime error|backtrace|segmentation|sigsegv' "$outdir/$name.err" && { echo "FAIL: crash output"; fail=1; }
[ -e "$lst" ] && { echo "FAIL: a listing was written"; fail=1; }
ls "$outdir/$name.lst.tmp" >/dev/null 2>&1 && { echo "FAIL: temporary listing left"; fail=1; }
# The same message (location and mechanism report) from every backend, MUMPS
# included when built in (--solver mumps is a usage error otherwise).
backends="lapack cholmod umfpack"
"$bin" --solver mumps --version >/dev/null 2>&1 && backends="$backends mumps mumps-ldlt"
for s in $backends; do
  (cd "$(dirname "$deck")" && "$bin" -q --solver $s "$name.deck" -o "$lst" >/dev/null 2>"$outdir/$name.$s.err")
  st=$?
  [ "$st" -eq "$want_status" ] || { echo "FAIL: --solver $s: exit status $st, expected $want_status"; fail=1; }
  cmp -s "$outdir/$name.err" "$outdir/$name.$s.err" || {
    echo "FAIL: --solver $s reports differently:"; diff "$outdir/$name.err" "$outdir/$name.$s.err"; fail=1; }
done
[ -e "$lst" ] && { echo "FAIL: a listing was written"; fail=1; }
[ $fail -eq 0 ] && echo "singular $name: status $status as expected, same report from every backend"; cat "$outdir/$name.err"
exit $fail
