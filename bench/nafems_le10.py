#!/usr/bin/env python3
"""NAFEMS LE10 (thick elliptic plate, 1 MPa on the upper face): sigma_yy at
D = (2, 0, 0.3) against -5.38 MPa, and the wall time, superjoin and CalculiX
side by side on the same decks.

usage: bench/nafems_le10.py [--exe BIN] [--work DIR] [--repeat R] [--out CSV] [--quick]

Decks: tests/solids/le10_deck.py (the problem, its supports and their source
there). Hexahedra C3D20R, C3D20, C3D8I, C3D8 on structured n_theta x n_r x n_z
meshes, tetrahedra C3D10 and C3D4 from gmsh at characteristic length h. Each
deck is run as `superjoin -i job` and `ccx -i job` in directories of their
own, OMP_NUM_THREADS=1 for both (the machine has 2 cores); the time is the
wall clock of the whole run (reading, solving, writing .dat and .frd), best
of R. sigma_yy is the nodal value of the .frd's STRESS block at D (extrapolated
from the integration points and averaged over the elements at D, both
programs). The error is (sigma - (-5.38)) / 5.38. --quick: the two coarser
meshes of each type only.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "solids"))
import le10_deck as le10  # noqa: E402

MESHES = [("C3D20R", [(4, 2, 1), (8, 4, 2), (16, 8, 4), (32, 16, 8)]),
          ("C3D20", [(4, 2, 1), (8, 4, 2), (16, 8, 4), (32, 16, 8)]),
          ("C3D8I", [(8, 4, 2), (16, 8, 4), (32, 16, 8), (64, 32, 16)]),
          ("C3D8", [(8, 4, 2), (16, 8, 4), (32, 16, 8), (64, 32, 16)]),
          ("C3D10", [0.4, 0.2, 0.1]),
          ("C3D4", [0.2, 0.1, 0.07])]


def label(size):
    return "x".join(str(v) for v in size) if isinstance(size, tuple) else f"h={size}"


def run(cmd, work, repeat):
    """Best wall time of `cmd -i job` in work, and whether it succeeded."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    best = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        r = subprocess.run([cmd, "-i", "job"], cwd=work, capture_output=True, text=True, env=env)
        t = time.perf_counter() - t0
        if r.returncode != 0 or not os.path.exists(os.path.join(work, "job.frd")):
            print(f"FAIL {cmd} in {work}: {r.stderr.strip()[-300:]}", file=sys.stderr)
            return None
        best = t if best is None else min(best, t)
    return best


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--work", default="/tmp/nafems_le10")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", "nafems_le10.csv"))
    ap.add_argument("--quick", action="store_true")
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    rows = []
    print("| element | mesh | elements | DOFs | superjoin sigma_yy (MPa) | ccx sigma_yy (MPa) | error | "
          "superjoin (s) | ccx (s) | ccx / superjoin |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for etype, sizes in MESHES:
        for size in sizes[:2] if a.quick else sizes:
            work = os.path.join(a.work, f"{etype}_{label(size)}")
            shutil.rmtree(work, ignore_errors=True)
            nodes, elems = le10.mesh(etype, size, work)
            text, d = le10.deck(nodes, elems, etype)
            got = {}
            for who, cmd in (("superjoin", exe), ("ccx", "ccx")):
                w = os.path.join(work, who)
                os.makedirs(w, exist_ok=True)
                with open(os.path.join(w, "job.inp"), "w") as f:
                    f.write(text)
                t = run(cmd, w, a.repeat)
                got[who] = (le10.frd_stress(os.path.join(w, "job.frd"), d)[1], t) if t is not None else (None, None)
            (s_sj, t_sj), (s_cx, t_cx) = got["superjoin"], got["ccx"]
            err = (s_sj - le10.TARGET) / abs(le10.TARGET) if s_sj is not None else None
            row = dict(element=etype, mesh=label(size), elements=len(elems), dofs=3 * len(nodes),
                       sigma_superjoin=s_sj, sigma_ccx=s_cx, error=err, time_superjoin=t_sj, time_ccx=t_cx)
            rows.append(row)
            ratio = f"{t_cx / t_sj:.2f}" if t_sj and t_cx else "-"
            print(f"| {etype} | {label(size)} | {len(elems)} | {3 * len(nodes)} | "
                  f"{s_sj if s_sj is not None else '-'} | {s_cx if s_cx is not None else '-'} | "
                  f"{100 * err:+.2f} % | {t_sj:.2f} | {t_cx:.2f} | {ratio} |" if err is not None else
                  f"| {etype} | {label(size)} | FAILED |", flush=True)
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0 if all(r["sigma_superjoin"] is not None for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
