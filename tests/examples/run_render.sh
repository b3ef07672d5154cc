#!/usr/bin/env bash
# tools/render draws a 2D deck, a 3D deck and a .pvd into PNG files, states the
# magnification, and refuses an unknown step.
# usage: run_render.sh SOURCE_DIR SUPERJOIN WORK_DIR
set -u
src=$1; bin=$2; work=$3
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail=0
png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] && [ "$(stat -c %s "$1")" -gt 5000 ]; }
"$src/tools/render" --superjoin "$bin" "$src/decks/demo.deck" --step ROOF -o demo.png --gnuplot-script demo.gp > out.txt || fail=1
png demo.png || { echo "FAIL: demo.png is not a PNG"; fail=1; }
grep -q '2D view, magnification x' out.txt || { echo "FAIL: 2D view not reported"; cat out.txt; fail=1; }
grep -q 'magnified x' demo.gp || { echo "FAIL: the title does not state the magnification"; fail=1; }
"$src/tools/render" --superjoin "$bin" "$src/decks/frame3d.deck" -o f3.png > out.txt || fail=1
png f3.png || { echo "FAIL: f3.png is not a PNG"; fail=1; }
grep -q '3D view' out.txt || { echo "FAIL: a 3D model was not drawn in 3D"; cat out.txt; fail=1; }
"$bin" -q "$src/decks/truss.deck" -o t.lst --vtk v/truss
"$src/tools/render" v/truss.pvd --step SIDE --scale 1000 -o t.png > out.txt || fail=1
png t.png && grep -q 'magnification x1000' out.txt || { echo "FAIL: render of a .pvd with --scale"; cat out.txt; fail=1; }
if "$src/tools/render" v/truss.pvd --step NOPE -o n.png 2>err.txt; then echo "FAIL: unknown step accepted"; fail=1; fi
grep -q "no step 'NOPE'" err.txt || { echo "FAIL: unknown step message"; cat err.txt; fail=1; }
[ $fail -eq 0 ] && echo "render: PNG files written"
exit $fail
