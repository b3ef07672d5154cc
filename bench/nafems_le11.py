#!/usr/bin/env python3
"""NAFEMS LE11 (solid cylinder/taper/sphere, temperature T = r + z): sigma_zz
at A = (1, 0, 0) against -105 MPa, superjoin and CalculiX side by side.

usage: bench/nafems_le11.py [--exe BIN] [--work DIR] [--repeat R] [--out CSV]

Decks: tests/solids/le11_deck.py (the profile, its sources and the
supports). gmsh's quadrangles of the profile at characteristic length h
(8 nodes for C3D20R, 4 for C3D8I) are swept through the quarter in n_phi
layers; both programs read the same deck (`-i job`, OMP_NUM_THREADS=1),
sigma_zz is the nodal value of the .frd's STRESS block at A, the time the
wall clock and CPU time of the run (bench/nafems_le10.py's run). Profile "finEALE" (D at
z = 0.7, the drawing's) on every mesh, "feenox" (D at z = sqrt(1/2)) on the
finest C3D20R mesh.
"""
import argparse
import csv
import os
import shutil
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "solids"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import le10_deck  # noqa: E402
import le11_deck as le11  # noqa: E402
from nafems_le10 import run, table_row  # noqa: E402

MESHES = [("C3D20R", 0.4, 2, "finEALE"), ("C3D20R", 0.2, 4, "finEALE"), ("C3D20R", 0.1, 8, "finEALE"),
          ("C3D20R", 0.1, 8, "feenox"),
          ("C3D8I", 0.2, 4, "finEALE"), ("C3D8I", 0.1, 8, "finEALE"), ("C3D8I", 0.05, 16, "finEALE")]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--work", default="/tmp/nafems_le11")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "nafems_le11.csv"))
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    rows = []
    print("| element | profile | h, n_phi | elements | DOFs | superjoin sigma_zz (MPa) | ccx sigma_zz (MPa) | error | "
          "superjoin wall / CPU (s) | ccx wall / CPU (s) | CPU ccx / superjoin |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for etype, h, nphi, variant in MESHES:
        work = os.path.join(a.work, f"{etype}_{h}_{nphi}_{variant}")
        shutil.rmtree(work, ignore_errors=True)
        nodes, quads, zt = le11.mesh(work, h, etype == "C3D20R", variant)
        xyz, hexes = le11.revolve(nodes, quads, nphi)
        text, node_a = le11.deck3d(xyz, hexes, etype, zt)
        got = {}
        for who, cmd in (("superjoin", exe), ("ccx", "ccx")):
            w = os.path.join(work, who)
            os.makedirs(w, exist_ok=True)
            with open(os.path.join(w, "job.inp"), "w") as f:
                f.write(text)
            t = run(cmd, w, a.repeat)
            got[who] = (le10_deck.frd_stress(os.path.join(w, "job.frd"), node_a)[2], t) if t else (None, (None, None))
        (s_sj, t_sj), (s_cx, t_cx) = got["superjoin"], got["ccx"]
        err = (s_sj - le11.TARGET) / abs(le11.TARGET) if s_sj is not None else None
        rows.append(dict(element=etype, profile=variant, h=h, nphi=nphi, elements=len(hexes), dofs=3 * len(xyz),
                         sigma_superjoin=s_sj, sigma_ccx=s_cx, error=err, wall_superjoin=t_sj[0],
                         cpu_superjoin=t_sj[1], wall_ccx=t_cx[0], cpu_ccx=t_cx[1]))
        print(table_row([etype, variant, f"{h}, {nphi}", len(hexes), 3 * len(xyz)], s_sj, s_cx, err, t_sj, t_cx),
              flush=True)
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0 if all(r["sigma_superjoin"] is not None for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
