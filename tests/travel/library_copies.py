#!/usr/bin/env python3
"""The condensation library and translated copies (issue 26, --library DIR
with --twins, the default).

A run condenses one part of each group of identical parts and shares it
(src/substructure/twins.f90); the library stores that part's entry, and a
pointer file <copy key>.<n>.sjg to it. A later run whose representative of
the group is another member (the first one changed) finds the entry through
the pointer (src/substructure/library.f90, find_copy). The model: a row of
solid blocks (C3D8) joined at the corners of their facing faces; B1..B3 are
translated copies (B4, loaded where the others are joined, is not).

1. first run: B1 and B4 condensed and stored, one pointer each; the same
   deck again: both loaded, no pointer added; B1's entry damaged: B1
   condensed and stored again, still one pointer.
2. B1's material changed: B1 condensed, B2 loaded from B1's old entry ("the
   entry of a translated copy", its key the old B1's), B4 loaded; results
   equal those of a run with a fresh library to round-off (RTOL).
3. not taken: B2 no longer a translation of the old B1 (one node moved by
   1e-7 of the block), --twins no, --library-verify, a pointer whose
   coordinates are moved as a whole (no longer those of its entry's part:
   its key, recomputed, does not match; nothing is said of it) and a
   truncated pointer: B2 condensed and stored each time, results as before.
4. a translated copy with loads its entry has not seen: condensed anew and
   stored under its own key; that entry damaged: replaced (the copy's entry
   is not taken in its place).
5. the whole deck moved: every part a translated copy of its old self; the
   same with axisymmetric elements (CAX4: the radius is x) and with material
   axes about a cylinder's axis: no copy taken (no pointer written at all),
   condensed anew, results equal a fresh library's to round-off.

usage: library_copies.py SUPERJOIN WORKDIR
"""
import glob
import os
import re
import shutil
import struct
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import equiv  # noqa: E402

RTOL = 1e-10
FAILED = []
MESH = 3
KEY = 64
POINTER_HEAD = 8 + 8 + 2 * KEY + 8 + 24   # magic, version, copy key, entry key, node count, extents


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        FAILED.append(what)


def blocks(nb=4, x0=0.0, e1=2.1e11, moved=None, load_b2=False, kind="C3D8"):
    """NB blocks of MESH^3 C3D8 (kind CAX4: MESH^2 squares in the XY plane;
    kind CYL: C3D8 of an orthotropic material about the axis x = y = 0) in
    a row from x0; the first of Young's modulus e1; moved = (block, node,
    dx): one node of one block moved along x."""
    m = MESH
    n1 = m + 1
    h = 1.0 / m
    flat = kind == "CAX4"

    def nid(i, j, k=0):
        return 1 + i + n1 * (j + n1 * k)

    out = ["*HEADING", f"library copies: {nb} blocks ({kind})"]
    for b in range(nb):
        out += [f"*MATERIAL, NAME=M{b + 1}"]
        if kind == "CYL":
            e = e1 if b == 0 else 2.1e11
            out += ["*ELASTIC, TYPE=ENGINEERING CONSTANTS",
                    f"{e:.6g}, {e / 2:.6g}, {e / 3:.6g}, 0.3, 0.25, 0.2, 8e10, 7e10,", "6e10"]
        else:
            out += ["*ELASTIC", f"{e1 if b == 0 else 2.1e11:.6g}, 0.3"]
    if kind == "CYL":
        out += ["*ORIENTATION, NAME=CYL, SYSTEM=CYLINDRICAL", "0, 0, 0, 0, 0, 1"]
    corners = [(0, 0), (m, 0)] if flat else [(j, k) for j in (0, m) for k in (0, m)]
    left = [nid(0, j, k) for j, k in corners]
    right = [nid(m, j, k) for j, k in corners]
    for b in range(nb):
        out += [f"*SUBSTRUCTURE, NAME=B{b + 1}", "*NODE"]
        for k in range(1 if flat else n1):
            for j in range(n1):
                for i in range(n1):
                    x = x0 + b + i * h
                    if moved and moved[0] == b + 1 and moved[1] == nid(i, j, k):
                        x += moved[2]
                    out.append(f"{nid(i, j, k)}, {x!r}, {j * h!r}, {k * h!r}")
        out.append(f"*ELEMENT, TYPE={'CAX4' if flat else 'C3D8'}, ELSET=ALL")
        e = 0
        for k in range(1 if flat else m):
            for j in range(m):
                for i in range(m):
                    e += 1
                    c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k)]
                    if not flat:
                        c += [nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                    out.append(f"{e}, " + ", ".join(map(str, c)))
        out += ["*NSET, NSET=LEFT", ", ".join(map(str, left)), "*NSET, NSET=RIGHT", ", ".join(map(str, right)),
                f"*NSET, NSET=MID", str(nid(m // 2 + 1, 1, 0 if flat else 1))]
        orient = ", ORIENTATION=CYL" if kind == "CYL" else ""
        out += [f"*SOLID SECTION, ELSET=ALL, MATERIAL=M{b + 1}{orient}"]
        out += ["1.0"] if flat else []
        out += ["*END SUBSTRUCTURE"]
    dofs = "1, 2" if flat else "1, 3"
    for b in range(nb - 1):
        out += [f"*CONTACT, NAME=J{b + 1}, MASTER=B{b + 1}, SLAVE=B{b + 2}", f"RIGHT, LEFT, {dofs}, 1e9"]
    out += ["*SUPPORT", f"B1.LEFT, {dofs}", "*STEP, NAME=PULL", "*CLOAD", f"B{nb}.RIGHT, 1, 1000",
            f"B{nb}.RIGHT, 2, 200"]
    if load_b2:
        out += ["B2.MID, 2, 50"]
    out += ["*END STEP"]
    return "\n".join(out) + "\n"


def run(binary, work, name, text, lib, *extra):
    deck = os.path.join(work, name + ".deck")
    with open(deck, "w") as fh:
        fh.write(text)
    lst = os.path.join(work, name + ".lst")
    csv = os.path.join(work, name + ".csv")
    cmd = [binary, "-q", "--condense", "yes", deck, "-o", lst, "--csv", csv, "--library", lib] + list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print(f"FAIL: {name} exited with {p.returncode}: {p.stderr.strip()[:400]}")
        sys.exit(1)
    with open(lst) as fh:
        notes = [line.strip() for line in fh if "library:" in line]
    return notes, csv


def said(notes, part, text):
    return any(f"substructure {part} " in n and text in n for n in notes)


def copied(notes):
    return [n for n in notes if "translated copy" in n]


def key_of(notes, part):
    for n in notes:
        m = re.search(rf"substructure {part} .*\(key ([0-9a-f]{{64}})\)", n)
        if m:
            return m.group(1)
    return None


def close(a, b):
    files = sorted(os.listdir(a))
    if files != sorted(os.listdir(b)):
        return False
    worst = 0.0
    for f in files:
        w, msg = equiv.compare_file(os.path.join(a, f), os.path.join(b, f), RTOL, 0.0)
        if msg:
            print(f"  {f}: {msg}")
            return False
        worst = max(worst, w)
    print(f"  largest scaled difference {worst:.2e}")
    return True


def pointers(lib):
    return sorted(glob.glob(os.path.join(lib, "*.sjg")))


def main():
    binary, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    lib = os.path.join(work, "lib")
    study, changed = blocks(), blocks(e1=2.0e11)

    # 1. the first run, and the same again
    a, _ = run(binary, work, "first", study, lib)
    check(said(a, "B1", "condensed and stored") and said(a, "B4", "condensed and stored") and len(a) == 2,
          "first run: B1 and B4 condensed and stored (B2, B3 share B1's condensation)")
    ptrs = pointers(lib)
    check(len(ptrs) == 2, f"one pointer per stored entry ({len(ptrs)})")
    again, _ = run(binary, work, "again", study, lib)
    check(said(again, "B1", "loaded from library") and said(again, "B4", "loaded from library")
          and not copied(again), "the same deck again: B1 and B4 loaded by their own keys")
    check(pointers(lib) == ptrs, "no pointer added by a run that loads")
    old_b1 = key_of(a, "B1")

    # 2. B1 changed: B2 represents the copies and takes the old B1's entry
    snapshot = os.path.join(work, "lib_first")
    shutil.copytree(lib, snapshot)

    def from_first(name):
        d = os.path.join(work, "lib_" + name)
        shutil.copytree(snapshot, d)
        return d

    c, c_csv = run(binary, work, "changed", changed, from_first("changed"))
    check(said(c, "B1", "condensed and stored") and said(c, "B4", "loaded from library"),
          "B1 changed: B1 condensed, B4 loaded")
    check(said(c, "B2", "the entry of a translated copy") and key_of(c, "B2") == old_b1,
          "B2 loaded from the old B1's entry, found through its pointer")
    _, f_csv = run(binary, work, "fresh", changed, os.path.join(work, "lib_fresh"))
    check(close(c_csv, f_csv), f"results equal a fresh library's to {RTOL:g}")

    damaged = from_first("damaged")
    entry = os.path.join(damaged, old_b1 + ".sjc")
    data = bytearray(open(entry, "rb").read())
    data[300] ^= 1
    with open(entry, "wb") as fh:
        fh.write(bytes(data))
    n, _ = run(binary, work, "damaged", study, damaged)
    names = [os.path.basename(p) for p in pointers(snapshot)]
    check(said(n, "B1", "condensed and stored") and any("not used" in x for x in n)
          and [os.path.basename(p) for p in pointers(damaged)] == names,
          "a damaged entry condensed anew and stored again keeps its one pointer")

    # a library that cannot be written (sysfs, even for root): the run goes on, nothing is said to be stored
    locked = "/sys/kernel"
    try:
        open(os.path.join(locked, "sj_probe"), "wb").close()
        locked = None
    except OSError:
        pass
    if locked:
        n, _ = run(binary, work, "locked", study, locked)
        check(said(n, "B1", "condensed, not stored") and any("cannot write" in x for x in n)
              and not any("and stored" in x for x in n), "an unwritable library: condensed, not stored, and said")

    # 3. not taken
    def not_taken(name, text, lib_dir, *extra, reference=f_csv):
        n, csv = run(binary, work, name, text, lib_dir, *extra)
        check(said(n, "B2", "condensed and stored") and not said(n, "B2", "translated copy")
              and not any("not used" in x for x in n),
              f"{name}: B2 condensed and stored, not as a copy, nothing said of the pointer")
        check(close(csv, reference), f"{name}: results equal a fresh library's")
        return n

    moved_b2 = blocks(e1=2.0e11, moved=(2, 6, 1e-7 / MESH))
    _, mf_csv = run(binary, work, "moved_node_fresh", moved_b2, os.path.join(work, "lib_mf"))
    not_taken("moved_node", moved_b2, from_first("moved_node"), reference=mf_csv)
    not_taken("twins_no", changed, from_first("twins_no"), "--twins", "no")
    not_taken("verify", changed, from_first("verify"), "--library-verify")
    shifted = from_first("shifted")
    for p in pointers(shifted):
        data = bytearray(open(p, "rb").read())
        n = struct.unpack("<q", data[POINTER_HEAD - 32:POINTER_HEAD - 24])[0]
        xs = list(struct.unpack(f"<{3 * n}d", data[POINTER_HEAD:]))
        xs = [v + (0.5 if i % 3 == 0 else 0.0) for i, v in enumerate(xs)]
        with open(p, "wb") as fh:
            fh.write(bytes(data[:POINTER_HEAD]) + struct.pack(f"<{3 * n}d", *xs))
    not_taken("shifted_pointer", changed, shifted)
    cut = from_first("cut_pointer")
    for p in pointers(cut):
        data = open(p, "rb").read()
        with open(p, "wb") as fh:
            fh.write(data[:len(data) - 24])
    not_taken("cut_pointer", changed, cut)
    check(len(pointers(cut)) == 4 and sum(p.endswith(".2.sjg") for p in pointers(cut)) == 1,
          "the damaged pointer stays, B2's is added as the second of its copy key")
    again, _ = run(binary, work, "cut_again", changed, cut)
    check(not copied(again) and said(again, "B2", "loaded from library"), "the next run finds B2's own entry")

    # 4. a copy with loads its entry has not seen
    loaded = from_first("loaded")
    d, d_csv = run(binary, work, "loaded", blocks(e1=2.0e11, load_b2=True), loaded)
    check(said(d, "B2", "the entry of a translated copy") and said(d, "B2", "has loads its entry has not seen"),
          "B2 with a load of its own: the copy's entry found, then condensed anew")
    entries = {os.path.basename(p)[:-4] for p in glob.glob(os.path.join(loaded, "*.sjc"))}
    again, _ = run(binary, work, "loaded_again", blocks(e1=2.0e11, load_b2=True), loaded)
    check(said(again, "B2", "loaded from library") and not copied(again) and key_of(again, "B2") in entries
          and key_of(again, "B2") != old_b1, "B2 stored under its own key: the next run loads it")
    _, g_csv = run(binary, work, "loaded_fresh", blocks(e1=2.0e11, load_b2=True), os.path.join(work, "lib_lf"))
    check(close(d_csv, g_csv), "its results equal a fresh library's")
    own = os.path.join(loaded, key_of(again, "B2") + ".sjc")
    data = bytearray(open(own, "rb").read())
    data[300] ^= 1
    with open(own, "wb") as fh:
        fh.write(bytes(data))
    e, _ = run(binary, work, "own_damaged", blocks(e1=2.0e11, load_b2=True), loaded)
    check(any("not used (checksum mismatch" in x for x in e) and said(e, "B2", "condensed and stored")
          and not copied(e) and open(own, "rb").read() != bytes(data),
          "B2's own entry damaged: condensed and the entry replaced, no copy taken in its place")

    # 5. the whole deck moved
    for kind, copies in (("C3D8", True), ("CAX4", False), ("CYL", False)):
        here = os.path.join(work, "lib_" + kind)
        x0, x1 = (1.0, 1.5) if kind == "CAX4" else (0.0, 10.0)
        first, _ = run(binary, work, kind + "_at", blocks(x0=x0, kind=kind), here)
        moved, m_csv = run(binary, work, kind + "_moved", blocks(x0=x1, kind=kind), here)
        _, r_csv = run(binary, work, kind + "_fresh", blocks(x0=x1, kind=kind), os.path.join(work, "lib_r" + kind))
        stored = sum("condensed and stored" in x for x in first)
        if copies:
            check(len(copied(moved)) == stored and stored >= 2 and len(pointers(here)) == stored,
                  f"{kind}: the deck moved, every stored part taken as a translated copy of its old self")
        else:
            check(not copied(moved) and not pointers(here) and sum("condensed and stored" in x for x in moved) == stored,
                  f"{kind}: the deck moved, no copy taken, no pointer written ({stored} parts condensed)")
        check(close(m_csv, r_csv), f"{kind}: results of the moved deck equal a fresh library's")

    if FAILED:
        print(f"{len(FAILED)} check(s) failed")
        return 1
    print("all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
