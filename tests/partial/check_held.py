#!/usr/bin/env python3
"""*BOUNDARY, FIXED holding to a step that was not solved.

usage: check_held.py SUPERJOIN DECK OUTDIR

Runs DECK (tests/partial/held_unsolved.deck) and checks: exit status 3 with
the mechanism of LOOSE on stderr; the listing marks LOOSE, HOLD and OWN NOT
SOLVED, HOLD and OWN with the message that they hold to LOOSE, which was not
solved; AFTER and LATE are solved and written to displacements.csv with
their closed forms (P = 2 at node 3, k = 100: u1 = P/k at node 2, 2 P/k at
node 3; LATE holds node 3 there without the load), the unsolved steps not.
"""
import csv
import os
import subprocess
import sys

from check_partial import blocks, report   # this script's directory is on sys.path
HELD = "  error: step {} holds DOFs at the displacements of step LOOSE (*BOUNDARY, FIXED), which was not solved"


def main():
    binary, deck, outdir = sys.argv[1:4]
    os.makedirs(outdir, exist_ok=True)
    lst, csvdir = os.path.join(outdir, "run.lst"), os.path.join(outdir, "csv")
    p = subprocess.run([binary, "-q", deck, "-o", lst, "--csv", csvdir], capture_output=True, text=True)
    fails = []
    if p.returncode != 3:
        fails.append(f"exit status {p.returncode}, expected 3: {p.stderr}")
    if "mechanism at substructure MAIN node 1 DOF 1" not in p.stderr:
        fails.append("no mechanism message on stderr: " + p.stderr)
    if not fails:
        b = blocks(lst)
        for name in ("LOOSE", "HOLD", "OWN"):
            if not any(line.startswith("NOT SOLVED") for line in b.get(name, [])):
                fails.append(f"{name} is not marked NOT SOLVED")
        for name in ("HOLD", "OWN"):
            if HELD.format(name) not in b.get(name, []):
                fails.append(f"{name} does not say it holds to LOOSE: {b.get(name, [])[:4]}")
        for name in ("AFTER", "LATE"):
            if any(line.startswith("NOT SOLVED") for line in b.get(name, [])):
                fails.append(f"{name} is marked NOT SOLVED")
        k, load = 100.0, 2.0
        want = {("AFTER", "2"): load / k, ("AFTER", "3"): 2 * load / k,
                ("LATE", "2"): load / k, ("LATE", "3"): 2 * load / k}
        with open(os.path.join(csvdir, "displacements.csv")) as f:
            got = {(r[0], r[2]): float(r[3]) for r in csv.reader(f) if r[0] in ("AFTER", "LATE", "HOLD", "OWN")}
        for key, w in want.items():
            if key not in got or abs(got[key] - w) > 1e-12 * abs(w):
                fails.append(f"{key} u1 = {got.get(key)}, closed form {w}")
        if any(key[0] in ("HOLD", "OWN") for key in got):
            fails.append("rows of the unsolved steps in displacements.csv")
    return report(fails, "the steps holding to an unsolved step are marked with its name, the others solved")


if __name__ == "__main__":
    sys.exit(main())
