#!/usr/bin/env python3
"""The 10-storey frame of decks/storeys.deck, written out explicitly.

usage: storeys.py SUPERJOIN DECKS_DIR WORKDIR

decks/storeys.deck builds the frame from one *PART (a storey: four B33 columns,
four B33 beams, one T3D2 brace) and ten *INSTANCE cards, translated up and
turned by 0, 90, 180 or 270 degrees about the vertical axis through the middle
of the plan, joined storey to storey by contacts (some PAIR=NEAREST).

This script writes the same structure without parts (storeys_explicit.deck):
ten *SUBSTRUCTURE blocks whose coordinates are placed here (x' = a + R (x + t - a),
Abaqus's order: translation, then rotation about the axis through a and b), with
the beam orientation vectors turned explicitly (the part's default v, global Z
or global X for the columns, becomes R Z or R X), and every contact pair written
node by node. Both decks are solved and every CSV file must agree to 1e-10
(relative to the largest magnitude of each column).
"""
import csv
import os
import subprocess
import sys

H = 3.0
PLAN = 4.0
CENTER = (2.0, 2.0)
NODES = {1: (0, 0, 0), 2: (PLAN, 0, 0), 3: (PLAN, PLAN, 0), 4: (0, PLAN, 0),
         5: (0, 0, H), 6: (PLAN, 0, H), 7: (PLAN, PLAN, H), 8: (0, PLAN, H)}
COLUMNS = {1: (1, 5), 2: (2, 6), 3: (3, 7), 4: (4, 8)}
BEAMS_DEFAULT = {5: (5, 6), 6: (6, 7)}
BEAMS_V = {7: (7, 8), 8: (8, 5)}
V_BEAMS = (1.0, 1.0, 0.5)
BRACE = {9: (1, 6)}
ANGLES = [None, 90, 180, 270, 0, 90, 180, 270, 0, 90]   # None: no rotation line
NEAREST = {2, 4, 6, 8}   # joints below these storeys use PAIR=NEAREST in decks/storeys.deck
G_ROT = 4.0e7


def rot_z(deg):
    """Quarter turns about +Z, exact."""
    q = (deg // 90) % 4
    c, s = [(1, 0), (0, 1), (-1, 0), (0, -1)][q]
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


def apply(r, v):
    return tuple(sum(r[i][j] * v[j] for j in range(3)) for i in range(3))


def place(k, x):
    """Storey k (1-based): translation (0, 0, (k-1) H), then the rotation about the axis through CENTER."""
    t = (0.0, 0.0, (k - 1) * H)
    a = (CENTER[0], CENTER[1], 0.0)
    r = rot_z(ANGLES[k - 1] or 0)
    y = tuple(x[i] + t[i] - a[i] for i in range(3))
    y = apply(r, y)
    return tuple(a[i] + y[i] for i in range(3))


def fmt(v):
    return repr(float(v))


def pairs(k):
    """Top nodes of storey k against the bottom nodes of storey k+1 at the same point."""
    out = []
    for m in (5, 6, 7, 8):
        pm = place(k, NODES[m])
        for s in (1, 2, 3, 4):
            ps = place(k + 1, NODES[s])
            if max(abs(pm[i] - ps[i]) for i in range(3)) < 1e-9:
                out.append((m, s))
    assert len(out) == 4, out
    return out


def explicit_deck():
    out = ["*HEADING", "10-storey frame written out explicitly (tests/parts/storeys.py)",
           "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e11, 0.3"]
    for k in range(1, 11):
        r = rot_z(ANGLES[k - 1] or 0)
        out.append(f"*SUBSTRUCTURE, NAME=S{k}")
        out.append("*NODE")
        for n, x in NODES.items():
            p = place(k, x)
            out.append(f"{n}, {fmt(p[0])}, {fmt(p[1])}, {fmt(p[2])}")
        out.append("*NSET, NSET=BOT")
        out.append("1, 2, 3, 4")
        out.append("*NSET, NSET=TOP")
        out.append("5, 6, 7, 8")
        for name, elems in (("COLS", COLUMNS), ("BEAMSD", BEAMS_DEFAULT), ("BEAMSV", BEAMS_V)):
            out.append(f"*ELEMENT, TYPE=B33, ELSET={name}")
            for e, (a, b) in elems.items():
                out.append(f"{e}, {a}, {b}")
        out.append("*ELEMENT, TYPE=T3D2, ELSET=BRACE")
        for e, (a, b) in BRACE.items():
            out.append(f"{e}, {a}, {b}")
        for name, v in (("COLS", (1, 0, 0)), ("BEAMSD", (0, 0, 1)), ("BEAMSV", V_BEAMS)):
            rv = apply(r, v)
            out.append(f"*BEAM SECTION, ELSET={name}, MATERIAL=STEEL")
            out.append("0.01, 2.0e-5, 8.0e-5, 1.0e-5")
            out.append(f"{fmt(rv[0])}, {fmt(rv[1])}, {fmt(rv[2])}")
        out.append("*SOLID SECTION, ELSET=BRACE, MATERIAL=STEEL")
        out.append("5.0e-4")
        out.append("*END SUBSTRUCTURE")
    for k in range(1, 10):
        out.append(f"*CONTACT, NAME=J{k}, MASTER=S{k}, SLAVE=S{k + 1}")
        for m, s in pairs(k):
            out.append(f"{m}, {s}, 1, 3, RIGID")
            out.append(f"{m}, {s}, 4, 6, {G_ROT}")
    out += ["*BOUNDARY", "S1.BOT, ENCASTRE",
            "*STEP, NAME=WIND", "*CLOAD", "S10.5, 1, 1.0e4", "S10.7, 2, 5.0e3", "S5.6, 3, -2.0e4",
            "S7.8, 1, -3.0e3", "*DLOAD", "S3.5, PY, 1.5e3", "*END STEP",
            "*STEP, NAME=TWIST", "*CLOAD", "S10.5, 6, 2.0e4", "S4.7, 4, 1.0e3", "*END STEP"]
    return "\n".join(out) + "\n"


def run(exe, deck, work, name):
    csvdir = os.path.join(work, name)
    r = subprocess.run([exe, "-q", deck, "-o", os.path.join(work, name + ".lst"), "--csv", csvdir],
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: {deck}: exit status {r.returncode}\n{r.stderr}")
        sys.exit(1)
    return csvdir


def read(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))


KEYS = ("step", "substructure", "contact", "node", "master_node", "slave_node", "element", "type", "end", "dof")


def compare(a, b, table):
    """Rows are matched by their key columns (PAIR=NEAREST lists a contact's
    pairs in the order of the slave set, the explicit deck in its own order)."""
    ra, rb = read(os.path.join(a, table)), read(os.path.join(b, table))
    keys = [j for j, name in enumerate(ra[0]) if name in KEYS]

    def order(rows):
        return rows[:1] + sorted(rows[1:], key=lambda r: [r[j].upper() for j in keys])
    ra, rb = order(ra), order(rb)
    if ra[0] != rb[0] or len(ra) != len(rb):
        print(f"FAIL: {table}: header or row count differ ({len(ra)} against {len(rb)})")
        return False, 0.0
    ncol = len(ra[0])
    numeric = []
    for j in range(ncol):
        try:
            [float(row[j]) for row in ra[1:]]
            numeric.append(j)
        except ValueError:
            pass
    worst = 0.0
    ok = True
    scale = {j: max([abs(float(row[j])) for row in ra[1:]] + [1e-300]) for j in numeric}
    for ia, (x, y) in enumerate(zip(ra[1:], rb[1:]), 2):
        for j in range(ncol):
            if j in numeric and j not in keys:
                d = abs(float(x[j]) - float(y[j])) / scale[j]
                worst = max(worst, d)
                if d > 1e-10:
                    if ok:
                        print(f"FAIL: {table} row {ia} {ra[0][j]}: {x[j]} against {y[j]}")
                    ok = False
            elif x[j].upper() != y[j].upper():
                if ok:
                    print(f"FAIL: {table} row {ia} {ra[0][j]}: {x[j]} against {y[j]}")
                ok = False
    return ok, worst


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, decks, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    explicit = os.path.join(work, "storeys_explicit.deck")
    with open(explicit, "w") as f:
        f.write(explicit_deck())
    a = run(exe, os.path.join(decks, "storeys.deck"), work, "parts")
    b = run(exe, explicit, work, "explicit")
    ok = True
    for table in ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv"):
        good, worst = compare(a, b, table)
        print(f"{'ok' if good else 'FAIL'}: {table}: largest difference {worst:.1e} of the column's largest value")
        ok = ok and good
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
