#!/usr/bin/env python3
"""Benchmark of parts made of parts (doc/performance.md, "Parts made of parts").

usage: bench/building.py [--bin build/superjoin] [--bin-a OTHER] [--work DIR] [--mesh M] [--floors N] [--grid G]
                         [--repeat R] [--edge-joined]

bench/gen_building.py writes the building of the issue (defaults: 20 floors of
4 x 4 = 16 bays, each bay an S4 slab of M x M elements on four B33 columns) as
nested parts (BAY -> FLOOR -> BUILDING) and as one level (the same bays as
instances of BAY). With --edge-joined the bays of a floor are joined along their
whole shared slab edges (every edge node), the floors only at the columns.
Five runs, timed in the same invocation (wall clock and CPU time, user +
system, each the best of R; on a shared machine the CPU time is the steadier
figure):

- monolithic: the nested deck, superjoin --condense no (one sparse
  factorization of the whole unfolded model);
- one level: the one-level deck, superjoin --condense yes (one condensation of
  BAY, reused by all bays; the interface system of all bays factorized);
- nested, by level: the nested deck, --condense yes --levels yes (each floor's
  interior reduced unknowns eliminated onto its boundary, floors alike sharing
  one factorization and one Schur complement, then the building's top system;
  src/analysis/level_solver.f90);
- nested, flat: the nested deck, --condense yes --levels no (as one level: the
  cost of the nesting itself);
- nested, auto: the nested deck, --condense yes and no --levels (the default,
  --levels auto: by level or flat as the counts say, src/analysis/levels.f90;
  its choice is printed after the table).

With --bin-a OTHER, a sixth run times OTHER's nested run by level (another
build, main's say) in the same invocation, for the ratio of the two builds.

The nested listing's notes on the condensation by level are printed after the
table. Every run's CSV files are checked against the one-level run's (names
mapped) to 1e-10 before any time is reported.
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def timed(cmd):
    """Wall clock and CPU time (user + system) of one run."""
    c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {' '.join(cmd)}: exit status {r.returncode}\n{r.stderr}")
    wall = time.perf_counter() - t0
    c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)


def flat(text):
    return re.sub(r"B\.K", "K", re.sub(r"B\.F(\d+)\.", r"F\1_", text))


def worst_difference(a, b, nested=True):
    """Largest |a - b| / max |column| over the numeric columns of two CSV files (a's names mapped if nested)."""
    text = open(a).read()
    ra = [line.split(",") for line in (flat(text) if nested else text).splitlines()]
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
    p.add_argument("--bin-a", help="another build whose nested run by level is timed too")
    p.add_argument("--work", default="/tmp/superjoin-building")
    p.add_argument("--mesh", type=int, default=8)
    p.add_argument("--floors", type=int, default=20)
    p.add_argument("--grid", type=int, default=4)
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--edge-joined", action="store_true")
    p.add_argument("--spacing", type=int, default=1, help="with --edge-joined: join every SPACING-th edge node")
    args = p.parse_args()
    os.makedirs(args.work, exist_ok=True)
    gen = [sys.executable, os.path.join(ROOT, "bench", "gen_building.py"), "--mesh", str(args.mesh),
           "--floors", str(args.floors), "--grid", str(args.grid)] + (["--edge-joined", "--spacing", str(args.spacing)]
                                                                 if args.edge_joined else [])
    decks = {}
    for name, extra in (("nested", []), ("explicit", ["--explicit"])):
        decks[name] = os.path.join(args.work, name + ".deck")
        with open(decks[name], "w") as f:
            subprocess.run(gen + extra, stdout=f, check=True)
    w = args.work
    runs = {   # name: (command, CSV directory, names of the nested deck)
        "monolithic": ([args.bin, "-q", decks["nested"], "--condense", "no", "-o", f"{w}/mono.lst", "--csv",
                        f"{w}/mono"], f"{w}/mono", True),
        "one level (explicit deck)": ([args.bin, "-q", decks["explicit"], "--condense", "yes", "-o", f"{w}/one.lst",
                                       "--csv", f"{w}/one"], f"{w}/one", False),
        "nested, by level": ([args.bin, "-q", decks["nested"], "--condense", "yes", "--levels", "yes", "-o", f"{w}/nested.lst",
                              "--csv", f"{w}/nested"], f"{w}/nested", True),
        "nested, flat (--levels no)": ([args.bin, "-q", decks["nested"], "--condense", "yes", "--levels", "no", "-o",
                                        f"{w}/flat.lst", "--csv", f"{w}/flat"], f"{w}/flat", True),
        "nested, auto (the default)": ([args.bin, "-q", decks["nested"], "--condense", "yes", "-o", f"{w}/auto.lst",
                                        "--csv", f"{w}/auto"], f"{w}/auto", True),
    }
    if args.bin_a:
        runs["nested, by level (--bin-a)"] = ([args.bin_a] + runs["nested, by level"][0][1:-4] +
                                              ["-o", f"{w}/nested_a.lst", "--csv", f"{w}/nested_a"], f"{w}/nested_a", True)
    best, cpu = {}, {}
    for _ in range(args.repeat):
        for name, (cmd, _, _) in runs.items():
            t, c = timed(cmd)
            best[name] = min(best.get(name, t), t)
            cpu[name] = min(cpu.get(name, c), c)
    tables = ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv")
    worst = {name: max(worst_difference(f"{d}/{t}", f"{w}/one/{t}", nested) for t in tables)
             for name, (_, d, nested) in runs.items() if name != "one level (explicit deck)"}
    dofs = re.search(r"active DOFs\s+(\d+)", open(f"{w}/mono.lst").read())
    print(f"building: {args.floors} floors of {args.grid}x{args.grid} bays, mesh {args.mesh}"
          f"{', bays joined along their edges' if args.edge_joined else ''}"
          f"{f' every {args.spacing} nodes' if args.edge_joined and args.spacing > 1 else ''}"
          f"{', ' + dofs.group(1) + ' DOFs' if dofs else ''}; against one level: "
          + ", ".join(f"{name} {d:.1e}" for name, d in worst.items()))
    print(f"  {'run':30s} {'wall':>8s}     {'ratio':>6s}   {'cpu':>8s}     {'ratio':>6s}   (best of {args.repeat}; "
          "ratio: x faster than monolithic)")
    for name, t in best.items():
        print(f"  {name:30s} {t:8.2f} s   {best['monolithic'] / t:6.2f}   {cpu[name]:8.2f} s   "
              f"{cpu['monolithic'] / cpu[name]:6.2f}")
    for name, lst in (("one level", "one"), ("nested, by level", "nested")):
        eq = re.search(r"equations\s+(\d+)", open(f"{w}/{lst}.lst").read())
        fnz = re.search(r"factor nonzeros\s+(\d+)", open(f"{w}/{lst}.lst").read())
        if eq and fnz:
            print(f"  {name}: {eq.group(1)} reduced equations, {fnz.group(1)} factor nonzeros")
    for level in re.findall(r"condensation by level: .*", open(f"{w}/nested.lst").read()):
        print("  " + level)
    choice = re.search(r"--levels auto: [^;]*", open(f"{w}/auto.lst").read())
    if choice:
        print("  the default run's choice: " + choice.group(0))
    return 0 if max(worst.values()) <= 1e-10 else 1


if __name__ == "__main__":
    sys.exit(main())
