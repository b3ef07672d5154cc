#!/usr/bin/env python3
"""Parts made of parts: --levels auto (the default) chooses by level or flat from the counts.

usage: levels_auto.py SUPERJOIN WORKDIR

Small edge-joined buildings (bench/gen_building.py --edge-joined --grid 2),
which --levels auto (src/analysis/levels.f90, auto_choice) condenses by level
when the floors' interiors are at least twice their boundaries and half of the
reduced unknowns, with at least 3 floors per kind:
- mesh 8, 9 floors (9 groups in 3 kinds, interiors 6144 against boundaries
  1536): by level;
- mesh 6, 4 floors (4 groups in 3 kinds): flat;
- mesh 4, 9 floors (interiors 2688 against boundaries 1536): flat.
For each, the default run (no --levels: auto) agrees to 1e-10 of each column's
largest value with --levels yes (by level) and --levels no (flat), to 5e-10
with the monolithic run (--condense no), and its listing note states the
counts and the choice. (The condensed runs agree to about 1e-11; the
monolithic run differs by 8e-11 to 1.3e-10 on mesh 8, depending on the CPU
the BLAS kernels run on, by 1e-10 to 2.6e-10 on meshes 6 and 7: the round-off
of a system whose condition estimate is about 1e8, eps times which is 2e-8,
not a difference of method.)
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from building import run, numeric_compare, exe_and_work, TABLES, GEN  # noqa: E402

SAME = lambda name: name  # noqa: E731
MONOLITHIC_RTOL = 5e-10   # the monolithic run's round-off (condition about 1e8): the docstring

CASES = (
    (8, 9, "--levels auto: interiors 6144 >= 2 x boundaries 1536, 6144 >= 1/2 of 7296 unknowns, "
           "9 groups >= 3 x 3 kinds: by level; each group's interior eliminated", True),
    (6, 4, "--levels auto: interiors 2016 >= 2 x boundaries 576, 2016 >= 1/2 of 2448 unknowns, "
           "4 groups < 3 x 3 kinds: flat; the condensed leaves' K* form one interface system", False),
    (4, 9, "--levels auto: interiors 2688 < 2 x boundaries 1536, 2688 >= 1/2 of 3840 unknowns, "
           "9 groups >= 3 x 3 kinds: flat; the condensed leaves' K* form one interface system", False),
)


def deck(work, mesh, floors):
    path = os.path.join(work, f"m{mesh}f{floors}.deck")
    with open(path, "w") as f:
        subprocess.run([sys.executable, GEN, "--mesh", str(mesh), "--floors", str(floors), "--grid", "2", "--edge-joined"],
                       stdout=f, check=True)
    return path


def check(found, what):
    print(f"{'ok' if found else 'FAIL'}: {what}")
    return found


def main(argv):
    args = exe_and_work(argv, __doc__)
    if args is None:
        return 2
    exe, work = args
    ok = True
    for mesh, floors, want, by_level in CASES:
        d = deck(work, mesh, floors)
        case = f"m{mesh}f{floors}"
        auto, auto_lst = run(exe, d, work, f"auto_{case}", "--condense", "yes")
        with open(auto_lst) as f:
            listing = f.read()
        ok = check(want in listing, f"{case}: the note has '{want}'") and ok
        ok = check((f"condensation by level: {floors} groups in 3 kinds" in listing) == by_level,
                   f"{case}: the solve is {'by level' if by_level else 'flat'}") and ok
        others = (("--levels yes", ("--condense", "yes", "--levels", "yes"), 1e-10),
                  ("--levels no", ("--condense", "yes", "--levels", "no"), 1e-10),
                  ("monolithic", ("--condense", "no"), MONOLITHIC_RTOL))
        for what, extra, rtol in others:
            other, _ = run(exe, d, work, f"{what.replace(' ', '').strip('-')}_{case}", *extra)
            for table in TABLES[:5]:
                good, worst = numeric_compare(auto, other, table, names=SAME, rtol=rtol)
                ok = check(good, f"{case}: {table}: auto against {what}, largest difference {worst:.1e}") \
                    and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
