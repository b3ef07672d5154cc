#!/usr/bin/env python3
"""Time against error of the thin (S4, S3) and thick (S4R, S3R) shells.

usage: bench/thick_time_error.py [--max-mesh N] [--repeat R] [--out CSV] [--exe BIN]

Problems (decks from tests/shells):
- plate: hard simply supported square plate, a/t = 100, uniform pressure
  (verify_thick.thick_plate); error of the centre deflection against the
  Reissner-Mindlin series for S4R/S3R and against the Kirchhoff (Navier)
  series for S4/S3 (the two differ by 5e-4 at a/t = 100);
- scordelis: Scordelis-Lo roof (shellgen.scordelis_lo), error against the
  MacNeal-Harder reference 0.3024 (itself rounded: the errors level off near
  1e-3, that is the reference, not the element).
Meshes 4x4, 8x8, ... up to N (default 128 for the plate, N/2 for the roof);
wall time of the whole run (best of R), written to a CSV (default
bench/results/thick_time_error.csv).
"""
import argparse
import csv
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "shells"))
import shellgen as g  # noqa: E402
import verify_thick as vt  # noqa: E402


def run(exe, case, work, repeat):
    deck = os.path.join(work, "p.deck")
    with open(deck, "w") as f:
        f.write(case.deck)
    out = os.path.join(work, "csv")
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, "p.lst"), deck],
                           capture_output=True, text=True)
        dt = time.perf_counter() - t0
        if r.returncode != 0:
            sys.exit(f"superjoin failed on {case.name}: {r.stderr}")
        best = dt if best is None else min(best, dt)
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            if row["substructure"] == case.sub and int(row["node"]) == case.node:
                return best, float(row[("u1", "u2", "u3")[case.dof - 1]])
    sys.exit(f"{case.name}: result node not found")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-mesh", type=int, default=128)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "thick_time_error.csv"))
    a = ap.parse_args()
    rows = []
    kirchhoff = -g.navier_ss_uniform()
    with tempfile.TemporaryDirectory() as work:
        for problem in ("plate", "scordelis"):
            for et in ("S4", "S4R", "S3", "S3R"):
                n = 4
                top = a.max_mesh if problem == "plate" else a.max_mesh // 2
                while n <= top:
                    if problem == "plate":
                        case = vt.thick_plate(n, et, "SS", 100)
                        ref = case.reference if et.endswith("R") else kirchhoff
                    else:
                        case = g.scordelis_lo(n, et)
                        ref = case.reference
                    dt, v = run(a.exe, case, work, a.repeat)
                    err = abs(v / ref - 1.0)
                    rows.append((problem, et, n, case.ndof, dt, err))
                    print(f"{problem:9s} {et:4s} {n:4d}x{n:<4d} DOFs {case.ndof:8d}  time {dt:8.3f} s  "
                          f"error {err:.3e}", flush=True)
                    n *= 2
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w") as f:
        f.write("problem,element,mesh,dofs,seconds,error\n")
        for r in rows:
            f.write(f"{r[0]},{r[1]},{r[2]},{r[3]},{r[4]:.4f},{r[5]:.6e}\n")
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
