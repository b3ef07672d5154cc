#!/usr/bin/env python3
"""Time against error of S4 (thin), S4R (MITC4) and S8R (eight-node) shells.

usage: bench/s8r_time_error.py [--max-mesh N] [--repeat R] [--target E] [--out CSV] [--exe BIN]

Problems (decks from tests/shells):
- plate: hard simply supported square plate, a/t = 100, uniform pressure
  (verify_thick.thick_plate); error of the centre deflection against the
  Reissner-Mindlin series for S4R/S8R and against the Kirchhoff (Navier)
  series for S4 (the two differ by 5e-4 at a/t = 100);
- scordelis: Scordelis-Lo roof under its self weight (*DLOAD GRAV: consistent
  loads for every element), error against the MacNeal-Harder reference 0.3024
  (itself rounded: errors level off near 1e-3, that is the reference).
Meshes: node grids 4x4, 8x8, ... up to N (default 128 for the plate, N/2 for
the roof); an S8R mesh on an n x n grid has (n/2)^2 elements and the same nodes
less the element centres. Wall time of the whole run (best of R). Prints a
markdown table and, per problem, the time each element needs to reach the
target error (log-log interpolation between the meshes around it) and its
ratio to S4R's, all from this one run; writes the CSV (default
bench/results/s8r_time_error.csv).
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "shells"))
import shellgen as g  # noqa: E402
import verify_thick as vt  # noqa: E402

ELEMENTS = ("S4", "S4R", "S8R")


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


def time_to(points, target):
    """Time to reach error <= target by log-log interpolation between the first
    mesh below the target and the one before it; None if never reached."""
    for k, (t, e) in enumerate(points):
        if e <= target:
            if k == 0:
                return t
            (t0, e0), (t1, e1) = points[k - 1], (t, e)
            if e0 <= e1 or t0 <= 0 or t1 <= 0:
                return t1
            s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(t0) + s * (math.log(t1) - math.log(t0)))
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-mesh", type=int, default=128)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--target", type=float, default=None,
                    help="error target (default 1e-3 plate, 3e-3 roof)")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "s8r_time_error.csv"))
    a = ap.parse_args()
    rows = []
    kirchhoff = -g.navier_ss_uniform()
    with tempfile.TemporaryDirectory() as work:
        for problem in ("plate", "scordelis"):
            for et in ELEMENTS:
                n = 4
                top = a.max_mesh if problem == "plate" else a.max_mesh // 2
                while n <= top:
                    if problem == "plate":
                        case = vt.thick_plate(n, et, "SS", 100)
                        ref = case.reference if et.endswith("R") else kirchhoff
                    else:
                        case = g.scordelis_lo(n, et, gravity=True)
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
    print(f"wrote {a.out}\n")
    print("| problem | element | node grid | DOFs | time (s) | error |")
    print("|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]}x{r[2]} | {r[3]} | {r[4]:.3f} | {r[5]:.2e} |")
    print("\n| problem | target error | element | time to reach it (s) | / S4R |")
    print("|---|---|---|---|---|")
    for problem in ("plate", "scordelis"):
        target = a.target or (1e-3 if problem == "plate" else 3e-3)
        times = {et: time_to([(r[4], r[5]) for r in rows if r[0] == problem and r[1] == et], target)
                 for et in ELEMENTS}
        for et in ELEMENTS:
            t, base = times[et], times["S4R"]
            if t is None:
                print(f"| {problem} | {target:.0e} | {et} | not reached | - |")
            else:
                ratio = f"{t / base:.2f}" if base else "-"
                print(f"| {problem} | {target:.0e} | {et} | {t:.3f} | {ratio} |")

if __name__ == "__main__":
    main()
