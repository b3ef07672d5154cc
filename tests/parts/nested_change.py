#!/usr/bin/env python3
"""Joint studies on contacts declared inside parts made of parts (*CHANGE CONTACT by instance path).

usage: nested_change.py SUPERJOIN WORKDIR [turned|twins]

bench/gen_building.py writes a building of 4 floors of 2 x 2 bays (mesh 4;
parts BAY -> FLOOR -> BUILDING, one instance B). Its step WIND is copied into
steps that change contacts declared inside the parts, and each step of the
nested run must equal an independent run of the explicit deck
(`gen_building.py --explicit`: one level, contacts F2_J1, K2_3, ...) whose
contact lines carry that step's values, edited by hand here, to 1e-10 of each
column's largest value. Released DOFs keep their rows (force 0) in the nested
run only, as the reference manual says.

Default: bays joined along their edges (--edge-joined), runs monolithic
(--condense no), condensed flat (--levels no) and by level (--levels yes: a
floor whose joint changed is no longer alike the others, the listing's
kinds), steps:
- STUDY, a SWEEP over two values: `NAME=B.F2.J1` (the floor's joint J1 in
  floor F2 only, node pairs written as in the part: BAY1.E, BAY2.W) on the
  translations, and a line `B.K2_3` (the building's storey joint K2_3) on the
  rotations;
- FLOORS: `PART=FLOOR, NAME=J4` (J4 in every floor) and `NAME=B.F3.J3` (node
  pairs by their whole path);
- RELEASE: the rotations of `B.F3.J2` released (g = 0).

`turned`: bays joined at their corners, B turned by 30 degrees about an
inclined axis, and a contact JM of FLOOR between the mid-edge nodes of BAY1 and
BAY2 with g = 0 (it connects nothing) that only floor F2's copy switches on
(so only some steps and one floor connect it); runs by level with --solver
umfpack, flat with lapack, monolithic with cholmod; steps:
- STUDY (SWEEP): `NAME=B.F2.JM` and `B.K2_3`;
- FLOORS: `PART=FLOOR` with the line `J1, 4, 6, g` (J1 whole, every floor);
- RELEASE: `B.F3.J2` released and `PART=BUILDING` with the line `F2.J3` (a
  path inside the part).

`twins`: two buildings B and C alike (the edge-joined one, C 20 m east), a
step TWIN that changes C.F2.J1 only: by level and flat against the monolithic
run to 1e-10; by level the 8 floors form 3 kinds (B.F2 = B.F3 = C.F2 = C.F3
...) until C.F2 has a joint of its own (more kinds in TWIN's factorization).
"""
import csv
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from building import run, flat_names, numeric_compare, GEN  # noqa: E402
TABLES = ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv", "plate_results.csv")
FLOORS = 4

SCENARIOS = {
    "edge": {
        "build": ["--mesh", "4", "--floors", str(FLOORS), "--grid", "2", "--edge-joined"],
        "part_contact": None,
        "changes": {   # step -> *CHANGE CONTACT cards of the nested deck
            "STUDY": ["*CHANGE CONTACT, NAME=B.F2.J1, SWEEP", "BAY1.E, BAY2.W, 1, 3, 1.0e8, 1.0e12",
                      "*CHANGE CONTACT, SWEEP", "B.K2_3, 4, 6, 1.0e7, 4.0e10"],
            "FLOORS": ["*CHANGE CONTACT, PART=FLOOR, NAME=J4", "BAY3.E, BAY4.W, 4, 6, 1.0e6",
                       "*CHANGE CONTACT, NAME=B.F3.J3", "B.F3.BAY2.N, B.F3.BAY4.S, 1, 3, 2.0e9"],
            "RELEASE": ["*CHANGE CONTACT", "B.F3.J2, 4, 6, 0.0"],
        },
        "edits": {   # solved step -> (explicit contact, first dof, last dof, g) of its reference deck
            "WIND": [],
            "STUDY-1": [("F2_J1", 1, 3, "1.0e8"), ("K2_3", 4, 6, "1.0e7")],
            "STUDY-2": [("F2_J1", 1, 3, "1.0e12"), ("K2_3", 4, 6, "4.0e10")],
            "FLOORS": [(f"F{k}_J4", 4, 6, "1.0e6") for k in range(1, FLOORS + 1)] + [("F3_J3", 1, 3, "2.0e9")],
            "RELEASE": [("F3_J2", 4, 6, "0.0")],
        },
        "runs": [("monolithic", ["--condense", "no"]), ("flat", ["--condense", "yes", "--levels", "no"]),
                 ("levels", ["--condense", "yes", "--levels", "yes"])],
    },
    "turned": {
        "build": ["--mesh", "4", "--floors", str(FLOORS), "--grid", "2", "--turn", "30"],
        "part_contact": ("JM", "BAY1", "BAY2", "15", "11", "1, 6"),   # mid-edge nodes of mesh 4
        "changes": {
            "STUDY": ["*CHANGE CONTACT, NAME=B.F2.JM, SWEEP", "BAY1.15, BAY2.11, 1, 6, 1.0e9, 1.0e11",
                      "*CHANGE CONTACT, SWEEP", "B.K2_3, 4, 6, 1.0e7, 4.0e10"],
            "FLOORS": ["*CHANGE CONTACT, PART=FLOOR", "J1, 4, 6, 1.0e6"],
            "RELEASE": ["*CHANGE CONTACT", "B.F3.J2, 4, 6, 0.0", "*CHANGE CONTACT, PART=BUILDING",
                        "F2.J3, 1, 3, 5.0e8"],
        },
        "edits": {
            "WIND": [],
            "STUDY-1": [("F2_JM", 1, 6, "1.0e9"), ("K2_3", 4, 6, "1.0e7")],
            "STUDY-2": [("F2_JM", 1, 6, "1.0e11"), ("K2_3", 4, 6, "4.0e10")],
            "FLOORS": [(f"F{k}_J1", 4, 6, "1.0e6") for k in range(1, FLOORS + 1)],
            "RELEASE": [("F3_J2", 4, 6, "0.0"), ("F2_J3", 1, 3, "5.0e8")],
        },
        "runs": [("levels_umfpack", ["--condense", "yes", "--levels", "yes", "--solver", "umfpack"]),
                 ("flat_lapack", ["--condense", "yes", "--levels", "no", "--solver", "lapack"]),
                 ("monolithic_cholmod", ["--condense", "no", "--solver", "cholmod"])],
    },
}


def nested_deck(text, sc):
    """The generated deck with the scenario's part contact (g = 0) in FLOOR and its steps (each a copy of
    WIND with its cards)."""
    if sc["part_contact"]:
        name, a, b, na, nb, dofs = sc["part_contact"]
        text = text.replace("*END PART\n*PART, NAME=BUILDING", f"*CONTACT, NAME={name}, MASTER={a}, SLAVE={b}\n"
                            f"{a}.{na}, {b}.{nb}, {dofs}, 0.0\n*END PART\n*PART, NAME=BUILDING")
    body = re.search(r"\*STEP, NAME=WIND\n(.*?)\*END STEP\n?", text, re.S).group(1)
    steps = [f"*STEP, NAME={name}\n{body}" + "\n".join(cards) + "\n*END STEP\n"
             for name, cards in sc["changes"].items()]
    return text.rstrip("\n") + "\n" + "".join(steps)


def explicit_deck(text, sc, edits):
    """The explicit deck with the scenario's part contact after each floor's contacts (the order of the
    unfolded nested deck) and the g of the contact lines of edits replaced."""
    if sc["part_contact"]:
        name, a, b, na, nb, dofs = sc["part_contact"]
        for k in range(1, FLOORS + 1):
            after = f"*CONTACT, NAME=F{k + 1}_J1," if k < FLOORS else "*CONTACT, NAME=K1_1,"
            text = text.replace(after, f"*CONTACT, NAME=F{k}_{name}, MASTER=F{k}_{a}, SLAVE=F{k}_{b}\n"
                                f"F{k}_{a}.{na}, F{k}_{b}.{nb}, {dofs}, 0.0\n{after}", 1)
    out, contact = [], None
    for line in text.split("\n"):
        if line.startswith("*"):
            m = re.match(r"\*CONTACT, NAME=([^,]+),", line)
            contact = m.group(1) if m else None
        elif contact:
            f = [x.strip() for x in line.split(",")]
            for name, first, last, g in edits:
                if name == contact and (int(f[2]), int(f[3])) == (first, last):
                    line = ", ".join(f[:4] + [g])
        out.append(line)
    return "\n".join(out)


def read_rows(path):
    """Header and rows of a CSV file, split into key (text and integer columns) and values (the columns of
    reals, the step first)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    real = [j for j in range(1, len(head)) if body and all(_is_number(r[j]) for r in body)
            and any(re.search(r"[.Ee]", r[j]) for r in body)]
    return head, real, [(tuple(r[j] for j in range(len(head)) if j not in real), [float(r[j]) for j in real])
                        for r in body]


def _is_number(s):
    try:
        float(s)
    except ValueError:
        return False
    return True


def compare_step(nested, ref, table, step):
    """Rows of step `step` of the nested run against the reference run's rows (its one step WIND):
    the same keys (released contact DOFs: rows of force 0 in the nested run only), values to 1e-10 of each
    column's largest reference value. Returns (ok, largest difference)."""
    head, real, rows = read_rows(os.path.join(nested, table))
    _, _, ref_rows = read_rows(os.path.join(ref, table))
    want = {k[1:]: v for k, v in ref_rows}
    got = {tuple(flat_names(x) for x in k[1:]): v for k, v in rows if k[0] == step}
    scale = [max([abs(v[i]) for v in want.values()] + [1e-300]) for i in range(len(real))]
    worst = 0.0
    for key, v in got.items():
        if key not in want:
            if table == "contact_forces.csv" and v[-1] == 0.0:
                continue   # a DOF this step releases
            print(f"FAIL: {table} {step}: row {key} not in the reference")
            return False, worst
        worst = max([worst] + [abs(a - b) / s for a, b, s in zip(v, want[key], scale)])
    missing = [k for k in want if k not in got]
    if missing:
        print(f"FAIL: {table} {step}: {len(missing)} reference rows missing, first {missing[0]}")
        return False, worst
    return worst <= 1e-10, worst


def twins(exe, work):
    """Two buildings B and C alike: C.F2's joint J1 changed in a step. By level and flat against the
    monolithic run; the floors of both buildings share 3 kinds until C.F2 has a joint of its own."""
    text = subprocess.run([sys.executable, GEN, *SCENARIOS["edge"]["build"]], stdout=subprocess.PIPE, text=True,
                          check=True).stdout
    text = text.replace("*INSTANCE, NAME=B, PART=BUILDING\n*END INSTANCE", "*INSTANCE, NAME=B, PART=BUILDING\n"
                        "*END INSTANCE\n*INSTANCE, NAME=C, PART=BUILDING\n20.0, 0.0, 0.0\n*END INSTANCE")
    supports = re.search(r"\*BOUNDARY\n(.*?)\*STEP", text, re.S).group(1)
    text = text.replace(supports, supports + supports.replace("B.F", "C.F"), 1)
    text = text.replace("*CLOAD\n", "*CLOAD\nC.F4.BAY4.21, 1, 1.0e5\n", 1)
    body = re.search(r"\*STEP, NAME=WIND\n(.*?)\*END STEP\n?", text, re.S).group(1)
    deck = os.path.join(work, "twins.deck")
    with open(deck, "w") as f:
        f.write(text.rstrip("\n") + f"\n*STEP, NAME=TWIN\n{body}*CHANGE CONTACT, NAME=C.F2.J1\n"
                "BAY1.E, BAY2.W, 1, 3, 1.0e8\n*END STEP\n")
    mono, _ = run(exe, deck, work, "twins_monolithic", "--condense", "no")
    ok = True
    listings = {}
    for name, opts in (("twins_levels", ["--levels", "yes"]), ("twins_flat", ["--levels", "no"])):
        out, listings[name] = run(exe, deck, work, name, "--condense", "yes", *opts)
        results = [numeric_compare(out, mono, table, names=lambda x: x) for table in TABLES]
        good = all(g for g, _ in results)
        print(f"{'ok' if good else 'FAIL'}: {name} against monolithic, largest difference "
              f"{max(w for _, w in results):.1e}")
        ok = ok and good
    with open(listings["twins_levels"]) as f:
        kinds = [int(k) for k in re.findall(r"condensation by level: 8 groups in (\d+) kinds", f.read())]
    split = len(kinds) == 2 and kinds[0] == 3 and kinds[1] > 3
    print(f"{'ok' if split else 'FAIL'}: by level, the 8 floors in 3 kinds, then C.F2 apart: kinds {kinds}")
    return 0 if ok and split else 1


def main(argv):
    if len(argv) not in (3, 4) or (len(argv) == 4 and argv[3] not in (*SCENARIOS, "twins")):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1:3]
    if len(argv) == 4 and argv[3] == "twins":
        os.makedirs(work, exist_ok=True)
        return twins(exe, work)
    sc = SCENARIOS[argv[3] if len(argv) == 4 else "edge"]
    os.makedirs(work, exist_ok=True)
    gen = lambda *more: subprocess.run([sys.executable, GEN, *sc["build"], *more], stdout=subprocess.PIPE,  # noqa
                                       text=True, check=True).stdout
    deck = os.path.join(work, "nested.deck")
    with open(deck, "w") as f:
        f.write(nested_deck(gen(), sc))
    explicit = gen("--explicit")
    refs = {}
    for step, edits in sc["edits"].items():
        path = os.path.join(work, f"explicit_{step}.deck")
        with open(path, "w") as f:
            f.write(explicit_deck(explicit, sc, edits))
        refs[step], _ = run(exe, path, work, f"ref_{step}", "--condense", "no")
    ok = True
    listings = {}
    for name, opts in sc["runs"]:
        out, listings[name] = run(exe, deck, work, name, *opts)
        good_run, worst_run = True, 0.0
        for step in sc["edits"]:
            for table in TABLES:
                good, worst = compare_step(out, refs[step], table, step)
                if not good:
                    print(f"FAIL: {name} {step} {table}: largest difference {worst:.1e}")
                good_run = good_run and good
                worst_run = max(worst_run, worst)
        print(f"{'ok' if good_run else 'FAIL'}: {name}: every step against its explicit deck edited by hand, "
              f"largest difference {worst_run:.1e}")
        ok = ok and good_run
    levels = [name for name, _ in sc["runs"] if name.startswith("levels")][0]
    with open(listings[levels]) as f:
        listing = f.read()
    wants = ["joint study (*CHANGE CONTACT): 5 sets of contact stiffnesses", "condensation by level: done"]
    if not sc["part_contact"]:
        # the middle floors alike (3 kinds) until one of them has a joint of its own (4 kinds)
        wants += [f"{FLOORS} groups in 3 kinds", f"{FLOORS} groups in 4 kinds"]
    for want in wants:
        found = want in listing
        print(f"{'ok' if found else 'FAIL'}: the listing by level has '{want}'")
        ok = ok and found
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
