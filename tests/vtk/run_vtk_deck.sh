#!/usr/bin/env bash
# Solve one deck with --csv and --vtk, check the VTK files against the VTK XML
# format and against the CSV values (check_vtk.py), and check that a second
# run writes the same bytes.
# usage: run_vtk_deck.sh SUPERJOIN PYTHON DECK OUTDIR
set -u
bin=$1; py=$2; deck=$3; outdir=$4
here=$(cd "$(dirname "$0")" && pwd)
name=$(basename "$deck" .deck)
out="$outdir/$name"
rm -rf "$out"; mkdir -p "$out" || exit 1
"$bin" -q "$deck" -o "$out/a.lst" --csv "$out/csv" --vtk "$out/a/$name" || { echo "FAIL: superjoin exited with $?"; exit 1; }
"$bin" -q "$deck" -o "$out/b.lst" --vtk "$out/b/$name.pvd" || { echo "FAIL: second run exited with $?"; exit 1; }
status=0
for f in "$out/a"/*; do
  cmp -s "$f" "$out/b/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs between two runs"; status=1; }
done
[ "$(ls "$out/a" | wc -l)" -eq "$(ls "$out/b" | wc -l)" ] || { echo "FAIL: the runs wrote different files"; status=1; }
ls "$out/a" | grep -q '\.tmp$' && { echo "FAIL: temporary file left"; status=1; }
"$py" "$here/check_vtk.py" "$out/a/$name.pvd" --csv "$out/csv" || status=1
exit $status
