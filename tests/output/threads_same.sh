#!/usr/bin/env bash
# The listing's long tables are formatted on two threads where the machine
# has two CPUs (src/output/rows.f90): a listing must be byte for byte the one
# a single thread writes. Three models whose every long table spans several
# chunks of 2048 items (each thread's share per turn): a frame (displacements,
# contact forces, element end forces), CPS4 panels (plate resultants and
# stresses), a truss strip (truss axial forces). OpenBLAS on one thread in
# both runs, so that only the listing's threads differ (OpenBLAS's own
# threads change the last digits of some results). Exit 77 (skipped) on a
# machine with one CPU, where there is no second thread to compare with.
#
# usage: threads_same.sh SUPERJOIN GEN_FRAME PYTHON ROOT WORKDIR
set -euo pipefail
bin=$(realpath "$1"); gen_frame=$(realpath "$2"); python=$3; root=$(realpath "$4"); work=$5
[ "$(nproc)" -ge 2 ] || { echo "one CPU: no second thread to compare with"; exit 77; }
mkdir -p "$work"
cd "$work"
"$gen_frame" --dofs 3e4 --shape long frame.deck 2>/dev/null
"$python" "$root/bench/gen_panel_grid.py" --nx 2 --ny 1 --mesh 40 > panels.deck
"$python" - > trusses.deck <<'EOF'
# a plane truss strip of 1000 bays (top and bottom chords, posts, diagonals:
# 4001 T2D2 bars) on rollers along its bottom chord, held at its left end,
# loaded on its top chord and pulled at its right end
n = 1000
print("*HEADING\ntruss strip for tests/output/threads_same.sh")
print("*NODE, NSET=ALL")
for i in range(n + 1):
    print(f"{2 * i + 1}, {float(i)}, 0.0")
    print(f"{2 * i + 2}, {float(i)}, 1.0")
print("*ELEMENT, TYPE=T2D2, ELSET=BARS")
e = 0
for i in range(n + 1):
    e += 1; print(f"{e}, {2 * i + 1}, {2 * i + 2}")
    if i < n:
        e += 1; print(f"{e}, {2 * i + 1}, {2 * i + 3}")
        e += 1; print(f"{e}, {2 * i + 2}, {2 * i + 4}")
        e += 1; print(f"{e}, {2 * i + 1}, {2 * i + 4}")
print("*MATERIAL, NAME=STEEL\n*ELASTIC\n210e9, 0.3")
print("*SOLID SECTION, ELSET=BARS, MATERIAL=STEEL\n1e-3")
print("*BOUNDARY\n1, 1, 2\n2, 1")
for i in range(1, n + 1):
    print(f"{2 * i + 1}, 2")
print("*STEP\n*STATIC\n*CLOAD")
for i in range(n + 1):
    print(f"{2 * i + 2}, 2, {-1000.0 - i}")
print(f"{2 * n + 2}, 1, 500.0")
print("*END STEP")
EOF
status=0
for model in frame panels trusses; do
  env -u OMP_NUM_THREADS OPENBLAS_NUM_THREADS=1 "$bin" -q "$model.deck" -o "$model.two.lst"
  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$bin" -q "$model.deck" -o "$model.one.lst"
  if cmp -s "$model.two.lst" "$model.one.lst"; then
    echo "$model: the listing on two threads is the one-thread listing ($(wc -l < "$model.one.lst") lines)"
  else
    echo "FAIL: $model: the listing on two threads differs from the one-thread listing"
    cmp "$model.two.lst" "$model.one.lst" || true
    status=1
  fi
done
exit $status
