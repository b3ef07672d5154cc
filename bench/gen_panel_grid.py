#!/usr/bin/env python3
"""A grid of CPS4 panels joined along whole edges (the ordering benchmark).

usage: gen_panel_grid.py [--nx NX] [--ny NY] [--mesh M] [--g G] [--bolted] > grid.deck

NX x NY square steel plane-stress panels (1 m, 50 mm, M x M CPS4 elements
each), every panel a substructure of its own, side by side in the XY plane.
Neighbours are joined node by node along their whole common edge: the
normal translation RIGID, the shear translation a spring of stiffness G
(N/m per node pair; default 1e9). The panels of the first column are
clamped along their left edge, the last column is pulled and sheared at its
right edge. Each panel has 2 (M+1)^2 nodal DOFs (24 panels of M = 90:
397 488). The monolithic matrix is a 2D mesh with seams: the model on which
the node-graph METIS ordering competes with CHOLMOD's own AMD analysis
(doc/performance.md).

With --bolted the panels are 24 instances (NX x NY) of one *PART PANEL,
bolted to each other at three points per edge (nodes M/4, M/2, M - M/4 of
the edge: normal translation RIGID, shear G) and to a surrounding frame at
the three points of each outer edge (both translations held), each panel
loaded at its middle node by its own force (it grows with the panel's
place): every instance has the same 12 boundary nodes, so one condensation
serves all (doc/performance.md, "Identical instances").
"""
import argparse

SIDE = 1.0
THICK = 0.05
E, NU = 2.1e11, 0.3


def chunk(ids, per=16):
    return [", ".join(str(i) for i in ids[k:k + per]) for k in range(0, len(ids), per)]


def panel(name, m, x0, y0):
    n1 = m + 1
    out = [f"*SUBSTRUCTURE, NAME={name}", "*NODE"]
    for j in range(n1):
        for i in range(n1):
            out.append(f"{j * n1 + i + 1}, {x0 + SIDE * i / m:.12g}, {y0 + SIDE * j / m:.12g}, 0")
    out.append("*ELEMENT, TYPE=CPS4, ELSET=SKIN")
    for j in range(m):
        for i in range(m):
            a = j * n1 + i + 1
            out.append(f"{j * m + i + 1}, {a}, {a + 1}, {a + n1 + 1}, {a + n1}")
    edges = {"LEFT": [j * n1 + 1 for j in range(n1)], "RIGHT": [j * n1 + n1 for j in range(n1)],
             "BOTTOM": [i + 1 for i in range(n1)], "TOP": [m * n1 + i + 1 for i in range(n1)]}
    for edge, ids in edges.items():
        out.append(f"*NSET, NSET={edge}")
        out += chunk(ids)
    out.append("*SOLID SECTION, ELSET=SKIN, MATERIAL=STEEL")
    out.append(f"{THICK}")
    out.append("*END SUBSTRUCTURE")
    return out


def bolt_index(m):
    """Positions along an edge (0..M) of the three bolts."""
    return [m // 4, m // 2, m - m // 4]


def bolted_part(m):
    """One *PART PANEL: the panel at the origin, its bolt sets and its middle node."""
    n1 = m + 1
    out = panel("PANEL", m, 0.0, 0.0)
    out[0] = "*PART, NAME=PANEL"
    out[-1] = "*END PART"
    b = bolt_index(m)
    sets = {"LB": [j * n1 + 1 for j in b], "RB": [j * n1 + n1 for j in b],
            "BB": [i + 1 for i in b], "TB": [m * n1 + i + 1 for i in b], "MID": [(m // 2) * n1 + m // 2 + 1]}
    extra = []
    for name, ids in sets.items():
        extra.append(f"*NSET, NSET={name}")
        extra += chunk(ids)
    return out[:-3] + extra + out[-3:]


def bolted(args):
    """The --bolted deck (see the module's doc)."""
    nx, ny, m = args.nx, args.ny, args.mesh
    name = lambda i, j: f"P{i + 1}_{j + 1}"
    out = ["*HEADING", f"{nx} x {ny} instances of one CPS4 panel ({m}x{m}) bolted at three points per edge, "
           f"bench/gen_panel_grid.py --bolted --nx {nx} --ny {ny} --mesh {m}",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:.6g}, {NU}"]
    out += bolted_part(m)
    out.append("*ASSEMBLY, NAME=GRID")
    for j in range(ny):
        for i in range(nx):
            out += [f"*INSTANCE, NAME={name(i, j)}, PART=PANEL", f"{i * SIDE:.12g}, {j * SIDE:.12g}, 0",
                    "*END INSTANCE"]
    for j in range(ny):
        for i in range(nx):
            if i + 1 < nx:
                out.append(f"*CONTACT, NAME=H{i + 1}_{j + 1}, MASTER={name(i, j)}, SLAVE={name(i + 1, j)}")
                out.append("RB, LB, 1, 1, RIGID")
                out.append(f"RB, LB, 2, 2, {args.g}")
            if j + 1 < ny:
                out.append(f"*CONTACT, NAME=V{i + 1}_{j + 1}, MASTER={name(i, j)}, SLAVE={name(i, j + 1)}")
                out.append("TB, BB, 2, 2, RIGID")
                out.append(f"TB, BB, 1, 1, {args.g}")
    out.append("*END ASSEMBLY")
    out.append("*BOUNDARY")
    for j in range(ny):
        out.append(f"{name(0, j)}.LB, 1, 2")
        out.append(f"{name(nx - 1, j)}.RB, 1, 2")
    for i in range(nx):
        out.append(f"{name(i, 0)}.BB, 1, 2")
        out.append(f"{name(i, ny - 1)}.TB, 1, 2")
    out.append("*STEP, NAME=PRESS")
    out.append("*CLOAD")
    for j in range(ny):
        for i in range(nx):
            k = j * nx + i
            out.append(f"{name(i, j)}.MID, 1, {1.0e4 * (1 + 0.1 * k):.6g}")
            out.append(f"{name(i, j)}.MID, 2, {-2.0e4 * (1 + 0.05 * k):.6g}")
    out.append("*END STEP")
    print("\n".join(out))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--nx", type=int, default=6)
    ap.add_argument("--ny", type=int, default=4)
    ap.add_argument("--mesh", type=int, default=90)
    ap.add_argument("--g", default="1e9")
    ap.add_argument("--bolted", action="store_true", help="instances of one panel bolted at 3 points per edge")
    args = ap.parse_args()
    if args.bolted:
        bolted(args)
        return
    nx, ny, m = args.nx, args.ny, args.mesh
    name = lambda i, j: f"P{i + 1}_{j + 1}"
    out = ["*HEADING", f"{nx} x {ny} CPS4 panels ({m}x{m} each) joined along whole edges, "
           f"bench/gen_panel_grid.py --nx {nx} --ny {ny} --mesh {m}",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:.6g}, {NU}"]
    for j in range(ny):
        for i in range(nx):
            out += panel(name(i, j), m, i * SIDE, j * SIDE)
    for j in range(ny):
        for i in range(nx):
            if i + 1 < nx:
                out.append(f"*CONTACT, NAME=H{i + 1}_{j + 1}, MASTER={name(i, j)}, SLAVE={name(i + 1, j)}")
                out.append("RIGHT, LEFT, 1, 1, RIGID")
                out.append(f"RIGHT, LEFT, 2, 2, {args.g}")
            if j + 1 < ny:
                out.append(f"*CONTACT, NAME=V{i + 1}_{j + 1}, MASTER={name(i, j)}, SLAVE={name(i, j + 1)}")
                out.append("TOP, BOTTOM, 2, 2, RIGID")
                out.append(f"TOP, BOTTOM, 1, 1, {args.g}")
    out.append("*BOUNDARY")
    for j in range(ny):
        out.append(f"{name(0, j)}.LEFT, 1, 2")
    out.append("*STEP, NAME=PULL")
    out.append("*CLOAD")
    for j in range(ny):
        out.append(f"{name(nx - 1, j)}.RIGHT, 1, {1.0e4 / (m + 1):.6g}")
        out.append(f"{name(nx - 1, j)}.RIGHT, 2, {2.0e3 / (m + 1):.6g}")
    out.append("*END STEP")
    print("\n".join(out))


if __name__ == "__main__":
    main()
