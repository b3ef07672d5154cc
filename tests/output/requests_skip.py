#!/usr/bin/env python3
"""Output requests decide what is computed and written, and change no result.

usage: requests_skip.py SUPERJOIN DECK "REQUEST CARDS" EXPECT_ELEMENTS [ARGS...]

Solves DECK as it is (full output) and a copy with REQUEST CARDS appended
(lines separated by '|'), both with --csv and ARGS. Checks, for the copy:
- its CSV tables hold exactly the rows its *NODE FILE / *EL FILE requests name
  (displacements with U, reactions with RF, element tables with S/E/SF), and
  every value is the full run's, bit for bit (the solution is the same; an
  element whose results are skipped contributes to no reaction);
- contact forces are always written and equal the full run's;
- element_forces.csv / plate_results.csv name EXPECT_ELEMENTS distinct
  elements (0: the table must be absent), and the listing says for how many
  elements it holds results (*EL PRINT) when it is fewer than all;
- the listing has no DISPLACEMENTS table (the requests replace it);
- the VTK file written with the CSV files holds the same arrays and values
  (tests/vtk/check_vtk.py: an array exactly when its table exists, zeros and
  a `results` flag of 0 outside the requested sets).
"""
import csv
import os
import re
import subprocess
import sys
import tempfile


def run(binary, deck, outdir, args):
    p = subprocess.run([binary, "-q", os.path.basename(deck), "-o", os.path.join(outdir, "run.lst"),
                        "--csv", os.path.join(outdir, "csv")] + args,
                       cwd=os.path.dirname(deck), capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"FAIL: exit {p.returncode} on {deck}: {p.stderr.strip()}")
    return os.path.join(outdir, "csv"), open(os.path.join(outdir, "run.lst")).read()


def rows(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        r = csv.reader(f)
        head = next(r)
        return head, [tuple(x) for x in r]


def main(argv):
    if len(argv) < 5:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    binary, deck, cards, expect = os.path.abspath(argv[1]), os.path.abspath(argv[2]), argv[3], int(argv[4])
    args = argv[5:]
    fails = []
    with tempfile.TemporaryDirectory() as tmp:
        variant = os.path.join(os.path.dirname(deck), f".requests_skip_{os.getpid()}.deck")
        with open(deck) as f, open(variant, "w") as g:
            g.write(f.read().rstrip("\n") + "\n" + cards.replace("|", "\n") + "\n")
        try:
            os.mkdir(os.path.join(tmp, "a"))
            os.mkdir(os.path.join(tmp, "b"))
            full, _ = run(binary, deck, os.path.join(tmp, "a"), args)
            vtk = os.path.join(tmp, "b", "vtk", "part")
            part, listing = run(binary, variant, os.path.join(tmp, "b"), args + ["--vtk", vtk])
        finally:
            os.remove(variant)
        for name in ("displacements.csv", "reactions.csv", "contact_forces.csv", "element_forces.csv",
                     "plate_results.csv"):
            a, b = rows(os.path.join(full, name)), rows(os.path.join(part, name))
            if b is None:
                continue
            if a is None:
                fails.append(f"{name}: written with requests, not without")
                continue
            if a[0] != b[0]:
                fails.append(f"{name}: header {b[0]} != {a[0]}")
            missing = set(b[1]) - set(a[1])
            if missing:
                fails.append(f"{name}: {len(missing)} rows differ from the full run, e.g. {sorted(missing)[0]}")
        if rows(os.path.join(part, "contact_forces.csv")) != rows(os.path.join(full, "contact_forces.csv")):
            fails.append("contact_forces.csv differs from the full run")
        elems = set()
        for name in ("element_forces.csv", "plate_results.csv"):
            t = rows(os.path.join(part, name))
            if t is not None:
                elems |= {(r[1], r[2]) for r in t[1]}
        if len(elems) != expect:
            fails.append(f"the element tables name {len(elems)} elements, expected {expect}")
        if expect == 0 and any(os.path.exists(os.path.join(part, n)) for n in ("element_forces.csv",)):
            fails.append("element_forces.csv written though no *EL FILE asks for it")
        # the VTK arrays follow the same requests: the same values as the CSV files
        chk = subprocess.run([sys.executable, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))),
                                                            "vtk", "check_vtk.py"), vtk + ".pvd", "--csv", part],
                             capture_output=True, text=True)
        if chk.returncode != 0:
            fails.append("VTK with requests: " + (chk.stdout + chk.stderr).strip()[-800:])
        if re.search(r"^DISPLACEMENTS", listing, re.M):
            fails.append("the listing still has the DISPLACEMENTS table")
        m = re.search(r"element results listed for (\d+) of (\d+) elements", listing)
        if m and int(m.group(1)) >= int(m.group(2)):
            fails.append(f"note claims a reduction that is none: {m.group(0)}")
    for f in fails:
        print("FAIL:", f)
    if not fails:
        print(f"ok: {os.path.basename(deck)} {' '.join(args)}: {expect} elements")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
