#!/usr/bin/env python3
"""Parts made of parts: a building of floors of bays against its one-level model.

usage: building.py SUPERJOIN WORKDIR

bench/gen_building.py writes a building of 3 floors of 2 x 2 bays twice: nested
(*PART BAY; *PART FLOOR of four BAY instances and the contacts between them;
*PART BUILDING of three FLOOR instances and the contacts between floors; one
instance B of BUILDING) and explicit (one *PART BAY, twelve instances F1_BAY1 ..
F3_BAY4 placed by the composed translation, the same contacts in the same
order). Checks:

- the nested run's CSV files (--levels no: the condensed bays in one interface
  system, as the explicit deck's), with the instance paths written as the
  explicit deck's names (B.F3.BAY2 -> F3_BAY2, B.K1_2 -> K1_2), are
  byte-identical to the explicit run's (the unfolding keeps the numbering and
  the placement);
- its listing names nodes by instance path (B.F3.BAY2.12) and says that the
  nesting is unfolded (and, condensed, solved by level);
- the nested run with --condense yes (one condensation of BAY, reused by all
  twelve bays; the top floor's interior eliminated by level) agrees with the
  explicit run to 1e-10 of each column's largest value, and its listing says
  per depth what the condensation by level eliminates (src/analysis/levels.f90:
  a floor's own, boundary and interior reduced unknowns);
- the same building turned (instance B by 30 degrees about an inclined axis:
  three placements composed) agrees with its explicit deck (the composed
  translation, then B's rotation) to 1e-10.
"""
import csv
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
GEN = os.path.join(HERE, "..", "..", "bench", "gen_building.py")
TABLES = ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv",
          "plate_results.csv", "nodes.csv")


def flat_names(text):
    """Instance paths of the nested deck as the explicit deck names them."""
    return re.sub(r"B\.K", "K", re.sub(r"B\.F(\d+)\.", r"F\1_", text))


def exe_and_work(argv, doc):
    """SUPERJOIN and WORKDIR of a `usage: X.py SUPERJOIN WORKDIR` script (the work
    directory made), or None after doc's usage line on stderr."""
    if len(argv) != 3:
        print(doc.strip().splitlines()[2], file=sys.stderr)
        return None
    os.makedirs(argv[2], exist_ok=True)
    return argv[1], argv[2]


def run(exe, deck, work, name, *extra):
    csvdir = os.path.join(work, name)
    lst = os.path.join(work, name + ".lst")
    r = subprocess.run([exe, "-q", deck, "-o", lst, "--csv", csvdir, *extra], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: {deck} {' '.join(extra)}: exit status {r.returncode}\n{r.stderr}")
        sys.exit(1)
    return csvdir, lst


def numeric_compare(a, b, table, names=flat_names, rtol=1e-10):
    """Largest difference of two runs' table, relative to each numeric column's largest value (good: at most
    rtol); the other columns must agree once a's are written by names (the nested paths as the explicit names,
    by default)."""
    with open(os.path.join(a, table), newline="") as f:
        ra = list(csv.reader(f))
    with open(os.path.join(b, table), newline="") as f:
        rb = list(csv.reader(f))
    if len(ra) != len(rb) or ra[0] != rb[0]:
        print(f"FAIL: {table}: header or row count differ")
        return False, 0.0
    cols = range(len(ra[0]))
    numeric = [j for j in cols if all(_is_float(r[j]) for r in ra[1:])]
    scale = {j: max([abs(float(r[j])) for r in ra[1:]] + [1e-300]) for j in numeric}
    worst = 0.0
    for x, y in zip(ra[1:], rb[1:]):
        for j in cols:
            if j in numeric:
                worst = max(worst, abs(float(x[j]) - float(y[j])) / scale[j])
            elif names(x[j]) != y[j]:
                print(f"FAIL: {table}: {x[j]} against {y[j]}")
                return False, worst
    return worst <= rtol, worst


def _is_float(s):
    try:
        float(s)
        return True
    except ValueError:
        return False


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    decks = {}
    for name, extra in (("nested", []), ("explicit", ["--explicit"]), ("turned", ["--turn", "30"]),
                        ("turned_explicit", ["--turn", "30", "--explicit"])):
        decks[name] = os.path.join(work, name + ".deck")
        with open(decks[name], "w") as f:
            subprocess.run([sys.executable, GEN, "--mesh", "4", "--floors", "3", "--grid", "2", *extra],
                           stdout=f, check=True)
    n, nlst = run(exe, decks["nested"], work, "nested", "--levels", "no")
    e, _ = run(exe, decks["explicit"], work, "explicit")
    c, clst = run(exe, decks["nested"], work, "condensed", "--condense", "yes")
    ok = True
    for table in TABLES:
        with open(os.path.join(n, table)) as f:
            mapped = flat_names(f.read())
        with open(os.path.join(e, table)) as f:
            same = mapped == f.read()
        print(f"{'ok' if same else 'FAIL'}: {table}: nested (names mapped) byte-identical to explicit")
        ok = ok and same
    with open(nlst) as f:
        listing = f.read()
    for want in ("parts made of parts: unfolded into 12 instances of parts with a mesh and 20 contacts of "
                 "parts (named by instance path; condensed: by level)", "B.F3.BAY2 "):
        found = want in listing
        print(f"{'ok' if found else 'FAIL'}: listing has '{want}'")
        ok = ok and found
    with open(clst) as f:
        clisting = f.read()
    found = "condensations: 1 computed, 11 reused" in clisting
    print(f"{'ok' if found else 'FAIL'}: condensed run computes one condensation of BAY and reuses it 11 times")
    ok = ok and found
    # the floors by level: floor 1 exports all it owns (the floor above stands on it), floor 3 exports
    # nothing (its own variables would be its interior), floor 2 both exports and hangs on floor 1
    want = ("depth 2: 3 groups (B.F1 .. B.F3), own 96, boundary 96..192 (exported 0..96, attached 0..96), "
            "interior 0..96 (total 96), kinds by counts and rotation: 3; depth 1: 1 group (B), own 384, "
            "boundary 0 (exported 0, attached 0), interior 384 (total 384), kinds by counts and rotation: 1")
    found = want in clisting
    print(f"{'ok' if found else 'FAIL'}: condensed listing's note on the condensation by level has '{want}'")
    ok = ok and found
    for table in TABLES[:5]:
        good, worst = numeric_compare(c, e, table)
        print(f"{'ok' if good else 'FAIL'}: {table}: condensed against explicit, largest difference {worst:.1e}")
        ok = ok and good
    t, _ = run(exe, decks["turned"], work, "turned")
    te, _ = run(exe, decks["turned_explicit"], work, "turned_explicit")
    for table in TABLES:
        good, worst = numeric_compare(t, te, table)
        print(f"{'ok' if good else 'FAIL'}: {table}: turned nested against turned explicit, largest difference "
              f"{worst:.1e}")
        ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
