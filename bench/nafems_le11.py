#!/usr/bin/env python3
"""NAFEMS LE11 (solid cylinder/taper/sphere, temperature T = r + z): sigma_zz
at A = (1, 0, 0) against -105 MPa, superjoin and CalculiX side by side.

usage: bench/nafems_le11.py [--exe BIN] [--work DIR] [--repeat R] [--out CSV] [--full]

Decks: tests/solids/le11_deck.py (the profile, its sources and the
supports). gmsh's quadrangles of the profile at characteristic length h
(8 nodes for C3D20R, 4 for C3D8I) are swept through the quarter in n_phi
layers; both programs read the same deck (`-i job`, OMP_NUM_THREADS=1),
sigma_zz is the nodal value of the .frd's STRESS block at A, the time the
wall clock and CPU time of the run (bench/nafems_le10.py's run). Profile "finEALE" (D at
z = 0.7, the drawing's) on every mesh, "feenox" (D at z = sqrt(1/2)) beside
it on two C3D20R meshes. --full adds the finer meshes (45k DOFs C3D20R,
about a minute each on an idle machine).
"""
import os
import shutil
import sys

sys.dont_write_bytecode = True            # no bench/__pycache__ from importing nafems_le10
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "solids"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import le11_deck as le11  # noqa: E402
from nafems_le10 import arguments, both, table_row, write_csv  # noqa: E402

# (element, h, n_phi, profile, run by default (else with --full only))
MESHES = [("C3D20R", 0.4, 2, "finEALE", True), ("C3D20R", 0.2, 4, "finEALE", True),
          ("C3D20R", 0.2, 4, "feenox", True), ("C3D20R", 0.1, 8, "finEALE", False),
          ("C3D20R", 0.1, 8, "feenox", False),
          ("C3D8I", 0.2, 4, "finEALE", True), ("C3D8I", 0.1, 8, "finEALE", True), ("C3D8I", 0.05, 16, "finEALE", False)]


def main():
    ap = arguments("nafems_le11")
    ap.add_argument("--full", action="store_true")
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    rows = []
    print("| element | profile | h, n_phi | elements | DOFs | superjoin sigma_zz (MPa) | ccx sigma_zz (MPa) | error | "
          "superjoin wall / CPU (s) | ccx wall / CPU (s) | CPU ccx / superjoin |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for etype, h, nphi, variant, default in MESHES:
        if not (default or a.full):
            continue
        work = os.path.join(a.work, f"{etype}_{h}_{nphi}_{variant}")
        shutil.rmtree(work, ignore_errors=True)
        nodes, quads, zt = le11.mesh(work, h, etype == "C3D20R", variant)
        xyz, hexes = le11.revolve(nodes, quads, nphi)
        text, node_a = le11.deck3d(xyz, hexes, etype, zt)
        r = both(text, node_a, 2, work, exe, a.repeat, le11.TARGET)
        rows.append(dict(element=etype, profile=variant, h=h, nphi=nphi, elements=len(hexes), dofs=3 * len(xyz), **r))
        print(table_row([etype, variant, f"{h}, {nphi}", len(hexes), 3 * len(xyz)], r), flush=True)
    return write_csv(rows, a.out)


if __name__ == "__main__":
    sys.exit(main())
