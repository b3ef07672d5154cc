#!/usr/bin/env python3
"""Assembly-level sets over several instances are the union of their members, as in Abaqus.

usage: set_union.py SUPERJOIN WORKDIR

Abaqus/CAE writes an assembly set that spans instances as several cards of
one name (*NSET, NSET=LOADED, INSTANCE=A / *NSET, NSET=LOADED, INSTANCE=B);
named plainly at model level it is the union of the members, each in its own
instance. Two C3D8 blocks A and B (B turned and moved) and a third instance C
of another part that has a part-level node set LOADED of its own:

1. union: *BOUNDARY, *CLOAD, *DLOAD, *TEMPERATURE and *INITIAL CONDITIONS,
   TYPE=TEMPERATURE on plain ROOTS, LOADED,
   SKIN give the displacements (CSV, every node of every instance) of the
   same deck with each card written once per instance (A.ROOTS, B.ROOTS, ...),
   to 1e-12 relative to the largest; C (part set LOADED, not a member: the
   assembly's set wins) stays unloaded, so it moves by its temperature alone
   in neither deck (C has no temperature: zero displacement). A *DSLOAD on a
   *SURFACE of the union's elements gives the same.
   The same for a set over inner instances named by path (INSTANCE=B.F1.BAY2
   and B.F2.BAY2, parts made of parts), its members in card order.
2. requests: *NODE PRINT, NSET=LOADED and *EL PRINT, ELSET=SKIN list the
   members of both instances, in the order of the set cards (SKIN's card for
   B comes first: B's element 2, then A's 1 and 2 from GENERATE), the same
   rows as the scoped deck's requests; TOTALS= on a union is refused.
3. a part-level set of two instances named plainly stays ambiguous: the
   error names A.FAR and B.FAR, at the card's file:line, exit 1 (a load,
   without and with a substructure MAIN, and an output request).
4. cards whose members must lie in one substructure (*RIGID BODY, *TRANSFORM,
   a *COUPLING surface, a *TIE surface) refuse the union at the card's
   file:line ('spans 2 substructures'), exit 1, no traceback; a member
   instance of an undefined part gives its *INSTANCE message alone, one on
   an instance of a part made of parts only (no mesh) a message at its card.
"""
import csv
import os
import re
import subprocess
import sys

TOL = 1e-12

MATERIAL = """*MATERIAL, NAME=M
*ELASTIC
 1000.0, 0.3
*EXPANSION
 1.0e-3
"""

PART = """*PART, NAME={part}
*NODE
 1, 0.0, 0.0, 0.0
 2, 0.0, 0.0, 1.0
 3, 0.0, 1.0, 0.0
 4, 0.0, 1.0, 1.0
 5, 1.0, 0.0, 0.0
 6, 1.0, 0.0, 1.0
 7, 1.0, 1.0, 0.0
 8, 1.0, 1.0, 1.0
 9, 2.0, 0.0, 0.0
 10, 2.0, 0.0, 1.0
 11, 2.0, 1.0, 0.0
 12, 2.0, 1.0, 1.0
*ELEMENT, TYPE=C3D8, ELSET=BLOCK
 1, 1, 5, 7, 3, 2, 6, 8, 4
 2, 5, 9, 11, 7, 6, 10, 12, 8
*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
*NSET, NSET=ROOT
 1, 2, 3, 4
*NSET, NSET=FAR
 9, 10, 11, 12
{extra}*END PART
"""


def model(with_c=True, with_main=False):
    """Parts BLK (and BLK2, whose part set LOADED is not the assembly's), the assembly's sets;
    with_main: a node of the assembly's own (substructure MAIN, which has no set LOADED)."""
    text = MATERIAL + PART.format(part="BLK", extra="")
    if with_c:
        text += PART.format(part="BLK2", extra="*NSET, NSET=LOADED\n 9, 11\n")
    text += """*ASSEMBLY, NAME=PAIR
*INSTANCE, NAME=A, PART=BLK
*END INSTANCE
*INSTANCE, NAME=B, PART=BLK
 0.5, 4.0, -1.0
 0.0, 0.0, 0.0, 0.2, 0.3, 1.0, 30.0
*END INSTANCE
"""
    if with_c:
        text += "*INSTANCE, NAME=C, PART=BLK2\n 0.0, -4.0, 0.0\n*END INSTANCE\n"
    if with_main:
        text += "*NODE\n 100, 5.0, 5.0, 5.0\n"
    text += """*NSET, NSET=ROOTS, INSTANCE=A
 1, 2, 3, 4
*NSET, NSET=ROOTS, INSTANCE=B
 1, 2, 3, 4
*NSET, NSET=LOADED, INSTANCE=A
 10, 12
*NSET, NSET=LOADED, INSTANCE=B
 11
*ELSET, ELSET=SKIN, INSTANCE=B
 2
*ELSET, ELSET=SKIN, INSTANCE=A, GENERATE
 1, 2, 1
*END ASSEMBLY
"""
    if with_c:
        text += "*BOUNDARY\n C.ROOT, ENCASTRE\n"
    if with_main:
        text += "*BOUNDARY\n 100, ENCASTRE\n"
    return text


NESTED = """*MATERIAL, NAME=STEEL
*ELASTIC
2.1e11, 0.3
*PART, NAME=BAY
*NODE
1, 0.0, 0.0
2, 1.0, 0.0
*ELEMENT, TYPE=B23, ELSET=E
1, 1, 2
*BEAM SECTION, ELSET=E, MATERIAL=STEEL
1.0e-3, 1.0e-6
*END PART
*PART, NAME=FLOOR
*INSTANCE, NAME=BAY1, PART=BAY
*END INSTANCE
*INSTANCE, NAME=BAY2, PART=BAY
1.0, 0.0, 0.0
*END INSTANCE
*CONTACT, NAME=J, MASTER=BAY1, SLAVE=BAY2
BAY1.2, BAY2.1, 1, 6, RIGID
*END PART
*PART, NAME=BUILDING
*INSTANCE, NAME=F1, PART=FLOOR
*END INSTANCE
*INSTANCE, NAME=F2, PART=FLOOR
2.0, 0.0, 0.0
*END INSTANCE
*CONTACT, NAME=K, MASTER=F1.BAY2, SLAVE=F2.BAY1
F1.BAY2.2, F2.BAY1.1, 1, 6, RIGID
*END PART
*ASSEMBLY
*INSTANCE, NAME=B, PART=BUILDING
*END INSTANCE
*NSET, NSET=BASE, INSTANCE=B.F1.BAY1
1
*NSET, NSET=PAIR, INSTANCE=B.F1.BAY2
2
*NSET, NSET=PAIR, INSTANCE=B.F2.BAY2
2
*END ASSEMBLY
*BOUNDARY
BASE, ENCASTRE
*STEP
*CLOAD
{loads}*NODE PRINT, NSET=PAIR
U
*END STEP
"""


def cards(scoped):
    """Boundary, loads and requests on the union (plain names) or per instance."""
    def each(name, rest, order=("A", "B")):
        if scoped:
            return "".join(f" {i}.{name}{rest}\n" for i in order)
        return f" {name}{rest}\n"
    text = "*BOUNDARY\n" + each("ROOTS", ", ENCASTRE")
    text += "*INITIAL CONDITIONS, TYPE=TEMPERATURE\n" + each("LOADED", ", 10.0")
    text += "*STEP\n*STATIC\n*CLOAD\n" + each("LOADED", ", 2, -10.0")
    text += "*DLOAD\n" + each("SKIN", ", P2, 5.0", ("B", "A"))
    text += "*TEMPERATURE\n" + each("LOADED", ", 40.0")
    if scoped:
        text += "*NODE PRINT, NSET=A.LOADED\nU\n*NODE PRINT, NSET=B.LOADED\nU\n"
        text += "*EL PRINT, ELSET=B.SKIN\nS\n*EL PRINT, ELSET=A.SKIN\nS\n"
    else:
        text += "*NODE PRINT, NSET=LOADED\nU\n*EL PRINT, ELSET=SKIN\nS\n"
    return text + "*END STEP\n"


def run(exe, work, name, text, want_ok=True, csv_dir=False):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(text)
    lst = os.path.join(work, name + ".lst")
    args = [exe, "-q", path, "-o", lst]
    if csv_dir:
        args += ["--csv", os.path.join(work, name)]
    r = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, timeout=120)
    if want_ok and r.returncode != 0:
        sys.exit(f"FAIL: {name}: exit {r.returncode}\n{r.stderr}")
    if not want_ok:
        return r
    with open(lst) as f:
        return f.read()


def displacements(work, name):
    """{(substructure, node): [u1..u6]} from the CSV (one step)."""
    out = {}
    with open(os.path.join(work, name, "displacements.csv")) as f:
        rows = list(csv.reader(f))
    head = [h.strip().lower() for h in rows[0]]
    isub = next(i for i, h in enumerate(head) if h.startswith("sub"))
    inode = next(i for i, h in enumerate(head) if h == "node")
    for row in rows[1:]:
        vals = []
        for i, x in enumerate(row):
            if i in (isub, inode) or head[i] == "step":
                continue
            try:
                vals.append(float(x))
            except ValueError:
                pass
        out[(row[isub].strip(), row[inode].strip())] = vals
    return out


NUMBER = re.compile(r"-?\d\.\d{6}E[+-]\d{3}")


def request_rows(text):
    """(substructure, id, numbers) of every row of the REQUESTED OUTPUT section, in order."""
    body = text.split("REQUESTED OUTPUT", 1)[1].split("\n=====", 1)[0]
    rows = []
    for line in body.splitlines():
        f = line.split()
        if len(f) > 2 and f[0] in ("A", "B", "C") and NUMBER.search(line):
            rows.append((f[0], f[1], [float(x) for x in NUMBER.findall(line)]))
    return rows


def check_error(r, name, pattern):
    err = r.stderr
    if r.returncode != 1 or "Traceback" in err or "Error termination" in err:
        sys.exit(f"FAIL: {name}: exit {r.returncode}, stderr:\n{err}")
    if not re.search(pattern, err):
        sys.exit(f"FAIL: {name}: no message matching {pattern!r} in:\n{err}")
    print(f"ok   {name}: {err.strip().splitlines()[0]}")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)

    # 1. the union's loads and supports are those of the per-instance cards (without and
    # with a substructure MAIN, which a plain name is looked for in first)
    for tag, main in (("", False), ("_main", True)):
        plain = run(exe, work, "union" + tag, model(with_main=main) + cards(False), csv_dir=True)
        scoped = run(exe, work, "scoped" + tag, model(with_main=main) + cards(True), csv_dir=True)
        du, ds = displacements(work, "union" + tag), displacements(work, "scoped" + tag)
        if sorted(du) != sorted(ds) or not du:
            sys.exit("FAIL: the two decks' displacement tables have different nodes")
        scale = max(abs(v) for vals in ds.values() for v in vals)
        worst = max(abs(a - b) for k in ds for a, b in zip(du[k], ds[k])) / scale
        print(f"ok   union{tag} against per-instance cards: {len(du)} nodes, largest difference {worst:.1e} "
              "of the largest value")
        if worst > TOL or scale == 0.0:
            sys.exit(f"FAIL: displacements differ by {worst:.3e} (relative; tolerance {TOL})")
        # every member moved, the supports held, C (its own part set LOADED) untouched
        for inst in ("A", "B"):
            if max(abs(v) for v in du[(inst, "12")]) == 0.0:
                sys.exit(f"FAIL: instance {inst} did not move: the union missed it")
            if max(abs(v) for v in du[(inst, "1")]) != 0.0:
                sys.exit(f"FAIL: {inst}.1 moved: the *BOUNDARY on the union missed it")
        if max(abs(v) for n in range(1, 13) for v in du[("C", str(n))]) != 0.0:
            sys.exit("FAIL: instance C moved: its part set LOADED was taken for the assembly's")

    # *DSLOAD on a surface of the union's elements: the *DLOAD's loads
    deck = (model() + cards(False)).replace("*BOUNDARY\n ROOTS", "*SURFACE, NAME=SS\n SKIN, S2\n*BOUNDARY\n ROOTS")
    run(exe, work, "dsload", deck.replace("*DLOAD\n SKIN, P2, 5.0", "*DSLOAD\n SS, P, 5.0"), csv_dir=True)
    dd = displacements(work, "dsload")
    ds = displacements(work, "scoped")
    worst = max(abs(a - b) for k in ds for a, b in zip(dd[k], ds[k])) / max(abs(v) for vals in ds.values() for v in vals)
    print(f"ok   *DSLOAD on a surface of the union: largest difference {worst:.1e}")
    if sorted(dd) != sorted(ds) or worst > TOL:
        sys.exit(f"FAIL: *DSLOAD on the union's surface differs by {worst:.3e}")

    # 1b. a set over inner instances by path (INSTANCE=B.F1.BAY2, B.F2.BAY2): the same
    nested = run(exe, work, "nested", NESTED.format(loads="PAIR, 2, -1000.0\n"), csv_dir=True)
    run(exe, work, "nested_scoped", NESTED.format(loads="B.F1.BAY2.PAIR, 2, -1000.0\nB.F2.BAY2.PAIR, 2, -1000.0\n"),
        csv_dir=True)
    du, ds = displacements(work, "nested"), displacements(work, "nested_scoped")
    scale = max(abs(v) for vals in ds.values() for v in vals)
    worst = max(abs(a - b) for k in ds for a, b in zip(du[k], ds[k])) / scale
    body = nested.split("REQUESTED OUTPUT", 1)[1].split("\n=====", 1)[0]
    rows = [line.split()[:2] for line in body.splitlines() if line.strip().startswith("B.F")]
    print(f"ok   nested: {len(du)} nodes, largest difference {worst:.1e}; *NODE PRINT rows {rows}")
    if sorted(du) != sorted(ds) or worst > TOL or scale == 0.0:
        sys.exit(f"FAIL: nested union: displacements differ by {worst:.3e}")
    if rows != [["B.F1.BAY2", "2"], ["B.F2.BAY2", "2"]]:
        sys.exit("FAIL: nested union: *NODE PRINT, NSET=PAIR does not list B.F1.BAY2.2 then B.F2.BAY2.2 (card order)")

    # 2. the requests list both instances, in the order of the set cards
    ru, rs = request_rows(plain), request_rows(scoped)
    order = [(s, i) for s, i, _ in ru]
    nodes = [k for k in order if k in (("A", "10"), ("A", "12"), ("B", "11"))]
    if nodes != [("A", "10"), ("A", "12"), ("B", "11")]:
        sys.exit(f"FAIL: *NODE PRINT, NSET=LOADED lists {nodes}, not A.10, A.12, B.11")
    elems = []
    for k in order[3:]:
        if not elems or elems[-1] != k:
            elems.append(k)
    if elems != [("B", "2"), ("A", "1"), ("A", "2")]:
        sys.exit(f"FAIL: *EL PRINT, ELSET=SKIN lists {elems}, not B.2 then A.1, A.2 (card order)")
    if [(s, i) for s, i, _ in rs] != order:
        sys.exit("FAIL: the union's request rows are not those of the per-instance requests")
    worst = max(abs(a - b) / max(1.0, max(abs(x) for x in vb))
                for (_, _, va), (_, _, vb) in zip(ru, rs) for a, b in zip(va, vb))
    if worst > TOL:
        sys.exit(f"FAIL: the request rows differ by {worst:.3e}")
    print(f"ok   requests: nodes {nodes}, elements {elems} (card order), rows as the scoped requests'")
    deck = model() + cards(False).replace("*NODE PRINT, NSET=LOADED", "*NODE PRINT, NSET=LOADED, TOTALS=YES")
    r = run(exe, work, "totals", deck, want_ok=False)
    check_error(r, "totals", r"totals\.deck:\d+: error: TOTALS= of \*NODE PRINT over node set LOADED, which spans 2")

    # 3. a part-level set of two instances named plainly: still ambiguous
    deck = model(with_c=False) + cards(False).replace("*CLOAD\n LOADED", "*CLOAD\n FAR")
    line = deck.splitlines().index(" FAR, 2, -10.0") + 1
    r = run(exe, work, "part_set", deck, want_ok=False)
    check_error(r, "part_set", rf"part_set\.deck:{line}: error: node FAR is not in a substructure.*"
                r"FAR is a set of each of the instances A, B, kept apart: name the ones meant, A\.FAR and B\.FAR")
    deck = model(with_c=False, with_main=True) + cards(False).replace("*CLOAD\n LOADED", "*CLOAD\n FAR")
    line = deck.splitlines().index(" FAR, 2, -10.0") + 1
    r = run(exe, work, "part_set_main", deck, want_ok=False)
    check_error(r, "part_set_main", rf"part_set_main\.deck:{line}: error: unknown node set FAR in substructure MAIN "
                r"\(FAR is a set of each of the instances A, B, kept apart: name the ones meant, A\.FAR and B\.FAR\)")
    deck = model(with_c=False) + cards(False).replace("NSET=LOADED", "NSET=FAR")
    line = deck.splitlines().index("*NODE PRINT, NSET=FAR") + 1
    r = run(exe, work, "part_set_request", deck, want_ok=False)
    check_error(r, "part_set_request", rf"part_set_request\.deck:{line}: error: unknown node set FAR \(NSET= of "
                r"\*NODE PRINT.*A\.FAR and B\.FAR")

    # 4. cards whose members must lie in one substructure refuse the union
    single = {
        "rigid": "*RIGID BODY, NSET=LOADED, REF NODE=A.1\n",
        "transform": "*TRANSFORM, NSET=LOADED\n 0., 1., 0., -1., 0., 0.\n",
        "coupling": "*SURFACE, NAME=SS\n SKIN, S4\n*COUPLING, REF NODE=A.1, SURFACE=SS, CONSTRAINT NAME=C1\n"
                    "*KINEMATIC\n",
        "tie": "*SURFACE, NAME=SS\n SKIN, S4\n*SURFACE, NAME=TT\n A.BLOCK, S6\n*TIE, NAME=T1\n SS, TT\n",
    }
    for name, card in single.items():
        deck = model(with_c=False) + card + cards(False)
        line = deck.splitlines().index(card.splitlines()[0]) + 1   # the card (its *SURFACE for a surface)
        r = run(exe, work, name, deck, want_ok=False)
        what = "node set LOADED" if name in ("rigid", "transform") else "element set SKIN"
        check_error(r, name, rf"{name}\.deck:{line}: error: {what} spans 2 substructures \((A, B|B, A): an "
                    r"assembly-level set over several instances\)")
    # an instance of an undefined part among the members: its *INSTANCE error is the one message
    deck = model(with_c=False).replace("*INSTANCE, NAME=B, PART=BLK", "*INSTANCE, NAME=B, PART=NOPE") + cards(False)
    r = run(exe, work, "broken", deck, want_ok=False)
    check_error(r, "broken", r"broken\.deck:\d+: error: \*INSTANCE B of undefined part NOPE")
    if r.stderr.count("error:") != 1:
        sys.exit(f"FAIL: broken: more than the one message:\n{r.stderr}")
    # a member on an instance of a part made of parts only (INSTANCE=B: no mesh of its own):
    # one message at its card, not a union that silently lacks it
    deck = NESTED.format(loads="PAIR, 2, -1000.0\n").replace("INSTANCE=B.F2.BAY2", "INSTANCE=B")
    line = deck.splitlines().index("*NSET, NSET=PAIR, INSTANCE=B") + 1
    r = run(exe, work, "meshless", deck, want_ok=False)
    check_error(r, "meshless", rf"meshless\.deck:{line}: error: INSTANCE=B of \*NSET names an instance of part "
                r"BUILDING, which is made of parts only")
    if r.stderr.count("error:") != 1:
        sys.exit(f"FAIL: meshless: more than the one message:\n{r.stderr}")
    # a part made of parts with a set of its own (its entry is no instance): not taken for one
    deck = NESTED.format(loads="PAIR, 2, -1000.0\n").replace("*END PART\n*ASSEMBLY", "*ELSET, ELSET=Q\n1\n*END PART\n*ASSEMBLY")
    r = run(exe, work, "part_of_parts_set", deck, want_ok=False)
    if r.returncode not in (0, 1) or "signal" in r.stderr or "Traceback" in r.stderr:
        sys.exit(f"FAIL: part_of_parts_set: exit {r.returncode}\n{r.stderr}")
    print(f"ok   part_of_parts_set: exit {r.returncode}, no crash")
    print("PASS")


if __name__ == "__main__":
    main()
