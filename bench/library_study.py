#!/usr/bin/env python3
"""The condensation library in a design study (issue 26): the second run with
one part changed, against the first.

Two studies, every part a substructure, all condensed (--condense yes):

  --model blocks (default): a row of NB solid blocks (1 m cubes, M x M x M
      C3D8 each) joined at the four corners of their facing faces by contact
      springs on DOFs 1-3, the first block held at its four left corners, the
      last pulled at its right corners. Parts whose condensation costs a
      sparse 3D factorization, with a small boundary (24 DOFs).
  --model panels: a grid of NX x NY plane-stress panels joined along whole
      edges (bench/gen_panel_grid.py): a cheap 2D factorization, a large
      boundary (8 M DOFs), the unfavourable case for the library.

The changed part is the first one (its section's material or thickness).
Runs, in this order, each timed by wall clock around the process (best of
--repeat):

  plain      no library (the reference cost of one run)
  first      --library DIR, empty: every panel condensed and stored
  second     --library DIR, one panel's thickness changed: one condensed, the others loaded
  unchanged  --library DIR, the changed deck again: every panel loaded

The blocks B1..B(NB-1) are translated copies of one part (the last one
differs: it is loaded where the others are joined), which the runs find and
condense once (--twins yes, the default): the first run condenses two parts,
the second at least the changed one, and finds the copies' entry through its
pointer (src/substructure/library.f90). --distinct gives every block its own
material (no twins: the first run condenses every part); --twins no is
passed to every run.

and the ratios second/first and second/plain on one line, for the wall clock
and for the CPU time of the process (user + system: what a loaded machine
distorts least). Listing and CSV
writing are part of every run (kept small: no --csv).

usage: library_study.py [--bin SUPERJOIN] [--model blocks|panels] [--nb 6] [--nx 4] [--ny 3] [--mesh M]
                        [--distinct] [--twins yes|no] [--repeat 3] [--work DIR]
"""
import argparse
import os
import resource
import shutil
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def blocks_deck(nb, m, distinct=False):
    """NB solid blocks of M x M x M C3D8 in a row, joined at face corners
    (distinct: each block of its own Young's modulus, so no two are twins)."""
    n1 = m + 1
    h = 1.0 / m

    def nid(i, j, k):
        return 1 + i + n1 * (j + n1 * k)

    out = ["*HEADING", f"library study: {nb} blocks of {m}^3 C3D8"]
    for b in range(nb):
        e = 2.1e11 + (1e9 * b if distinct else 0.0)
        out += [f"*MATERIAL, NAME=M{b + 1}", "*ELASTIC", f"{e:.4g}, 0.3"]
    left = [nid(0, j, k) for j in (0, m) for k in (0, m)]
    right = [nid(m, j, k) for j in (0, m) for k in (0, m)]
    for b in range(nb):
        out += [f"*SUBSTRUCTURE, NAME=B{b + 1}", "*NODE"]
        for k in range(n1):
            for j in range(n1):
                for i in range(n1):
                    out.append(f"{nid(i, j, k)}, {b + i * h!r}, {j * h!r}, {k * h!r}")
        out.append("*ELEMENT, TYPE=C3D8, ELSET=ALL")
        e = 0
        for k in range(m):
            for j in range(m):
                for i in range(m):
                    e += 1
                    c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k)]
                    c += [nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                    out.append(f"{e}, " + ", ".join(map(str, c)))
        out += ["*NSET, NSET=LEFT", ", ".join(map(str, left)), "*NSET, NSET=RIGHT", ", ".join(map(str, right))]
        out += [f"*SOLID SECTION, ELSET=ALL, MATERIAL=M{b + 1}", "*END SUBSTRUCTURE"]
    for b in range(nb - 1):
        out += [f"*CONTACT, NAME=J{b + 1}, MASTER=B{b + 1}, SLAVE=B{b + 2}", "RIGHT, LEFT, 1, 3, 1e9"]
    out += ["*SUPPORT", "B1.LEFT, 1, 3", "*STEP, NAME=PULL", "*CLOAD", f"B{nb}.RIGHT, 1, 1000",
            f"B{nb}.RIGHT, 3, 200", "*END STEP"]
    return "\n".join(out) + "\n"


def timed(cmd, repeat, before=None):
    """Best of repeat: (wall seconds, CPU seconds of the process: user + system)."""
    best = None
    for _ in range(repeat):
        if before:
            before()
        r0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        t = time.perf_counter()
        p = subprocess.run(cmd, capture_output=True, text=True)
        dt = time.perf_counter() - t
        r1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            sys.exit(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr[:300]}")
        cpu = (r1.ru_utime - r0.ru_utime) + (r1.ru_stime - r0.ru_stime)
        best = (dt, cpu) if best is None else (min(best[0], dt), min(best[1], cpu))
    return best


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--model", choices=("blocks", "panels"), default="blocks")
    ap.add_argument("--nb", type=int, default=6)
    ap.add_argument("--nx", type=int, default=4)
    ap.add_argument("--ny", type=int, default=3)
    ap.add_argument("--mesh", type=int)
    ap.add_argument("--distinct", action="store_true", help="blocks: each of its own material (no twins)")
    ap.add_argument("--twins", choices=("yes", "no"), default="yes")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench_library"))
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    deck = os.path.join(a.work, "study.deck")
    changed = os.path.join(a.work, "changed.deck")
    if a.model == "blocks":
        m = a.mesh or 16
        text = blocks_deck(a.nb, m, a.distinct)
        edited = text.replace("2.1e+11, 0.3", "2.0e+11, 0.3", 1)   # the first block's material
        n, dofs = a.nb, a.nb * 3 * (m + 1) ** 3
    else:
        m = a.mesh or 40
        text = subprocess.run([sys.executable, os.path.join(HERE, "gen_panel_grid.py"), "--nx", str(a.nx), "--ny",
                               str(a.ny), "--mesh", str(m)], capture_output=True, text=True, check=True).stdout
        cut = text.index("\n", text.index("*SOLID SECTION")) + 1
        edited = text[:cut] + text[cut:].replace("0.05", "0.06", 1)   # the first panel's thickness
        n, dofs = a.nx * a.ny, a.nx * a.ny * 2 * (m + 1) ** 2
    with open(deck, "w") as fh:
        fh.write(text)
    with open(changed, "w") as fh:
        fh.write(edited)
    lib = os.path.join(a.work, "lib")
    lst = os.path.join(a.work, "out.lst")

    def base(d):
        return [a.bin, "-q", "--condense", "yes", "--twins", a.twins, d, "-o", lst]

    def fresh():
        shutil.rmtree(lib, ignore_errors=True)

    def stored():   # the library as the first run leaves it
        fresh()
        subprocess.run(base(deck) + ["--library", lib], check=True, capture_output=True)

    plain = timed(base(deck), a.repeat)
    first = timed(base(deck) + ["--library", lib], a.repeat, fresh)
    second = timed(base(changed) + ["--library", lib], a.repeat, stored)
    unchanged = timed(base(changed) + ["--library", lib], a.repeat)
    size = sum(os.path.getsize(os.path.join(lib, f)) for f in os.listdir(lib))
    kind = "distinct" if a.distinct else "twins " + a.twins
    print(f"{a.model} ({kind}): {n} parts, mesh {m}, {dofs} DOFs; library {size / 1e6:.1f} MB")
    for what, k in (("wall", 0), ("cpu", 1)):
        print(f"{what}: plain {plain[k]:.3f} s  first {first[k]:.3f} s  second (1 of {n} changed) {second[k]:.3f} s  "
              f"unchanged {unchanged[k]:.3f} s  second/first {second[k] / first[k]:.3f}  "
              f"second/plain {second[k] / plain[k]:.3f}")


if __name__ == "__main__":
    main()
