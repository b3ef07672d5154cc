#!/usr/bin/env python3
"""A strip of N S4 panels joined edge to edge: parts with large boundaries.

usage: gen_strip.py [--panels N] [--mesh M] [--joint G] > strip.deck

N square steel panels (1 m, 50 mm, M x M S4 elements each, one *SUBSTRUCTURE
each) side by side along x; the right edge of panel k is joined to the left
edge of panel k+1 node by node: translations RIGID, rotations of stiffness G
(default 1e6 N m/rad per node pair). Panel 1 is clamped along its left edge;
every panel carries a pressure. Each panel has 6 (M+1)^2 DOFs of which
12 (M+1) lie on its two joined edges (6 (M+1) for the first and last): its
condensed stiffness K* is dense on those, 8 (12 (M+1))^2 bytes, far more than
its interior. The benchmark of owners keeping their K* (bench/run_mpi_owner.sh
--strip) uses it; the modules models (gen_modules.py) have 48 boundary DOFs
per part, where K* is negligible.
"""
import argparse


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--panels", type=int, default=8)
    ap.add_argument("--mesh", type=int, default=20)
    ap.add_argument("--joint", type=float, default=1.0e6)
    a = ap.parse_args()
    n, m = a.panels, a.mesh
    h = 1.0 / m
    out = ["*HEADING",
           f"Strip of {n} S4 panels ({m}x{m} each) joined edge to edge, bench/gen_strip.py --panels {n} --mesh {m}",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e+11, 0.3"]
    for p in range(n):
        out.append(f"*SUBSTRUCTURE, NAME=P{p + 1}")
        out.append("*NODE")
        for j in range(m + 1):
            for i in range(m + 1):
                out.append(f"{j * (m + 1) + i + 1}, {p + i * h:.12g}, {j * h:.12g}, 0")
        out.append("*ELEMENT, TYPE=S4, ELSET=SKIN")
        e = 0
        for j in range(m):
            for i in range(m):
                e += 1
                n1 = j * (m + 1) + i + 1
                out.append(f"{e}, {n1}, {n1 + 1}, {n1 + m + 2}, {n1 + m + 1}")
        out.append("*NSET, NSET=LEFT")
        out.append(", ".join(str(j * (m + 1) + 1) for j in range(m + 1)))
        out.append("*NSET, NSET=RIGHT")
        out.append(", ".join(str(j * (m + 1) + m + 1) for j in range(m + 1)))
        out += ["*SHELL SECTION, ELSET=SKIN, MATERIAL=STEEL", "0.05", "*END SUBSTRUCTURE"]
    for p in range(n - 1):
        out.append(f"*CONTACT, NAME=J{p + 1}, MASTER=P{p + 1}, SLAVE=P{p + 2}")
        out.append("RIGHT, LEFT, 1, 3, RIGID")
        out.append(f"RIGHT, LEFT, 4, 6, {a.joint:g}")
    out += ["*BOUNDARY", "P1.LEFT, 1, 6", "*STEP, NAME=PRESSURE", "*DLOAD"]
    out += [f"P{p + 1}.SKIN, P, -100" for p in range(n)]   # along -normal: *DLOAD P pushes along it
    out.append("*END STEP")
    print("\n".join(out))


if __name__ == "__main__":
    main()
