#!/usr/bin/env python3
"""Joint study: every step of decks/joint_sweep.deck against an independent run.

usage: joint_sweep.py SUPERJOIN DECKS_DIR WORKDIR

decks/joint_sweep.deck is a 2D portal frame whose knees are rotational springs;
one step changes the left knee by *CHANGE CONTACT, NAME=KNEEL, SWEEP (five
values of g, so five steps STUDY-1 ... STUDY-5), one changes the right knee, one
keeps the stiffnesses of the *CONTACT cards. For each step this script writes
the portal without *CHANGE CONTACT, with that step's g in the *CONTACT card
and only that step's loads, solves it, and compares every CSV row of the step
to 1e-10 (relative to the largest magnitude of its column). A contact DOF that
another step of the study switches on is listed in every step of the study
(with zero force where it is off): such rows must be zero.
It also checks that the listing says how many factorizations were made.
"""
import csv
import os
import subprocess
import sys

HEAD = """*MATERIAL, NAME=STEEL
*ELASTIC
2.1e11, 0.3
*SUBSTRUCTURE, NAME=COLL
*NODE
1, 0.0, 0.0
2, 0.0, 4.0
*ELEMENT, TYPE=B23, ELSET=C
1, 1, 2
*BEAM SECTION, ELSET=C, MATERIAL=STEEL
5.38e-3, 8.36e-5
*END SUBSTRUCTURE
*SUBSTRUCTURE, NAME=COLR
*NODE
1, 6.0, 0.0
2, 6.0, 4.0
*ELEMENT, TYPE=B23, ELSET=C
1, 1, 2
*BEAM SECTION, ELSET=C, MATERIAL=STEEL
5.38e-3, 8.36e-5
*END SUBSTRUCTURE
*SUBSTRUCTURE, NAME=GIRDER
*NODE
1, 0.0, 4.0
2, 3.0, 4.0
3, 6.0, 4.0
*ELEMENT, TYPE=B23, ELSET=G
1, 1, 2
2, 2, 3
*BEAM SECTION, ELSET=G, MATERIAL=STEEL
7.64e-3, 1.94e-4
*END SUBSTRUCTURE
"""
CONTACTS = """*CONTACT, NAME=KNEEL, MASTER=COLL, SLAVE=GIRDER
2, 1, 1, 2, RIGID
2, 1, 6, 6, {gl}
*CONTACT, NAME=KNEER, MASTER=COLR, SLAVE=GIRDER
2, 3, 1, 2, RIGID
2, 3, 6, 6, {gr}
*BOUNDARY
COLL.1, ENCASTRE
COLR.1, 1, 2
"""
LOADS = """*CLOAD
GIRDER.1, 1, 2.0e4
GIRDER.2, 2, -5.0e4
"""
GL, GR = "8.0e6", "8.0e6"
SWEEP = ["1.0e5", "1.0e6", "1.0e7", "RIGID", "0"]
RIGHT = "2.0e6"


def sweep_deck():
    return ("*HEADING\n"
            "Joint study: a portal frame whose left knee stiffness is swept (tests/parts/joint_sweep.py)\n"
            "** units: N, m\n"
            "** Steps STUDY-1 ... STUDY-5 take the left knee's rotational g from the SWEEP line;\n"
            "** SOFT_RIGHT softens the right knee; BASE keeps the *CONTACT values.\n"
            "** tests/parts/joint_sweep.py checks every step against an independent run.\n"
            + HEAD + CONTACTS.format(gl=GL, gr=GR)
            + "*STEP, NAME=BASE\n" + LOADS + "*END STEP\n"
            + "*STEP, NAME=STUDY\n" + LOADS
            + "*CHANGE CONTACT, NAME=KNEEL, SWEEP\n2, 1, 6, 6, " + ", ".join(SWEEP) + "\n*END STEP\n"
            + "*STEP, NAME=SOFT_RIGHT\n" + LOADS
            + "*CHANGE CONTACT, NAME=KNEER\n2, 3, 6, 6, " + RIGHT + "\n*END STEP\n")


def single_deck(name, gl, gr):
    return (HEAD + CONTACTS.format(gl=gl, gr=gr) + f"*STEP, NAME={name}\n" + LOADS + "*END STEP\n")


def run(exe, deck, work, name, options=()):
    csvdir = os.path.join(work, name)
    lst = os.path.join(work, name + ".lst")
    r = subprocess.run([exe, "-q", deck, "-o", lst, "--csv", csvdir, *options], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: {deck}: exit status {r.returncode}\n{r.stderr}")
        sys.exit(1)
    return csvdir, lst


def rows(csvdir, table, step):
    with open(os.path.join(csvdir, table), newline="") as f:
        data = list(csv.reader(f))
    return data[0], [r for r in data[1:] if r[0].upper() == step.upper()]


KEYS = ("step", "substructure", "contact", "node", "master_node", "slave_node", "element", "type", "end", "dof")


def compare(a, b, table, step):
    head, ra = rows(a, table, step)
    _, rb = rows(b, table, step)
    keys = [j for j, n in enumerate(head) if n in KEYS]
    values = [j for j in range(len(head)) if j not in keys]
    ia = {tuple(r[j].upper() for j in keys): r for r in ra}
    ib = {tuple(r[j].upper() for j in keys): r for r in rb}
    ok = True
    worst = 0.0
    scale = {j: max([abs(float(r[j])) for r in rb] + [1e-300]) for j in values}
    for key, r in ia.items():
        if key not in ib:
            if any(float(r[j]) != 0.0 for j in values if head[j] == "force"):
                print(f"FAIL: {table} {step}: row {key} has a force but is not in the independent run")
                ok = False
            continue
        for j in values:
            d = abs(float(r[j]) - float(ib[key][j])) / scale[j]
            worst = max(worst, d)
            if d > 1e-10:
                print(f"FAIL: {table} {step} {key} {head[j]}: {r[j]} against {ib[key][j]}")
                ok = False
    for key in ib:
        if key not in ia:
            print(f"FAIL: {table} {step}: row {key} of the independent run is missing")
            ok = False
    return ok, worst


def compare_step(a, b, step):
    """Every table of one step: (all within 1e-10, the largest difference)."""
    ok, worst = True, 0.0
    for table in ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv"):
        good, w = compare(a, b, table, step)
        ok = ok and good
        worst = max(worst, w)
    return ok, worst


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, decks, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(decks, "joint_sweep.deck")
    with open(deck) as f:
        if f.read() != sweep_deck():
            print(f"FAIL: {deck} differs from the deck this script describes (regenerate it with --write)")
            return 1
    a, lst = run(exe, deck, work, "study")
    cases = [("BASE", GL, GR)] + [(f"STUDY-{i + 1}", g, GR) for i, g in enumerate(SWEEP)] + [("SOFT_RIGHT", GL, RIGHT)]
    ok = True
    for step, gl, gr in cases:
        single = os.path.join(work, f"single_{step}.deck")
        with open(single, "w") as f:
            f.write(single_deck(step, gl, gr))
        b, _ = run(exe, single, work, f"single_{step}")
        good, worst = compare_step(a, b, step)
        ok = ok and good
        print(f"{'ok' if ok else 'FAIL'}: step {step} (left knee g = {gl}, right knee g = {gr}): "
              f"largest difference {worst:.1e} of the column's largest value")
    with open(lst) as f:
        text = f.read()
    want = "joint study (*CHANGE CONTACT): 7 sets of contact stiffnesses, 7 interface factorizations"
    if want not in text:
        print(f"FAIL: the listing does not say '{want}'")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    if len(sys.argv) == 3 and sys.argv[1] == "--write":
        with open(sys.argv[2], "w") as f:
            f.write(sweep_deck())
        sys.exit(0)
    sys.exit(main(sys.argv))
