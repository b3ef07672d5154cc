#!/usr/bin/env python3
"""Time versus error on the simply supported square plate (uniform pressure).

usage: bench/plate_time_error.py [--max-mesh N] [--repeat R] [--out CSV] [--png PNG]

For S4 and S3 meshes 2x2 ... NxN (default N = 256, about 400 000 DOFs) it
solves tests/shells' generated deck with superjoin, records the wall time
(best of R runs) and the error of the centre deflection against the Navier
series, writes a CSV and, if gnuplot is installed, a PNG with error against
time and error against DOFs. Paths default to bench/results/ and doc/img/.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "shells"))
import shellgen as g  # noqa: E402


def run(exe, deck, work, repeat):
    best = None
    out = os.path.join(work, "csv")
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, "p.lst"), deck],
                           capture_output=True, text=True)
        dt = time.perf_counter() - t0
        if r.returncode != 0:
            sys.exit(f"superjoin failed on {deck}: {r.stderr}")
        best = dt if best is None else min(best, dt)
    return best, out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--max-mesh", type=int, default=256)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "plate_time_error.csv"))
    ap.add_argument("--png", default=os.path.join(ROOT, "doc", "img", "plate_time_error.png"))
    a = ap.parse_args()
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for et in ("S4", "S3"):
            n = 2
            while n <= a.max_mesh:
                case = g.square_plate(n, et, "SS", "UNIFORM")
                deck = os.path.join(work, "p.deck")
                with open(deck, "w") as f:
                    f.write(case.deck)
                dt, out = run(a.exe, deck, work, a.repeat)
                w = None
                with open(os.path.join(out, "displacements.csv")) as f:
                    for row in csv.DictReader(f):
                        if row["substructure"] == case.sub and int(row["node"]) == case.node:
                            w = float(row["u3"])
                err = abs(w / case.reference - 1.0)
                rows.append((et, n, case.ndof, dt, err))
                print(f"{et} {n:4d}x{n:<4d} DOFs {case.ndof:8d}  time {dt:8.3f} s  error {err:.3e}", flush=True)
                n *= 2
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w") as f:
        f.write("element,mesh,dofs,seconds,error\n")
        for r in rows:
            f.write(f"{r[0]},{r[1]},{r[2]},{r[3]:.4f},{r[4]:.6e}\n")
    print(f"wrote {a.out}")
    if not shutil.which("gnuplot"):
        print("gnuplot not found: no plot (apt-get install gnuplot-nox)")
        return
    os.makedirs(os.path.dirname(a.png), exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        for et in ("S4", "S3"):
            with open(os.path.join(work, et + ".dat"), "w") as f:
                for r in rows:
                    if r[0] == et:
                        f.write(f"{r[2]} {r[3]} {r[4]}\n")
        script = f"""
set terminal pngcairo size 1100,450 font ",10"
set output '{a.png}'
set multiplot layout 1,2 title 'Simply supported square plate, uniform pressure: centre deflection against the Navier series'
set logscale xy
set grid
set format y '10^{{%L}}'
set xlabel 'wall time per run (s)'
set ylabel 'relative error'
plot '{work}/S4.dat' u 2:3 w lp pt 7 t 'S4 (DKQ)', '{work}/S3.dat' u 2:3 w lp pt 5 t 'S3 (DKT)'
set xlabel 'DOFs'
set format x '10^{{%L}}'
plot '{work}/S4.dat' u 1:3 w lp pt 7 t 'S4 (DKQ)', '{work}/S3.dat' u 1:3 w lp pt 5 t 'S3 (DKT)', \\
     '{work}/S4.dat' u 1:(3*$1**-1) w l dt 2 lc rgb 'gray' t 'slope -1 (h^2)'
unset multiplot
"""
        subprocess.run(["gnuplot"], input=script, text=True, check=True)
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
