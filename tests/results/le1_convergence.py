#!/usr/bin/env python3
"""NAFEMS LE1 (elliptic membrane) with CPS4: sigma_yy at D from the averaged
nodal stresses (*NODE PRINT S), on refined meshes, with the observed rate.

usage: le1_convergence.py SUPERJOIN WORKDIR [--check] [--fine]

Quarter of the membrane, t = 0.1, E = 210e3 MPa, nu = 0.3: inner edge
x^2/2^2 + y^2/1^2 = 1, outer edge x^2/3.25^2 + y^2/2.75^2 = 1 under a uniform
outward pressure of 10 MPa; symmetry u = 0 on x = 0 and v = 0 on y = 0. The
target is sigma_yy = 92.7 MPa at D = (2, 0). The mesh maps the parametric
angle theta (0..pi/2, 2m elements) and the position between the two ellipses
(m elements) bilinearly; the outer pressure enters as the consistent nodal
loads of the straight element edges. --fine adds 128 x 64, 256 x 128 and 512 x 256. With
--check the script fails unless the error falls on the four coarsest meshes
(pre-asymptotic: it overshoots on 64 x 32 and then returns from above, see
doc/verification.md), 16 x 8 is within 4% and every finer mesh within 0.6%
of 92.7.
"""
import csv
import math
import os
import subprocess
import sys

TARGET = 92.7
LEVELS = [2, 4, 8, 16, 32]
FINE = [64, 128, 256]


def deck_text(m):
    nt, nr = 2 * m, m
    lines = ["*HEADING", f"NAFEMS LE1, CPS4 {nt} x {nr}", "*NODE"]
    nid = {}
    xy = {}
    k = 0
    for j in range(nr + 1):
        r = j / nr
        for i in range(nt + 1):
            th = 0.5 * math.pi * i / nt
            c, s = (0.0, 1.0) if i == nt else (math.cos(th), math.sin(th))
            x = (1 - r) * 2.0 * c + r * 3.25 * c
            y = (1 - r) * 1.0 * s + r * 2.75 * s
            k += 1
            nid[i, j] = k
            xy[k] = (x, y)
            lines.append(f"{k}, {x:.17g}, {y:.17g}")
    lines.append("*ELEMENT, TYPE=CPS4, ELSET=ALL")
    e = 0
    for j in range(nr):
        for i in range(nt):
            e += 1
            lines.append(f"{e}, {nid[i, j]}, {nid[i + 1, j]}, {nid[i + 1, j + 1]}, {nid[i, j + 1]}")
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", "210000.0, 0.3",
              "*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL", "0.1", "*BOUNDARY"]
    for j in range(nr + 1):
        lines.append(f"{nid[0, j]}, 2, 2")
        lines.append(f"{nid[nt, j]}, 1, 1")
    force = {}
    for i in range(nt):
        a, b = nid[i, nr], nid[i + 1, nr]
        (xa, ya), (xb, yb) = xy[a], xy[b]
        # outward normal of the edge a -> b (counter-clockwise about the origin): (dy, -dx)
        fx, fy = 10.0 * 0.1 * (yb - ya), -10.0 * 0.1 * (xb - xa)
        for n in (a, b):
            force.setdefault(n, [0.0, 0.0])
            force[n][0] += fx / 2
            force[n][1] += fy / 2
    lines.append("*STEP")
    lines.append("*CLOAD")
    for n in sorted(force):
        lines.append(f"{n}, 1, {force[n][0]:.17g}")
        lines.append(f"{n}, 2, {force[n][1]:.17g}")
    lines += ["*NODE PRINT, NSET=D", "S", "*END STEP"]
    lines.insert(lines.index("*MATERIAL, NAME=STEEL"), f"*NSET, NSET=D\n{nid[0, 0]}")
    return "\n".join(lines) + "\n"


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1], argv[2]
    check = "--check" in argv[3:]
    os.makedirs(work, exist_ok=True)
    rows = []
    for m in LEVELS + (FINE if "--fine" in argv[3:] else []):
        name = os.path.join(work, f"le1_{m}")
        with open(name + ".deck", "w") as f:
            f.write(deck_text(m))
        r = subprocess.run([exe, "-q", name + ".deck", "-o", name + ".lst", "--csv", name + ".csv"],
                           stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            print(f"FAIL: superjoin exited with {r.returncode} on {name}.deck\n{r.stderr}")
            return 1
        with open(os.path.join(name + ".csv", "nodal_stresses.csv")) as f:
            d = [row for row in csv.DictReader(f) if row["node"] == "1"]
        rows.append((m, float(d[0]["syy"])))
    # error: against 92.7; order: from the changes between successive meshes,
    # log2(|s(h) - s(2h)| / |s(h/2) - s(h)|), which does not need the target.
    print(f"{'mesh':>9} {'sigma_yy(D)':>14} {'error':>9} {'change':>10} {'order':>6}")
    prev = None
    for k, (m, s) in enumerate(rows):
        err = abs(s - TARGET) / TARGET
        change = order = ""
        if k > 0:
            change = f"{s - rows[k - 1][1]:10.4f}"
        if k > 1:
            order = f"{math.log(abs(rows[k - 1][1] - rows[k - 2][1]) / abs(s - rows[k - 1][1]), 2):.2f}"
        print(f"{2 * m:>4} x {m:<3} {s:14.4f} {err:9.2e} {change:>10} {order:>6}")
    if check:
        errs = [abs(s - TARGET) / TARGET for _, s in rows]
        if not all(errs[k + 1] < errs[k] for k in range(3)):
            print(f"FAIL: the error does not fall on the four coarsest meshes: {errs[:4]}")
            return 1
        if errs[2] > 0.04 or max(errs[3:]) > 0.006:
            print(f"FAIL: sigma_yy(D) too far from {TARGET}: relative errors {errs}")
            return 1
        print("ok: LE1 sigma_yy(D) converges to 92.7")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
