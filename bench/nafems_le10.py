#!/usr/bin/env python3
"""NAFEMS LE10 (thick elliptic plate, 1 MPa on the upper face): sigma_yy at
D = (2, 0, 0.3) against -5.38 MPa, and the wall time, superjoin and CalculiX
side by side on the same decks.

usage: bench/nafems_le10.py [--exe BIN] [--work DIR] [--repeat R] [--out CSV] [--quick | --full]

Decks: tests/solids/le10_deck.py (the problem, its supports and their source
there). Hexahedra C3D20R, C3D20, C3D8I, C3D8 on structured n_theta x n_r x n_z
meshes, tetrahedra C3D10 and C3D4 from gmsh at characteristic length h. Each
deck is run as `superjoin -i job` and `ccx -i job` in directories of their
own, OMP_NUM_THREADS=1 for both (the machine has 2 cores); the time is the
wall clock of the whole run (reading, solving, writing .dat and .frd), best
of R, and its CPU time (user + system of the child: both run one thread, so
on an idle machine the two agree; on a loaded one the CPU time is the fairer
figure). sigma_yy is the nodal value of the .frd's STRESS block at D (extrapolated
from the integration points and averaged over the elements at D, both
programs). The error is (sigma - (-5.38)) / 5.38. --quick: the two coarser
meshes of each type only; --full: one finer mesh of each type (about 60k
DOFs for the quadratic types, 110k for the linear hexahedra; a few minutes
on an idle machine).
"""
import argparse
import csv
import os
import resource
import shutil
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tests", "solids"))
import le10_deck as le10  # noqa: E402

# (element, meshes run by default, meshes added by --full)
MESHES = [("C3D20R", [(4, 2, 1), (8, 4, 2), (16, 8, 4)], [(32, 16, 8)]),
          ("C3D20", [(4, 2, 1), (8, 4, 2), (16, 8, 4)], [(32, 16, 8)]),
          ("C3D8I", [(8, 4, 2), (16, 8, 4), (32, 16, 8)], [(64, 32, 16)]),
          ("C3D8", [(8, 4, 2), (16, 8, 4), (32, 16, 8)], [(64, 32, 16)]),
          ("C3D10", [0.4, 0.2], [0.1]),
          ("C3D4", [0.2, 0.1], [0.07])]


def label(size):
    return "x".join(str(v) for v in size) if isinstance(size, tuple) else f"h={size}"


def run(cmd, work, repeat):
    """Best (wall, CPU) seconds of `cmd -i job` in work; None if it failed."""
    env = dict(os.environ, OMP_NUM_THREADS="1")
    best = None
    for _ in range(repeat):
        c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        r = subprocess.run([cmd, "-i", "job"], cwd=work, capture_output=True, text=True, env=env)
        t = time.perf_counter() - t0
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
        if r.returncode != 0 or not os.path.exists(os.path.join(work, "job.frd")):
            print(f"FAIL {cmd} in {work}: {r.stderr.strip()[-300:]}", file=sys.stderr)
            return None
        best = (t, cpu) if best is None else (min(best[0], t), min(best[1], cpu))
    return best


def both(text, node, column, work, exe, repeat, target):
    """Run the deck with superjoin and ccx in work/superjoin, work/ccx: the row's
    fields (the .frd's STRESS column at node from each, the error of
    superjoin's against target, wall and CPU seconds)."""
    got = {}
    for who, cmd in (("superjoin", exe), ("ccx", "ccx")):
        w = os.path.join(work, who)
        os.makedirs(w, exist_ok=True)
        with open(os.path.join(w, "job.inp"), "w") as f:
            f.write(text)
        t = run(cmd, w, repeat)
        got[who] = (le10.frd_stress(os.path.join(w, "job.frd"), node)[column], t) if t else (None, (None, None))
    (s_sj, t_sj), (s_cx, t_cx) = got["superjoin"], got["ccx"]
    return dict(sigma_superjoin=s_sj, sigma_ccx=s_cx,
                error=(s_sj - target) / abs(target) if s_sj is not None else None,
                wall_superjoin=t_sj[0], cpu_superjoin=t_sj[1], wall_ccx=t_cx[0], cpu_ccx=t_cx[1])


def table_row(head, r):
    """A markdown row: head cells, the two sigmas, the error, wall / CPU of each, the CPU ratio."""
    if r["sigma_superjoin"] is None or r["sigma_ccx"] is None:
        return "| " + " | ".join(str(v) for v in head) + " | FAILED |"
    return ("| " + " | ".join(str(v) for v in head) + f" | {r['sigma_superjoin']} | {r['sigma_ccx']} | "
            f"{100 * r['error']:+.2f} % | {r['wall_superjoin']:.2f} / {r['cpu_superjoin']:.2f} | "
            f"{r['wall_ccx']:.2f} / {r['cpu_ccx']:.2f} | {r['cpu_ccx'] / max(r['cpu_superjoin'], 1e-3):.2f} |")


def write_csv(rows, out):
    """The rows to out; exit status 1 if a run failed."""
    os.makedirs(os.path.dirname(out), exist_ok=True)
    with open(out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    return 0 if all(r["sigma_superjoin"] is not None and r["sigma_ccx"] is not None for r in rows) else 1


def arguments(name):
    """The options both benches take: --exe, --work, --repeat, --out."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--work", default="/tmp/" + name)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "bench", "results", name + ".csv"))
    return ap


def main():
    ap = arguments("nafems_le10")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--full", action="store_true")
    a = ap.parse_args()
    exe = os.path.abspath(a.exe)
    rows = []
    print("| element | mesh | elements | DOFs | superjoin sigma_yy (MPa) | ccx sigma_yy (MPa) | error | "
          "superjoin wall / CPU (s) | ccx wall / CPU (s) | CPU ccx / superjoin |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for etype, sizes, more in MESHES:
        for size in sizes[:2] if a.quick else sizes + more if a.full else sizes:
            work = os.path.join(a.work, f"{etype}_{label(size)}")
            shutil.rmtree(work, ignore_errors=True)
            nodes, elems = le10.mesh(etype, size, work)
            text, d = le10.deck(nodes, elems, etype)
            r = both(text, d, 1, work, exe, a.repeat, le10.TARGET)
            rows.append(dict(element=etype, mesh=label(size), elements=len(elems), dofs=3 * len(nodes), **r))
            print(table_row([etype, label(size), len(elems), 3 * len(nodes)], r), flush=True)
    return write_csv(rows, a.out)


if __name__ == "__main__":
    sys.exit(main())
