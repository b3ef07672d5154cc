#!/usr/bin/env python3
"""Identical parts found by their geometry (--twins, issue 26): copies of one
slab-on-columns part written as separate substructures (bench/gen_twins.py),
all condensed. P2 is the original moved, P3 and P4 turned by arbitrary proper
rotations and moved: they must share P1's condensation (P3, P4 turned). MOVED
(one node moved by 1e-6 m), MIRROR (a mirror image) and WRONGV (turned, its
columns' orientation vector not turned) must not.

Checks: the listing's one note names exactly the twins; --twins no gives no
note and every part condensed on its own; every CSV value of both runs and of
a monolithic run (--condense no) agrees to 1e-10; the K* of the turned twin P3
(*SUBSTRUCTURE MATRIX OUTPUT, Matrix Market) equals its own condensation to
1e-10 of its largest entry; with --library, only the four parts condensed
are stored (then loaded), the twins found as before. Straight cantilevers (nodes on one line): the orientation vector fixes the
turn about the line. With a rectangular brace on the default
orientation vector (it does not turn with the copy: the element check), only
the moved copy P2 is a twin.

usage: twins.py SUPERJOIN WORKDIR
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "bench"))
import equiv  # noqa: E402
from gen_twins import rotation, apply as turn  # noqa: E402

RTOL = 1e-10
NOTE = "identical parts share a condensation (found by their geometry; --twins no: each its own):"
EXPORT = "*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=P3, FILE NAME=p3, FORMAT=MATRIX MARKET"


def deck(work, name, extra):
    path = os.path.join(work, name, "twins.deck")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    text = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "gen_twins.py"), "--mesh", "4",
                           "--copies", "4"] + extra, capture_output=True, text=True, check=True).stdout
    with open(path, "w") as fh:
        fh.write(text.replace("*STEP", EXPORT + "\n*STEP", 1))
    return path


def line_deck(work):
    """Straight B33 cantilevers on one line each (10 elements, a rectangular
    section), root clamped, loaded at the tip. Orientation vector given: A;
    B turned and moved, its vector turned (a twin); C turned the same, its
    vector turned 30 degrees further about the beam's axis (the same beam
    turned about its axis: a twin too). On the default vector: D, and E, D
    moved (not matched: nothing fixes the turn about the line)."""
    path = os.path.join(work, "line", "line.deck")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    r = rotation([1.0, -2.0, 0.7], 48.0)
    axis = turn(r, [1.0, 0.0, 0.0])
    out = ["*HEADING", "straight twins", "*MATERIAL, NAME=ST", "*ELASTIC", "2.1e11, 0.3"]
    for name, rr, t, v in (("A", None, [0.0, 0.0, 0.0], [0.0, 1.0, 1.0]),
                           ("B", r, [5.0, 1.0, -2.0], turn(r, [0.0, 1.0, 1.0])),
                           ("C", r, [9.0, -3.0, 1.0], turn(rotation(axis, 30.0), turn(r, [0.0, 1.0, 1.0]))),
                           ("D", None, [0.0, 4.0, 0.0], None), ("E", None, [2.0, 6.0, 1.0], None)):
        out += [f"*SUBSTRUCTURE, NAME={name}, CONDENSE=YES", "*NODE"]
        for k in range(11):
            x = [0.3 * k, 0.0, 0.0]
            x = turn(rr, x) if rr else x
            out.append(f"{k + 1}, " + ", ".join(repr(a + b) for a, b in zip(x, t)))
        out.append("*ELEMENT, TYPE=B33, ELSET=E")
        out += [f"{k + 1}, {k + 1}, {k + 2}" for k in range(10)]
        out += ["*NSET, NSET=ROOT", "1", "*NSET, NSET=TIP", "11", "*BEAM SECTION, ELSET=E, MATERIAL=ST",
                "0.006, 2.0e-6, 4.5e-5, 6.0e-6"] + ([", ".join(repr(a) for a in v)] if v else []) + \
               ["*END SUBSTRUCTURE"]
    out += ["*BOUNDARY"] + [f"{n}.ROOT, 1, 6" for n in "ABCDE"]
    out += ["*STEP", "*CLOAD", "A.TIP, 2, 1000.0", "B.TIP, 3, -700.0", "C.TIP, 1, 500.0", "C.TIP, 2, 300.0",
            "D.TIP, 3, 100.0", "E.TIP, 2, 200.0", "*END STEP"]
    with open(path, "w") as fh:
        fh.write("\n".join(out) + "\n")
    return path


def solve(binary, path, args):
    work = os.path.dirname(path)
    p = subprocess.run([binary, "-q", path, "-o", os.path.join(work, "out.lst"), "--csv",
                        os.path.join(work, "csv")] + args, capture_output=True, text=True)
    if p.returncode != 0:
        raise SystemExit(f"FAIL: {path} {' '.join(args)} exited with {p.returncode}: {p.stderr.strip()[:300]}")
    with open(os.path.join(work, "out.lst")) as fh:
        return fh.read()


def market(path):
    """The entries of a Matrix Market coordinate file, {(i, j): value}."""
    out = {}
    with open(path) as fh:
        lines = [ln for ln in fh if not ln.startswith("%")]
    for ln in lines[1:]:
        i, j, v = ln.split()
        out[(int(i), int(j))] = float(v)
    return out


def main():
    binary, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    failed = passed = 0

    def check(ok, text):
        nonlocal failed, passed
        print(("ok: " if ok else "FAIL: ") + text)
        if ok:
            passed += 1
        else:
            failed += 1

    lst = {}
    for name, args in (("yes", []), ("no", ["--twins", "no"]), ("mono", ["--condense", "no"])):
        lst[name] = solve(binary, deck(work, name, ["--checks"]), args)
    want = NOTE + " P2 as P1, P3 as P1 turned, P4 as P1 turned"
    notes = [ln.strip() for ln in lst["yes"].splitlines() if NOTE in ln]
    check(notes == [want], f"the note names P2, P3 (turned), P4 (turned) and no other part: {notes}")
    check("condensations: 4 computed, 3 reused (2 turned by their instance's placement)" in lst["yes"],
          "4 condensations computed, 3 reused")
    check(NOTE not in lst["no"] and "condensations: 7 computed, 0 reused" in lst["no"],
          "--twins no: no note, every part condensed on its own")
    for other in ("no", "mono"):
        for f in sorted(os.listdir(os.path.join(work, "yes", "csv"))):
            worst, msg = equiv.compare_file(os.path.join(work, other, "csv", f), os.path.join(work, "yes", "csv", f),
                                            RTOL, 1e-14)
            check(not msg, f"{f} against {other}: largest relative difference {worst:.2e} {msg or ''}")
    a, b = market(os.path.join(work, "yes", "p3.mtx")), market(os.path.join(work, "no", "p3.mtx"))
    scale = max(abs(v) for v in b.values())
    diff = max(abs(a.get(k, 0.0) - b.get(k, 0.0)) for k in set(a) | set(b))
    # Entries missing from one file count as zeros: where P3's own K* has an
    # exact zero, the turned one may hold round-off (1e-14 of the largest
    # entry on some CPUs' BLAS kernels), and the other way round.
    check(len(set(a) & set(b)) >= len(b) // 2 and diff <= RTOL * scale,
          f"K* of P3: the turned twin's against its own, largest difference {diff / scale:.2e} of the largest entry")

    lib = os.path.join(work, "library")
    if os.path.isdir(lib):
        for f in os.listdir(lib):
            os.remove(os.path.join(lib, f))
    for name in ("stored", "loaded"):
        text = solve(binary, deck(work, name, ["--checks"]), ["--library", lib])
        worst = max(equiv.compare_file(os.path.join(work, "no", "csv", f), os.path.join(work, name, "csv", f),
                                       RTOL, 1e-14)[0] for f in os.listdir(os.path.join(work, "no", "csv")))
        check(NOTE + " P2 as P1, P3 as P1 turned, P4 as P1 turned" in text and text.count("library: substructure")
              == 4 and worst <= RTOL, f"--library ({name}): 4 entries, the same twins, results as --twins no "
              f"({worst:.2e})")

    rect = solve(binary, deck(work, "rect", ["--rect-brace"]), [])
    notes = [ln.strip() for ln in rect.splitlines() if NOTE in ln]
    check(notes == [NOTE + " P2 as P1"], f"rectangular brace on the default orientation: only P2 is a twin: {notes}")
    line = line_deck(work)
    text = solve(binary, line, [])
    notes = [ln.strip() for ln in text.splitlines() if NOTE in ln]
    yes_csv = os.path.join(work, "line_yes")
    shutil.rmtree(yes_csv, ignore_errors=True)   # a run before this one
    os.rename(os.path.join(work, "line", "csv"), yes_csv)
    solve(binary, line, ["--twins", "no"])
    worst = max(equiv.compare_file(os.path.join(work, "line", "csv", f), os.path.join(yes_csv, f), RTOL, 1e-14)[0]
                for f in os.listdir(yes_csv))
    check(notes == [NOTE + " B as A turned, C as A turned"] and worst <= RTOL,
          f"parts on one line: the orientation vector fixes the turn about the line (B, C twins of A), none on "
          f"the default vector (D, E); results as --twins no ({worst:.2e}): {notes}")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
