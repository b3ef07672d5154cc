#!/usr/bin/env python3
"""gen_stiffened.py -- stiffened-plate benchmark deck for superjoin.

An S4 skin (one substructure, m x m elements, simply supported edges, uniform
pressure) carries B33 stiffeners along x on every SPACING-th grid line (a
second substructure with its own nodes, coincident with the skin's), joined
node by node by compliant contact elements on all six DOFs.

usage: gen_stiffened.py (--dofs N | --mesh M) DECK
Prints on stderr: "gen_stiffened: M x M x K stiffened plate: E equations (D nodal DOFs ...)"
(the format bench/run_frame.sh reads; E is an estimate: D less the supported DOFs).
"""
import argparse
import sys

SPACING = 8                 # stiffener every SPACING grid lines
A, T = 1.0, 0.01            # plate side and skin thickness
E, NU = 2.1e11, 0.3
STIFF_SECTION = (2.0e-4, 4.0e-8, 1.0e-9, 5.0e-10)   # A, Iy, Iz, J
G_TRANS, G_ROT = 1.0e10, 1.0e5                    # joint stiffness per node
PRESSURE = 1.0e3


def counts(m):
    nstiff = len(stiffener_lines(m))
    return 6 * ((m + 1) ** 2 + nstiff * (m + 1)), nstiff


def stiffener_lines(m):
    return [j for j in range(SPACING, m, SPACING)]


def main():
    ap = argparse.ArgumentParser()
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument("--dofs", type=float)
    g.add_argument("--mesh", type=int)
    ap.add_argument("deck")
    a = ap.parse_args()
    if a.mesh:
        m = a.mesh
    else:
        m = 2
        while counts(m + 1)[0] <= a.dofs:
            m += 1
    m = max(2, m)
    ndof, nstiff = counts(m)
    lines = stiffener_lines(m)
    h = A / m

    def sid(i, j):
        return 1 + j * (m + 1) + i
    out = ["*HEADING", f"stiffened plate {m} x {m} S4, {nstiff} B33 stiffeners",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", f" {E!r}, {NU!r}",
           "*SUBSTRUCTURE, NAME=SKIN", "*NODE"]
    out += [f" {sid(i, j)}, {i * h!r}, {j * h!r}, 0.0" for j in range(m + 1) for i in range(m + 1)]
    out.append("*ELEMENT, TYPE=S4, ELSET=SKIN")
    e = 1
    for j in range(m):
        for i in range(m):
            out.append(f" {e}, {sid(i, j)}, {sid(i + 1, j)}, {sid(i + 1, j + 1)}, {sid(i, j + 1)}")
            e += 1
    edge = sorted({sid(i, j) for j in range(m + 1) for i in range(m + 1) if i in (0, m) or j in (0, m)})
    out.append("*NSET, NSET=EDGE")
    out += [" " + ", ".join(map(str, edge[k:k + 16])) for k in range(0, len(edge), 16)]
    out += ["*SHELL SECTION, ELSET=SKIN, MATERIAL=STEEL", f" {T!r}", "*END SUBSTRUCTURE"]

    out += ["*SUBSTRUCTURE, NAME=STIFF", "*NODE"]
    bid = {}
    n = 1
    for j in lines:
        for i in range(m + 1):
            bid[(i, j)] = n
            out.append(f" {n}, {i * h!r}, {j * h!r}, 0.0")
            n += 1
    out.append("*ELEMENT, TYPE=B33, ELSET=BEAMS")
    e = 1
    for j in lines:
        for i in range(m):
            out.append(f" {e}, {bid[(i, j)]}, {bid[(i + 1, j)]}")
            e += 1
    out += ["*BEAM SECTION, ELSET=BEAMS, MATERIAL=STEEL", " " + ", ".join(map(repr, STIFF_SECTION)),
            "*END SUBSTRUCTURE"]

    out.append("*CONTACT, NAME=WELD, MASTER=SKIN, SLAVE=STIFF")
    for (i, j), b in bid.items():
        out.append(f" {sid(i, j)}, {b}, 1, 3, {G_TRANS!r}")
        out.append(f" {sid(i, j)}, {b}, 4, 6, {G_ROT!r}")
    out += ["*BOUNDARY", " SKIN.EDGE, 1, 3", "*STEP, NAME=PRESSURE", "*DLOAD", f" SKIN.SKIN, P, {-PRESSURE!r}",
            "*END STEP"]
    with open(a.deck, "w") as f:
        f.write("\n".join(out) + "\n")
    nsupp = 3 * len(edge)
    print(f"gen_stiffened: {m} x {m} x {nstiff} stiffened plate: {ndof - nsupp} equations "
          f"({ndof} nodal DOFs, {nsupp} supported)", file=sys.stderr)


if __name__ == "__main__":
    main()
