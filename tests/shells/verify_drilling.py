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
BANDS (the values of doc/verification.md, to 1e-3): S4/S4R with the drilling
membrane on flat regions (DRILLING_MEMBRANE_TYPES in src/elements/shell.f90,
edge masks of src/elements/drill_mask.f90), S3/S3R with Felippa's OPT triangle
there (src/elements/opt_triangle.f90) and the CST elsewhere. ctest shells.drilling runs it with --check.
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


# The normalised values measured with S4/S4R's drilling membrane and S3/S3R's CST
# (doc/verification.md, "Drilling membranes"), for --check.
BANDS = {
    ("S4", "straight cantilever IN regular"): 0.9929,
    ("S3", "straight cantilever IN regular"): 1.0516,
    ("S4R", "straight cantilever IN regular"): 0.9929,
    ("S3R", "straight cantilever IN regular"): 1.0516,
    ("S4", "straight cantilever IN trapezoid"): 0.8814,
    ("S3", "straight cantilever IN trapezoid"): 0.5122,
    ("S4R", "straight cantilever IN trapezoid"): 0.8814,
    ("S3R", "straight cantilever IN trapezoid"): 0.5122,
    ("S4", "straight cantilever IN parallelogram"): 0.9512,
    ("S3", "straight cantilever IN parallelogram"): 0.5302,
    ("S4R", "straight cantilever IN parallelogram"): 0.9512,
    ("S3R", "straight cantilever IN parallelogram"): 0.5302,
    ("S4", "straight cantilever OUT regular"): 0.9867,
    ("S3", "straight cantilever OUT regular"): 0.9770,
    ("S4R", "straight cantilever OUT regular"): 0.9801,
    ("S3R", "straight cantilever OUT regular"): 0.9735,
    ("S4", "straight cantilever OUT trapezoid"): 0.9873,
    ("S3", "straight cantilever OUT trapezoid"): 0.9773,
    ("S4R", "straight cantilever OUT trapezoid"): 0.9631,
    ("S3R", "straight cantilever OUT trapezoid"): 0.9604,
    ("S4", "straight cantilever OUT parallelogram"): 0.9874,
    ("S3", "straight cantilever OUT parallelogram"): 0.9724,
    ("S4R", "straight cantilever OUT parallelogram"): 0.9779,
    ("S3R", "straight cantilever OUT parallelogram"): 0.9537,
    ("S4", "curved beam IN"): 1.0008,
    ("S3", "curved beam IN"): 1.0508,
    ("S4R", "curved beam IN"): 1.0008,
    ("S3R", "curved beam IN"): 1.0508,
    ("S4", "curved beam OUT"): 0.9135,
    ("S3", "curved beam OUT"): 0.8912,
    ("S4R", "curved beam OUT"): 0.9554,
    ("S3R", "curved beam OUT"): 0.8878,
    ("S4", "twisted beam IN 12x2"): 1.0016,
    ("S3", "twisted beam IN 12x2"): 0.9805,
    ("S4R", "twisted beam IN 12x2"): 1.0000,
    ("S3R", "twisted beam IN 12x2"): 0.9874,
    ("S4", "twisted beam OUT 12x2"): 1.0116,
    ("S3", "twisted beam OUT 12x2"): 0.8325,
    ("S4R", "twisted beam OUT 12x2"): 1.0040,
    ("S3R", "twisted beam OUT 12x2"): 0.8420,
    ("S4", "Scordelis-Lo 4x4"): 1.0333,
    ("S3", "Scordelis-Lo 4x4"): 0.6985,
    ("S4R", "Scordelis-Lo 4x4"): 1.0305,
    ("S3R", "Scordelis-Lo 4x4"): 0.6995,
    ("S4", "Scordelis-Lo 8x8"): 1.0011,
    ("S3", "Scordelis-Lo 8x8"): 0.8522,
    ("S4R", "Scordelis-Lo 8x8"): 1.0010,
    ("S3R", "Scordelis-Lo 8x8"): 0.8553,
    ("S4", "Scordelis-Lo 16x16"): 0.9958,
    ("S3", "Scordelis-Lo 16x16"): 0.9516,
    ("S4R", "Scordelis-Lo 16x16"): 0.9969,
    ("S3R", "Scordelis-Lo 16x16"): 0.9549,
    ("S4", "pinched hemisphere 4x4"): 1.0417,
    ("S3", "pinched hemisphere 4x4"): 0.9303,
    ("S4R", "pinched hemisphere 4x4"): 0.9923,
    ("S3R", "pinched hemisphere 4x4"): 0.9142,
    ("S4", "pinched hemisphere 8x8"): 1.0084,
    ("S3", "pinched hemisphere 8x8"): 0.9793,
    ("S4R", "pinched hemisphere 8x8"): 0.9883,
    ("S3R", "pinched hemisphere 8x8"): 0.9857,
    ("S4", "pinched hemisphere 16x16"): 0.9953,
    ("S3", "pinched hemisphere 16x16"): 0.9822,
    ("S4R", "pinched hemisphere 16x16"): 0.9904,
    ("S3R", "pinched hemisphere 16x16"): 0.9879,
}


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
            if a.check and (et, title) not in BANDS:
                failures.append(f"{et} {title}: no expected value")
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
