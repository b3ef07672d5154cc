#!/usr/bin/env python3
"""Parts made of parts condensed by level: a building whose bays are joined along their slab edges.

usage: edge_levels.py SUPERJOIN WORKDIR [results | note]

bench/gen_building.py --edge-joined writes a building of 4 floors of 2 x 2 bays
(mesh 4) whose bays are joined inside a floor at every node of their shared
slab edges, the floors only at the columns: a floor's edge joints (their roots
and Δu) are reduced unknowns no other floor sees, its interior, which the
condensed run eliminates floor by floor (analysis/level_solver.f90), the two
middle floors alike (one factorization and one Schur complement for both).

results: the nested run by level (the default) agrees to 1e-10 of each
column's largest value with the same deck condensed flat (--levels no), with
the explicit one-level deck condensed and with the monolithic run
(--condense no); so does the building turned by 30 degrees about an inclined
axis against its explicit deck.

note: the listing says that the condensation by level was done (groups, kinds,
interior eliminated, the top system), and --levels no that it was not; the
solve by level needed no iterative refinement (it is a direct solve of K_red:
a slip that refinement would hide, in the load condensation say, shows there).
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from building import run, numeric_compare, TABLES, GEN  # noqa: E402

SAME = lambda name: name  # noqa: E731


def deck(work, name, *extra):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        subprocess.run([sys.executable, GEN, "--mesh", "4", "--floors", "4", "--grid", "2", "--edge-joined", *extra],
                       stdout=f, check=True)
    return path


def compare(a, b, what, names=None):
    ok = True
    for table in TABLES[:5]:
        good, worst = numeric_compare(a, b, table, **({"names": names} if names else {}))
        print(f"{'ok' if good else 'FAIL'}: {table}: {what}, largest difference {worst:.1e}")
        ok = ok and good
    return ok


def has(listing, want):
    with open(listing) as f:
        found = want in f.read()
    print(f"{'ok' if found else 'FAIL'}: {os.path.basename(listing)} has '{want}'")
    return found


def main(argv):
    if len(argv) not in (3, 4):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1:3]
    mode = argv[3] if len(argv) == 4 else "results"
    work = os.path.join(work, mode)
    os.makedirs(work, exist_ok=True)
    nested = deck(work, "nested")
    lv, lv_lst = run(exe, nested, work, "levels", "--condense", "yes", "--levels", "yes")
    fl, fl_lst = run(exe, nested, work, "flat", "--condense", "yes", "--levels", "no")
    if mode == "note":
        ok = has(lv_lst, "condensation by level: done (each group's interior eliminated onto its boundary")
        ok = has(lv_lst, "depth 2: 4 groups (B.F1 .. B.F4), own 384, boundary 96..192 (exported 0..96, attached "
                 "0..96), interior 288..384 (total 1248)") and ok
        ok = has(lv_lst, "condensation by level: 4 groups in 3 kinds (groups alike share one factorization and one "
                 "Schur complement), 1248 interior reduced unknowns eliminated") and ok
        ok = has(fl_lst, "condensation by level: not done (--levels no;") and ok
        with open(lv_lst) as f:
            exact = "refinement steps" not in f.read()
        print(f"{'ok' if exact else 'FAIL'}: the solve by level needs no iterative refinement (a direct solve of K_red)")
        ok = ok and exact
        with open(fl_lst) as f:
            flat_has_none = "condensation by level: 4 groups" not in f.read()
        print(f"{'ok' if flat_has_none else 'FAIL'}: --levels no eliminates nothing by level")
        return 0 if ok and flat_has_none else 1
    ex, _ = run(exe, deck(work, "explicit", "--explicit"), work, "explicit", "--condense", "yes")
    mono, _ = run(exe, nested, work, "monolithic", "--condense", "no")
    ok = compare(lv, fl, "by level against flat (--levels no)", SAME)
    ok = compare(lv, ex, "by level against the explicit deck condensed") and ok
    ok = compare(lv, mono, "by level against monolithic", SAME) and ok
    t, _ = run(exe, deck(work, "turned", "--turn", "30"), work, "turned", "--condense", "yes")
    te, _ = run(exe, deck(work, "turned_explicit", "--turn", "30", "--explicit"), work, "turned_explicit",
                "--condense", "yes")
    ok = compare(t, te, "turned, by level against the turned explicit deck") and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
