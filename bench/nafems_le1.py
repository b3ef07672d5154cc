#!/usr/bin/env python3
"""NAFEMS LE1 (elliptic membrane) decks for CPS4 and CPS8, and what superjoin
gives today without nodal averaging.

usage: nafems_le1.py SUPERJOIN WORKDIR [--write-decks DIR]

Quarter of an elliptic membrane: inner ellipse x^2/2^2 + y^2/1^2 = 1, outer
ellipse x^2/3.25^2 + y^2/2.75^2 = 1, t = 0.1 m, E = 210 GPa, nu = 0.3, plane
stress; uniform outward normal traction 10 MPa on the outer edge; u_y = 0 on
y = 0, u_x = 0 on x = 0. Target: sigma_yy = 92.7 MPa at D = (2, 0), from
nodal stresses (NAFEMS).

The meshes are structured in the ellipse parameter (n_theta x n_r elements,
straight radial lines from (2 cos a, sin a) to (3.25 cos a, 2.75 sin a)),
not NAFEMS's standard meshes; the 3 x 2 and 6 x 4 meshes have the element
counts of NAFEMS's coarse (6) and fine (24) meshes. Mid-side nodes lie on the
ellipses. The outer traction is applied as consistent nodal loads (*CLOAD),
integrated by Gauss points along each (straight or parabolic) edge.

The table gives sigma_yy at the centroid of the element at D, and its
distance from D. These are centroid values, NOT the NAFEMS nodal value; they
approach 92.7 only as the centroid approaches D. The nodal value (*NODE PRINT
S, extrapolated from the integration points and averaged) with CPS4, CPS8 and
CPS8R: tests/results/le1_convergence.py (doc/verification.md).
"""
import argparse
import csv
import math
import os
import subprocess
import sys

E, NU, T, P = 210.0e3, 0.3, 0.1, 10.0     # MPa, m
TARGET = 92.7


def fmt(v):
    return repr(float(v))


def point(th_frac, r_frac):
    a = math.pi / 2 * th_frac
    xi, yi = 2.0 * math.cos(a), 1.0 * math.sin(a)
    xo, yo = 3.25 * math.cos(a), 2.75 * math.sin(a)
    return (xi + r_frac * (xo - xi), yi + r_frac * (yo - yi))


def mesh(nt, nr, etype):
    """Nodes {id: (x, y)}, elements [(id, node ids)] on the half-index grid."""
    quad8 = etype == "CPS8"

    def nid(i2, j2):
        return 1 + i2 + j2 * (2 * nt + 1)
    used, elems = set(), []
    for i in range(nt):
        for j in range(nr):
            I, J = 2 * i, 2 * j
            # corners counter-clockwise: outward first, then along theta
            a, b, c, d = (I, J), (I, J + 2), (I + 2, J + 2), (I + 2, J)
            if quad8:
                el = (a, b, c, d, (I, J + 1), (I + 1, J + 2), (I + 2, J + 1), (I + 1, J))
            else:
                el = (a, b, c, d)
            used.update(el)
            elems.append((len(elems) + 1, tuple(nid(*p) for p in el)))
    nodes = {nid(*p): point(p[0] / (2 * nt), p[1] / (2 * nr)) for p in used}
    return nodes, elems, nid


def outer_loads(nodes, nt, nr, nid, quad):
    """Consistent nodal loads of the outward normal traction P t on the outer edge."""
    loads = {}
    gauss = [(-math.sqrt(0.6), 5 / 9), (0.0, 8 / 9), (math.sqrt(0.6), 5 / 9)]
    J = 2 * nr
    for i in range(nt):
        ids = [nid(2 * i, J), nid(2 * i + 1, J), nid(2 * i + 2, J)] if quad else [nid(2 * i, J), nid(2 * i + 2, J)]
        xs = [nodes[n] for n in ids]
        for s, w in gauss:
            if quad:
                nf = [s * (s - 1) / 2, 1 - s * s, s * (s + 1) / 2]
                dn = [s - 0.5, -2 * s, s + 0.5]
            else:
                nf = [(1 - s) / 2, (1 + s) / 2]
                dn = [-0.5, 0.5]
            dx = sum(d * x[0] for d, x in zip(dn, xs))
            dy = sum(d * x[1] for d, x in zip(dn, xs))
            # theta increases along the edge: the body is on the left, outward normal ds = (dy, -dx)
            for n, v in zip(ids, nf):
                fx, fy = loads.get(n, (0.0, 0.0))
                loads[n] = (fx + P * T * w * v * dy, fy - P * T * w * v * dx)
    return loads


def deck(nt, nr, etype):
    nodes, elems, nid = mesh(nt, nr, etype)
    loads = outer_loads(nodes, nt, nr, nid, etype == "CPS8")
    out = ["*HEADING", f"NAFEMS LE1 elliptic membrane, {etype}, {nt} x {nr} elements (bench/nafems_le1.py)",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", f" {fmt(E)}, {fmt(NU)}", "*NODE"]
    out += [f" {n}, {fmt(x)}, {fmt(y)}" for n, (x, y) in sorted(nodes.items())]
    out.append(f"*ELEMENT, TYPE={etype}, ELSET=PLATE")
    out += [" " + ", ".join(str(v) for v in (e,) + ids) for e, ids in elems]
    out += ["*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL", f" {fmt(T)}", "*BOUNDARY"]
    for n, (x, y) in sorted(nodes.items()):
        i2 = (n - 1) % (2 * nt + 1)
        if i2 == 0:
            out.append(f" {n}, 2, 2")          # on y = 0
        if i2 == 2 * nt:
            out.append(f" {n}, 1, 1")          # on x = 0
    out += ["*STEP, NAME=PRESSURE", "*CLOAD"]
    for n, (fx, fy) in sorted(loads.items()):
        if abs(fx) > 0:
            out.append(f" {n}, 1, {fmt(fx)}")
        if abs(fy) > 0:
            out.append(f" {n}, 2, {fmt(fy)}")
    out.append("*END STEP")
    return "\n".join(out) + "\n", nodes, elems


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--write-decks")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    print("| element | mesh | sigma_yy at the centroid of the element at D (MPa) | distance from D of the corners' mean (m) |"
          " ratio to 92.7 |")
    print("|---|---|---|---|---|")
    for etype in ("CPS4", "CPS8"):
        for nt, nr in ((3, 2), (6, 4), (12, 8), (24, 16)):
            text, nodes, elems = deck(nt, nr, etype)
            name = f"le1_{etype.lower()}_{nt}x{nr}"
            if a.write_decks and (nt, nr) in ((3, 2), (6, 4)):
                os.makedirs(a.write_decks, exist_ok=True)
                with open(os.path.join(a.write_decks, name + ".deck"), "w") as f:
                    f.write(text)
            path = os.path.join(a.work, name + ".deck")
            with open(path, "w") as f:
                f.write(text)
            out = os.path.join(a.work, name + "_csv")
            r = subprocess.run([os.path.abspath(a.exe), "-q", "--csv", out, "-o", os.path.join(a.work, name + ".lst"),
                                path], capture_output=True, text=True)
            if r.returncode != 0:
                print(f"FAIL {name}: {r.stderr.strip()[:300]}")
                return 1
            res = {}
            with open(os.path.join(out, "plate_results.csv")) as f:
                for row in csv.DictReader(f):
                    res[int(row["element"])] = (float(row["nx"]), float(row["ny"]), float(row["nxy"]))
            e_d, ids = elems[0]                  # the element at theta = 0 next to the hole holds D
            (x1, y1), (x2, y2) = nodes[ids[0]], nodes[ids[1]]
            ang = math.atan2(y2 - y1, x2 - x1)
            s, c = math.sin(ang), math.cos(ang)
            nx, ny, nxy = res[e_d]
            syy = (nx * s * s + ny * c * c + 2 * nxy * s * c) / T
            corners = [nodes[n] for n in ids[:4]]
            cx = sum(p[0] for p in corners) / 4
            cy = sum(p[1] for p in corners) / 4
            print(f"| {etype} | {nt} x {nr} | {syy:.2f} | {math.hypot(cx - 2.0, cy):.3f} | {syy / TARGET:.3f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
