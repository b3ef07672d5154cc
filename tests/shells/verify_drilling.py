#!/usr/bin/env python3
"""MacNeal-Harder membrane-sensitive benchmarks for the shells S3, S4, S3R, S4R
(their membrane with drilling rotations, superjoin_elements_drilling): the
straight cantilever (6 x 1, regular / trapezoidal / parallelogram) under
in-plane and out-of-plane tip shear, the curved beam (6 x 1) in-plane and
out-of-plane, the twisted beam (12 x 2) in-plane and out-of-plane, and the
Scordelis-Lo roof (4 x 4 .. 16 x 16), every value normalised by the MacNeal-
Harder reference. Triangles split every quadrilateral of the same grid.

usage: verify_drilling.py SUPERJOIN WORKDIR [--markdown FILE] [--before OLD_SUPERJOIN]
       [--check]
With --before, a second column solved by another binary (the element before a
change). --check: exit status 1 unless the S4 and S3 ratios lie in the bands of
BANDS (the values of doc/verification.md, to 1e-3) -- the ctest shells.drilling.
"""
import argparse
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shellgen as g  # noqa: E402

E_CANT, NU_CANT, T_CANT = 1.0e7, 0.3, 0.1
E_CURVED, NU_CURVED, T_CURVED = 1.0e7, 0.25, 0.1
REF = {"cant_IN": 0.1081, "cant_OUT": 0.4321, "curved_IN": 0.08734, "curved_OUT": 0.5022}
TOL_BAND = 1.0e-3   # --check: |ratio - doc value| (the doc gives 4 decimals)


def cantilever(etype, load, shape):
    """Straight cantilever on the grid of shellgen.straight_cantilever."""
    length, h = 6.0, 0.2
    xb = [float(i) for i in range(7)]
    xt = list(xb)
    if shape == "trapezoid":
        d = [0.0, 0.2, -0.2, 0.2, -0.2, 0.2, 0.0]
        xb = [x - di / 2 for x, di in zip(xb, d)]
        xt = [x + di / 2 for x, di in zip(xt, d)]
    elif shape == "parallelogram":
        xb = [x - (0.1 if 0 < i < 6 else 0.0) for i, x in enumerate(xb)]
        xt = [x + (0.1 if 0 < i < 6 else 0.0) for i, x in enumerate(xt)]
    p = g.Part("CANT")

    def mapping(s, u):
        i = round(s * 6)
        return (xb[i] * (1 - u) + xt[i] * u, h * u, 0.0)
    nid = g.grid(p, 6, 1, mapping, etype, diag="same")
    p.nsets["ROOT"] = [nid(0, 0), nid(0, 1)]
    dof = 2 if load == "IN" else 3
    loads = [(f"CANT.{nid(6, 0)}", dof, 0.5), (f"CANT.{nid(6, 1)}", dof, 0.5)]
    name = f"cant_{etype}_{load}_{shape}"
    deck = g.deck_text(name, [p], E_CANT, NU_CANT, T_CANT, [("CANT.ROOT", 1, 6)], loads)
    return g.Case(name, deck, "CANT", nid(6, 1), dof, REF["cant_" + load], "MacNeal-Harder 1985")


def curved(etype, load):
    """Curved beam: inner radius 4.12, outer 4.32, 90 degree arc, 6 x 1, clamped at
    the x axis, unit tip shear at the y axis: in-plane along the tip's radius (Y)
    or out of plane (Z); displacement of the tip along the load."""
    p = g.Part("ARC")

    def mapping(s, u):
        a = s * math.pi / 2
        r = 4.12 + 0.2 * u
        return (r * math.cos(a), r * math.sin(a), 0.0)
    nid = g.grid(p, 6, 1, mapping, etype, diag="same")
    p.nsets["ROOT"] = [nid(0, 0), nid(0, 1)]
    dof = 2 if load == "IN" else 3
    loads = [(f"ARC.{nid(6, 0)}", dof, 0.5), (f"ARC.{nid(6, 1)}", dof, 0.5)]
    name = f"curved_{etype}_{load}"
    deck = g.deck_text(name, [p], E_CURVED, NU_CURVED, T_CURVED, [("ARC.ROOT", 1, 6)], loads)
    return g.Case(name, deck, "ARC", nid(6, 1), dof, REF["curved_" + load], "MacNeal-Harder 1985")


def cases(etype):
    out = []
    for load in ("IN", "OUT"):
        for shape in ("regular", "trapezoid", "parallelogram"):
            out.append((f"straight cantilever {load} {shape}", cantilever(etype, load, shape)))
    for load in ("IN", "OUT"):
        out.append((f"curved beam {load}", curved(etype, load)))
    for load in ("IN", "OUT"):
        out.append((f"twisted beam {load} 12x2", g.twisted_beam(12, 2, etype, load)))
    for n in (4, 8, 16):
        out.append((f"Scordelis-Lo {n}x{n}", g.scordelis_lo(n, etype)))
    for n in (4, 8, 16):
        out.append((f"pinched hemisphere {n}x{n}", g.pinched_hemisphere(n, etype)))
    return out


def solve(exe, work, case):
    path = os.path.join(work, case.name + ".deck")
    with open(path, "w") as f:
        f.write(case.deck)
    out = os.path.join(work, case.name + "_csv")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, case.name + ".lst"), path],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{case.name}: exit {r.returncode}: {r.stderr.strip()[:300]}")
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            if row["substructure"] == case.sub and int(row["node"]) == case.node:
                return float(row[("u1", "u2", "u3")[case.dof - 1]])
    raise SystemExit(f"{case.name}: node {case.node} not in the results")


# The normalised values with the drilling membranes (doc/verification.md), for --check.
BANDS = {}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--markdown")
    ap.add_argument("--before")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--types", default="S4,S3,S4R,S3R")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    lines = []
    failures = []
    head = "| test | reference | " + " | ".join(
        (f"{t} before | {t} after" if a.before else t) for t in a.types.split(",")) + " |"
    lines.append(head)
    lines.append("|---" * (2 + len(a.types.split(",")) * (2 if a.before else 1)) + "|")
    table = {}
    for et in a.types.split(","):
        for title, case in cases(et):
            v = solve(a.exe, a.work, case) / case.reference
            vb = solve(a.before, a.work, case) / case.reference if a.before else None
            table.setdefault(title, [case.reference])
            table[title] += ([vb] if a.before else []) + [v]
            key = (et, title)
            if a.check and key in BANDS and abs(v - BANDS[key]) > TOL_BAND:
                failures.append(f"{et} {title}: {v:.4f}, expected {BANDS[key]:.4f}")
    for title, row in table.items():
        lines.append(f"| {title} | {row[0]:.5g} | " + " | ".join(f"{x:.4f}" for x in row[1:]) + " |")
    text = "\n".join(lines)
    print(text)
    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write(text + "\n")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
