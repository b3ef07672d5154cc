#!/usr/bin/env python3
"""Joint study reuse: what a sweep keeps from one value for the next, against independent runs.

usage: joint_reuse.py SUPERJOIN WORKDIR

A joint study keeps, from one value of the contact stiffnesses to the next,
the interface matrix's analysis (refactored only while its pattern is the
same: finite g to finite g) and the condensed parts' loads f* (condensed
again only when the loads differ). This script solves the portal frame of
tests/parts/joint_sweep.py with its parts condensed (--condense yes) and
steps that take the left knee's rotational g from finite to finite
(1e5, 1e6, 1e7), to RIGID and to 0 (other unknowns: analyzed again), back to
finite, then a step with other loads and another finite g (its f* must be
condensed anew), and compares every CSV row of every step to 1e-10 with an
independent monolithic run (--condense no) of that step alone. It also
checks that the listing says how many factorizations and condensations were made.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from joint_sweep import HEAD, CONTACTS, LOADS, GL, GR, compare_step, run  # noqa: E402

SWEEP = ["1.0e5", "1.0e6", "1.0e7", "RIGID", "0", "3.0e6"]
HEAVY = """*CLOAD
GIRDER.1, 1, -1.5e4
GIRDER.2, 2, -9.0e4
GIRDER.2, 1, 7.0e3
"""
HEAVY_G = "5.0e5"


def study_deck():
    return ("*HEADING\nJoint study reuse (tests/parts/joint_reuse.py)\n" + HEAD + CONTACTS.format(gl=GL, gr=GR)
            + "*STEP, NAME=STUDY\n" + LOADS
            + "*CHANGE CONTACT, NAME=KNEEL, SWEEP\n2, 1, 6, 6, " + ", ".join(SWEEP) + "\n*END STEP\n"
            + "*STEP, NAME=HEAVY\n" + HEAVY
            + "*CHANGE CONTACT, NAME=KNEEL\n2, 1, 6, 6, " + HEAVY_G + "\n*END STEP\n")


def single_deck(name, gl, loads):
    return HEAD + CONTACTS.format(gl=gl, gr=GR) + f"*STEP, NAME={name}\n" + loads + "*END STEP\n"


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "study.deck")
    with open(deck, "w") as f:
        f.write(study_deck())
    a, lst = run(exe, deck, work, "study", ("--condense", "yes"))
    cases = [(f"STUDY-{i + 1}", g, LOADS) for i, g in enumerate(SWEEP)] + [("HEAVY", HEAVY_G, HEAVY)]
    ok = True
    for step, gl, loads in cases:
        single = os.path.join(work, f"single_{step}.deck")
        with open(single, "w") as f:
            f.write(single_deck(step, gl, loads))
        b, _ = run(exe, single, work, f"single_{step}", ("--condense", "no"))
        good, worst = compare_step(a, b, step)
        ok = ok and good
        print(f"{'ok' if ok else 'FAIL'}: step {step} (left knee g = {gl}): "
              f"largest difference {worst:.1e} of the column's largest value")
    with open(lst) as f:
        text = f.read()
    for want in ("joint study (*CHANGE CONTACT): 7 sets of contact stiffnesses, 7 interface factorizations, "
                 "2 condensations computed and reused 12 times",
                 "substructure GIRDER condensed (CONDENSE=YES)"):
        if want not in text:
            print(f"FAIL: the listing does not say '{want}'")
            ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
