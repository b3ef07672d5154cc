#!/usr/bin/env python3
"""Parts made of parts condensed by level, in a joint study (*CHANGE CONTACT, SWEEP).

usage: levels_sweep.py SUPERJOIN WORKDIR

bench/gen_building.py --edge-joined writes a building of 4 floors of 2 x 2 bays
(mesh 4), nested parts (BAY -> FLOOR -> BUILDING, one instance B). A contact
TOP at the top level (in *ASSEMBLY) joins the slab corner B.F4.BAY1.C3 to the
same point of B.F4.BAY4 diagonally, and a second step sweeps its stiffness over
two values (*CHANGE CONTACT, NAME=TOP, SWEEP): three sets of contact
stiffnesses, each solved by level with the condensations reused. The run by
level (--levels yes) agrees to 1e-10 of each column's largest value with the
same deck condensed flat (--levels no) and with the monolithic run
(--condense no), every step; its listing says the joint study and the
condensation by level were done.

(A contact declared inside a *PART, the floors' J* and the building's K*, is
changed by its instance path, NAME=B.F2.J1 or PART=FLOOR: tests/parts/nested_change.py.)
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from building import run, numeric_compare, exe_and_work, TABLES, GEN  # noqa: E402

SAME = lambda name: name  # noqa: E731

TOP = ("*CONTACT, NAME=TOP, MASTER=B.F4.BAY1, SLAVE=B.F4.BAY4\n"
       "B.F4.BAY1.C3, B.F4.BAY4.C1, 1, 3, 1.0e9\n"
       "*END ASSEMBLY")
SWEEP = ("*END STEP\n"
         "*STEP, NAME=SOFT\n*CLOAD\nB.F4.BAY4.5, 1, 2.0e5\n"
         "*CHANGE CONTACT, NAME=TOP, SWEEP\n"
         "B.F4.BAY1.C3, B.F4.BAY4.C1, 1, 3, 1.0e7, 1.0e11\n"
         "*END STEP")


def main(argv):
    args = exe_and_work(argv, __doc__)
    if args is None:
        return 2
    exe, work = args
    text = subprocess.run([sys.executable, GEN, "--mesh", "4", "--floors", "4", "--grid", "2", "--edge-joined"],
                          stdout=subprocess.PIPE, text=True, check=True).stdout
    deck = os.path.join(work, "sweep.deck")
    with open(deck, "w") as f:
        f.write(text.replace("*END ASSEMBLY", TOP).replace("*END STEP", SWEEP, 1))
    lv, lv_lst = run(exe, deck, work, "levels", "--condense", "yes", "--levels", "yes")
    fl, _ = run(exe, deck, work, "flat", "--condense", "yes", "--levels", "no")
    mono, _ = run(exe, deck, work, "monolithic", "--condense", "no")
    ok = True
    for other, what in ((fl, "flat (--levels no)"), (mono, "monolithic")):
        for table in TABLES[:5]:
            good, worst = numeric_compare(lv, other, table, names=SAME)
            print(f"{'ok' if good else 'FAIL'}: {table}: by level against {what}, largest difference {worst:.1e}")
            ok = ok and good
    with open(os.path.join(lv, "displacements.csv")) as f:
        steps = {line.split(",")[0] for line in f.read().splitlines()[1:]}
    swept = steps == {"WIND", "SOFT-1", "SOFT-2"}
    print(f"{'ok' if swept else 'FAIL'}: the steps of the sweep: {sorted(steps)}")
    with open(lv_lst) as f:
        listing = f.read()
    for want in ("joint study (*CHANGE CONTACT): 3 sets of contact stiffnesses, 3 interface factorizations",
                 "condensation by level: done (each group's interior eliminated onto its boundary"):
        found = want in listing
        print(f"{'ok' if found else 'FAIL'}: the listing by level has '{want}'")
        ok = ok and found
    return 0 if ok and swept else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
