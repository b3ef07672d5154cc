#!/usr/bin/env python3
"""Parts made of parts: a floor's boundary node that is a slave inside the floor.

usage: levels.py SUPERJOIN WORKDIR

A three-level deck (BAY -> FLOOR of two bays in a row -> BUILDING of three
floors -> one instance B), written here twice, nested and one level (instances
F2_BAY2, the same contacts in the same order). Inside a floor, contact J1 joins
bay 1's slab corners C2 and C3 to bay 2's C1 and C4: C1 by a finite g, C4 by
RIGID translations (and the middles of the shared edge by 1e11). The floor above stands on every slab corner (RIGID
translations), so those two slaves are on the floor's boundary: what a floor
exports to the building is its nodes' roots and its own contacts' Δu, never a
g-sized term between physical DOFs. Checks:

- nested, --condense yes --levels yes (by level), against the explicit deck (--condense yes and no) to
  1e-10 of each column's largest value (displacements, reactions, contact
  forces, element forces, plate results), also with the building turned by 30
  degrees about an inclined axis;
- the listing's notes on the condensation by level (done: the nested run is
  solved by level, analysis/level_solver): per depth, the groups and their
  variables (a floor: own, boundary, interior), then the groups, kinds and
  interior eliminated. J1 also joins the
  middles of the shared slab edge, which no other floor touches: every floor
  has 24 interior unknowns there (those two nodes of each bay, on the bays'
  boundary since the instances of BAY share one, and J1's Δu at them), the top
  floor all its 69;
- the sweep (solved by level: J1's Δu is a floor's interior, eliminated with
  the floor): J1's finite g from 1e6 to 1e14 times the slab's membrane
  stiffness E t. The difference to the RIGID joint falls as 1/g (the joint's
  compliance) until round-off, and never above: a stiff g inside a group loses
  no digits.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "bench"))
sys.path.insert(0, HERE)   # first: bench/ has a building.py too
from building import run, numeric_compare, TABLES  # noqa: E402
import gen_building as gb  # noqa: E402

MESH = 2
ET = gb.E * gb.THICK       # the slab's membrane stiffness (N/m)


def joint(inst_a, inst_b, g):
    """J1's lines: C2-C1 by g (translations), C3-C4 RIGID; rotations 4e9; and the middles of the
    shared slab edge (no other floor touches them: the floor's interior) by 1e11."""
    n = MESH + 1
    east, west = (MESH // 2) * n + n, (MESH // 2) * n + 1
    return [f"{inst_a}.C2, {inst_b}.C1, 1, 3, {g}", f"{inst_a}.C2, {inst_b}.C1, 4, 6, {gb.G_ROT!r}",
            f"{inst_a}.C3, {inst_b}.C4, 1, 3, RIGID", f"{inst_a}.C3, {inst_b}.C4, 4, 6, {gb.G_ROT!r}",
            f"{inst_a}.{east}, {inst_b}.{west}, 1, 6, {gb.G_TRA!r}"]


def storeys(name, inst):
    out = []
    for k in (1, 2):
        for b in (1, 2):
            out.append(f"*CONTACT, NAME={name(k, b)}, MASTER={inst(k, b)}, SLAVE={inst(k + 1, b)}")
            for c in range(1, 5):
                out.append(f"{inst(k, b)}.C{c}, {inst(k + 1, b)}.F{c}, 1, 3, RIGID")
                out.append(f"{inst(k, b)}.C{c}, {inst(k + 1, b)}.F{c}, 4, 6, {gb.G_ROT!r}")
    return out


def steps(path, mid):
    out = ["*BOUNDARY"] + [f"{path(1, b)}.FOOT, ENCASTRE" for b in (1, 2)]
    out += ["*STEP, NAME=PUSH", "*CLOAD", f"{path(3, 2)}.{(MESH + 1) ** 2}, 1, 2.0e5",
            f"{path(3, 1)}.{MESH + 1}, 2, -1.5e5", f"{path(2, 2)}.1, 2, 3.0e5"]
    out += [f"{path(k, 2)}.{mid}, 3, {-1.0e5 * k!r}" for k in (1, 2, 3)]
    out += ["*END STEP"]
    return out


def deck(g, explicit, turn):
    bay, mid = gb.bay(MESH)
    out = ["*HEADING", "A floor's boundary slaves (tests/parts/levels.py)", "*MATERIAL, NAME=CONCRETE",
           "*ELASTIC", f"{gb.E!r}, {gb.NU!r}"] + bay
    rot = [gb.turn_line(turn)] if turn else []
    if explicit:
        out.append("*ASSEMBLY, NAME=SITE")
        for k in (1, 2, 3):
            for b in (1, 2):
                out += [f"*INSTANCE, NAME=F{k}_BAY{b}, PART=BAY",
                        f"{gb.SIDE * (b - 1)!r}, 0.0, {gb.HEIGHT * (k - 1)!r}"] + rot + ["*END INSTANCE"]
        for k in (1, 2, 3):
            out.append(f"*CONTACT, NAME=F{k}_J1, MASTER=F{k}_BAY1, SLAVE=F{k}_BAY2")
            out += joint(f"F{k}_BAY1", f"F{k}_BAY2", g)
        out += storeys(lambda k, b: f"K{k}_{b}", lambda k, b: f"F{k}_BAY{b}")
        out.append("*END ASSEMBLY")
        return out + steps(lambda k, b: f"F{k}_BAY{b}", mid)
    out.append("*PART, NAME=FLOOR")
    for b in (1, 2):
        out += [f"*INSTANCE, NAME=BAY{b}, PART=BAY", f"{gb.SIDE * (b - 1)!r}, 0.0, 0.0", "*END INSTANCE"]
    out.append("*CONTACT, NAME=J1, MASTER=BAY1, SLAVE=BAY2")
    out += joint("BAY1", "BAY2", g) + ["*END PART", "*PART, NAME=BUILDING"]
    for k in (1, 2, 3):
        out += [f"*INSTANCE, NAME=F{k}, PART=FLOOR", f"0.0, 0.0, {gb.HEIGHT * (k - 1)!r}", "*END INSTANCE"]
    out += storeys(lambda k, b: f"K{k}_{b}", lambda k, b: f"F{k}.BAY{b}")
    out += ["*END PART", "*ASSEMBLY, NAME=SITE", "*INSTANCE, NAME=B, PART=BUILDING"]
    if turn:
        out += ["0.0, 0.0, 0.0"] + rot
    out += ["*END INSTANCE", "*END ASSEMBLY"]
    return out + steps(lambda k, b: f"B.F{k}.BAY{b}", mid)


def write(work, name, g, explicit=False, turn=0.0):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write("\n".join(deck(g, explicit, turn)) + "\n")
    return path


def compare(a, b, what, tables=TABLES[:5]):
    ok = True
    for table in tables:
        good, worst = numeric_compare(a, b, table)
        print(f"{'ok' if good else 'FAIL'}: {table}: {what}, largest difference {worst:.1e}")
        ok = ok and good
    return ok


def largest_difference(a, b):
    """Largest difference of two runs' displacements (same deck but J1's g), relative to each column's largest value."""
    return numeric_compare(a, b, "displacements.csv", names=lambda name: name)[1]


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    g = repr(1.0e11)
    n, nlst = run(exe, write(work, "nested", g), work, "nested", "--condense", "yes", "--levels", "yes")
    ex = write(work, "explicit", g, explicit=True)
    e, _ = run(exe, ex, work, "explicit", "--condense", "yes")
    m, _ = run(exe, ex, work, "monolithic", "--condense", "no")
    ok = compare(n, e, "nested condensed against explicit condensed")
    ok = compare(n, m, "nested condensed against explicit monolithic") and ok
    t, _ = run(exe, write(work, "turned", g, turn=30.0), work, "turned", "--condense", "yes", "--levels", "yes")
    te, _ = run(exe, write(work, "turned_explicit", g, explicit=True, turn=30.0), work, "turned_explicit",
                "--condense", "no")
    ok = compare(t, te, "turned nested condensed against turned explicit monolithic") and ok
    with open(nlst) as f:
        listing = f.read()
    for want in ("condensation by level: done (each group's interior eliminated onto its boundary, deepest first, "
                 "groups alike by their assembled matrix sharing one factorization: next note); in reduced unknowns: "
                 "depth 2: 3 groups (B.F1 .. B.F3), own 69, boundary 45..93 (exported 0..45, attached 0..48), "
                 "interior 24..69 (total 117), kinds by counts and rotation: 3",
                 "condensation by level: 3 groups in 3 kinds (groups alike share one factorization and one Schur "
                 "complement), 117 interior reduced unknowns eliminated"):
        found = want in listing
        print(f"{'ok' if found else 'FAIL'}: listing has '{want}'")
        ok = ok and found
    r, _ = run(exe, write(work, "rigid", "RIGID"), work, "rigid", "--condense", "yes", "--levels", "yes")
    for e10 in range(6, 15):
        s, _ = run(exe, write(work, f"g{e10}", repr(ET * 10.0 ** e10)), work, f"g{e10}", "--condense", "yes", "--levels", "yes")
        d = largest_difference(s, r)
        # the joint's compliance (about E t / g of the answer) or round-off, never more
        good = d <= max(2.0e-2 * 10.0 ** -e10, 1.0e-11)
        print(f"{'ok' if good else 'FAIL'}: g = 1e{e10} E t on J1 (inside a floor): against RIGID {d:.1e}")
        ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
