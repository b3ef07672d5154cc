#!/usr/bin/env python3
"""Benchmark of parts made of parts (doc/performance.md, "Parts made of parts").

usage: bench/building.py [--bin build/superjoin] [--work DIR] [--mesh M] [--floors N] [--grid G] [--repeat R]

bench/gen_building.py writes the building of the issue (defaults: 20 floors of
4 x 4 = 16 bays, each bay an S4 slab of M x M elements on four B33 columns) as
nested parts (BAY -> FLOOR -> BUILDING). Three runs of that one deck, timed
in the same invocation (wall clock, the best of R):

- monolithic: superjoin --condense no (one sparse factorization of the whole
  unfolded model);
- one level: superjoin --condense yes (each bay condensed from one condensation
  of BAY, reused by all bays; the interface system of all bays factorized);
- nested: the same run as "one level" today, since parts made of parts are
  unfolded and solved flattened (no condensation by level yet): the figure is
  the cost of the nesting itself (unfolding, path names) against the one-level
  deck written by gen_building.py --explicit and condensed the same way.

The nested CSV files are checked against the explicit deck's (names mapped) to
1e-10 before any time is reported.
"""
import argparse
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd):
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)}: exit status {r.returncode}\n{r.stderr}")
    return time.perf_counter() - t0


def flat(text):
    return re.sub(r"B\.K", "K", re.sub(r"B\.F(\d+)\.", r"F\1_", text))


def worst_difference(a, b):
    """Largest |a - b| / max |column| over the numeric columns of two CSV files (names mapped)."""
    ra = [line.split(",") for line in flat(open(a).read()).splitlines()]
    rb = [line.split(",") for line in open(b).read().splitlines()]
    assert len(ra) == len(rb) and ra[0] == rb[0], (a, b)
    worst = 0.0
    for j in range(len(ra[0])):
        try:
            xa = [float(r[j]) for r in ra[1:]]
            xb = [float(r[j]) for r in rb[1:]]
        except ValueError:
            assert [r[j] for r in ra] == [r[j] for r in rb], (a, j)
            continue
        scale = max([abs(x) for x in xa] + [1e-300])
        worst = max([worst] + [abs(x - y) / scale for x, y in zip(xa, xb)])
    return worst


def main():
    p = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    p.add_argument("--bin", default=os.path.join(ROOT, "build", "superjoin"))
    p.add_argument("--work", default="/tmp/superjoin-building")
    p.add_argument("--mesh", type=int, default=8)
    p.add_argument("--floors", type=int, default=20)
    p.add_argument("--grid", type=int, default=4)
    p.add_argument("--repeat", type=int, default=1)
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    gen = [sys.executable, os.path.join(ROOT, "bench", "gen_building.py"), "--mesh", str(args.mesh),
           "--floors", str(args.floors), "--grid", str(args.grid)]
    decks = {}
    for name, extra in (("nested", []), ("explicit", ["--explicit"])):
        decks[name] = os.path.join(args.work, name + ".deck")
        with open(decks[name], "w") as f:
            subprocess.run(gen + extra, stdout=f, check=True)
    w = args.work
    runs = {
        "monolithic": [args.bin, "-q", decks["nested"], "--condense", "no", "-o", f"{w}/mono.lst"],
        "one level (explicit deck)": [args.bin, "-q", decks["explicit"], "--condense", "yes", "-o",
                                      f"{w}/one.lst", "--csv", f"{w}/one"],
        "nested (flattened)": [args.bin, "-q", decks["nested"], "--condense", "yes", "-o", f"{w}/nested.lst",
                               "--csv", f"{w}/nested"],
    }
    best = {}
    for _ in range(args.repeat):
        for name, cmd in runs.items():
            t = timed(cmd)
            best[name] = min(best.get(name, t), t)
    worst = max(worst_difference(f"{w}/nested/{t}", f"{w}/one/{t}")
                for t in ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv"))
    dofs = re.search(r"active DOFs\s+(\d+)", open(f"{w}/mono.lst").read())
    print(f"building: {args.floors} floors of {args.grid}x{args.grid} bays, mesh {args.mesh}"
          f"{', ' + dofs.group(1) + ' DOFs' if dofs else ''}; nested against one level: {worst:.1e}")
    for name, t in best.items():
        print(f"  {name:28s} {t:8.2f} s   {best['monolithic'] / t:6.2f} x monolithic")
    return 0 if worst <= 1e-10 else 1


if __name__ == "__main__":
    sys.exit(main())
