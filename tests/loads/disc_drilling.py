#!/usr/bin/env python3
"""The spinning annular disc of verify_loads.py (*DLOAD CENTRIF, closed form of
Timoshenko & Goodier) solved three ways, to tell an element's error from a
missing boundary condition: (1) the quarter model of verify_loads.py
(symmetry edges fix the normal translation only), (2) the same quarter with
the drilling rotation theta_z also fixed on the symmetry edges (as Abaqus's
XSYMM / YSYMM), (3) the full annulus, theta_z free everywhere, with three
translations against rigid motion that the exact solution satisfies. Prints
max(|u(a)/u_a - 1|, |u(b)/u_b - 1|) on the radial line theta = 0 and the rate of
each halving; no pass/fail (a measurement for doc/verification.md,
"Drilling membranes").

Triangles (S3, CPS3) split every quadrilateral of the S4 / CPS4 mesh along
its diagonal 1-3.

usage: disc_drilling.py SUPERJOIN WORKDIR [ETYPE ...]   (default S4 CPS4)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import verify_loads as V  # noqa: E402

MESHES = [(2, 4), (4, 8), (8, 16), (16, 32)]


QUAD_OF = {"S3": "S4", "CPS3": "CPS4"}


def split_triangles(text, etype):
    """The deck of the quadrilateral type QUAD_OF[etype] with each element
    cut into two triangles of type etype (diagonal 1-3)."""
    out, inside, k = [], False, 0
    for line in text.split("\n"):
        if line.startswith("*"):
            inside = line.startswith("*ELEMENT")
            if inside:
                line = line.replace(f"TYPE={QUAD_OF[etype]}", f"TYPE={etype}")
            out.append(line)
            continue
        if inside and line.strip():
            n = [x.strip() for x in line.split(",")][1:]
            for tri in ([n[0], n[1], n[2]], [n[0], n[2], n[3]]):
                k += 1
                out.append(f"{k}, " + ", ".join(tri))
            continue
        out.append(line)
    return "\n".join(out)


def quarter(etype, nr, nt, fix_theta):
    if etype in QUAD_OF:
        text, na, nb = quarter(QUAD_OF[etype], nr, nt, fix_theta)
        return split_triangles(text, etype), na, nb
    text, na, nb = V.disc_deck(etype, nr, nt)
    if not fix_theta:
        return text, na, nb
    out = []
    for line in text.split("\n"):
        out.append(line)
        p = [s.strip() for s in line.split(",")]
        if len(p) == 3 and p[1:] in (["1", "1"], ["2", "2"]):
            out.append(f"{p[0]}, 6, 6")
    return "\n".join(out), na, nb


def full(etype, nr, nt):
    """Full annulus with 4 nt elements around (the quarter's element shapes)."""
    if etype in QUAD_OF:
        text, na, nb = full(QUAD_OF[etype], nr, nt)
        return split_triangles(text, etype), na, nb
    nt = 4 * nt
    shell = etype.startswith("S")
    ids = {}
    lines = ["*HEADING", f"full disc {etype} {nr}x{nt}", "*MATERIAL, NAME=STEEL", "*ELASTIC",
             f"{V.E}, {V.NU}", "*DENSITY", f"{V.RHO}", "*NODE"]
    for i in range(nr + 1):
        for j in range(nt):
            r = V.A + (V.B - V.A) * i / nr
            th = 2 * math.pi * j / nt
            ids[(i, j)] = len(ids) + 1
            lines.append(f"{ids[(i, j)]}, {r * math.cos(th)!r}, {r * math.sin(th)!r}" + (", 0.0" if shell else ""))
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=DISC")
    k = 0
    for i in range(nr):
        for j in range(nt):
            k += 1
            j1 = (j + 1) % nt
            lines.append(f"{k}, {ids[(i, j)]}, {ids[(i + 1, j)]}, {ids[(i + 1, j1)]}, {ids[(i, j1)]}")
    sec = "*SHELL SECTION" if shell else "*SOLID SECTION"
    lines += [f"{sec}, ELSET=DISC, MATERIAL=STEEL", f"{V.T}", "*BOUNDARY",
              f"{ids[(0, 0)]}, 2, 2", f"{ids[(0, nt // 2)]}, 2, 2", f"{ids[(0, nt // 4)]}, 1, 1"]
    if shell:
        lines += [f"{n}, 3, 5" for n in range(1, len(ids) + 1)]
    lines += ["*STEP, NAME=SPIN", "*STATIC", "*DLOAD",
              f"DISC, CENTRIF, {V.W2}, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0", "*END STEP"]
    return "\n".join(lines) + "\n", ids[(0, 0)], ids[(nr, 0)]


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    exe, work = argv[1], argv[2]
    for etype in argv[3:] or ["S4", "CPS4"]:
        print(f"\n| {etype} mesh | quarter | rate | quarter, theta_z = 0 on symmetry | rate | full annulus | rate |")
        print("|---|---|---|---|---|---|---|")
        prev = None
        for nr, nt in MESHES:
            errs = []
            for name, (text, na, nb) in [("q", quarter(etype, nr, nt, False)), ("qs", quarter(etype, nr, nt, True)),
                                         ("f", full(etype, nr, nt))]:
                d = V.solve(exe, work, f"dd_{etype}_{name}_{nr}", text)
                errs.append(max(abs(float(d[na]["u1"]) / V.disc_closed(V.A) - 1),
                                abs(float(d[nb]["u1"]) / V.disc_closed(V.B) - 1)))
            cells = []
            for k, e in enumerate(errs):
                cells += [f"{e:.3e}", f"{math.log2(prev[k] / e):.2f}" if prev else ""]
            print(f"| {nr} x {nt} | " + " | ".join(cells) + " |")
            prev = errs
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
