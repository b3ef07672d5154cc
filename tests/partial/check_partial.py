#!/usr/bin/env python3
"""A sweep value that makes a mechanism loses only its own step.

usage: check_partial.py SUPERJOIN DECK OUTDIR

Runs DECK (a *CHANGE CONTACT SWEEP over g = 1e3, 0, 1e4 whose 0 makes a
mechanism) and checks: exit status 3 with the mechanism on stderr; the listing
marks STUDY-2 NOT SOLVED with that message; STUDY-1 and STUDY-3 are listed and
written to the CSV files exactly as STUDY-1 and STUDY-2 of the same deck
without the value 0 (run too); the tip deflection is P (2L)^3/(3EI) + P L^2/g.
"""
import csv
import os
import subprocess
import sys

RULE_START = "=" * 20


def run(binary, deck, out):
    os.makedirs(out, exist_ok=True)
    lst = os.path.join(out, "run.lst")
    csvdir = os.path.join(out, "csv")
    p = subprocess.run([binary, "-q", deck, "-o", lst, "--csv", csvdir],
                       capture_output=True, text=True)
    return p, lst, csvdir


def blocks(lst):
    """The lines of every step block, by step name, without its STEP line."""
    lines = open(lst).read().splitlines()
    out, name = {}, None
    for i, line in enumerate(lines):
        if line.startswith("STEP ") and i > 0 and lines[i - 1].startswith(RULE_START):
            name = line.split()[2]
            out[name] = []
            continue
        if name is None:
            continue
        if line.startswith(RULE_START) and out[name]:
            name = None
            continue
        if not line.startswith(RULE_START):
            out[name].append(line)
    return out


def rows(csvdir, table):
    with open(os.path.join(csvdir, table)) as f:
        return list(csv.reader(f))


def combinations(binary, text, outdir):
    """A load combination of the failed step is marked NOT SOLVED too and
    left out of the envelope; one of solved steps superposes them."""
    fails = []
    deck = os.path.join(outdir, "comb.deck")
    with open(deck, "w") as f:
        f.write(text + "*LOAD COMBINATION, NAME=BAD\n STUDY-2, 1.0\n"
                "*LOAD COMBINATION, NAME=GOOD\n STUDY-1, 1.0\n STUDY-3, 2.0\n")
    p, lst, csvdir = run(binary, deck, os.path.join(outdir, "comb"))
    if p.returncode != 3:
        return [f"combinations: exit status {p.returncode}, expected 3"]
    b = blocks(lst)
    if "  error: step STUDY-2 of this combination was not solved" not in b.get("BAD", []):
        fails.append("combination BAD is not marked as using the failed step")
    if "ENVELOPE OF THE LOAD COMBINATIONS (GOOD)" not in open(lst).read():
        fails.append("the envelope is not over GOOD alone")
    tip = {r[0]: float(r[4]) for r in rows(csvdir, "displacements.csv") if r[1] == "C" and r[2] == "2"}
    if "BAD" in tip or abs(tip.get("GOOD", 0.0) - tip["STUDY-1"] - 2.0 * tip["STUDY-3"]) > 1e-12:
        fails.append(f"combination rows in displacements.csv: {tip}")
    return fails


def main():
    binary, deck, outdir = sys.argv[1:4]
    fails = []
    p, lst, csvdir = run(binary, deck, os.path.join(outdir, "partial"))
    if p.returncode != 3:
        fails.append(f"exit status {p.returncode}, expected 3")
    if "cannot be solved" not in p.stderr:
        fails.append("no mechanism message on stderr: " + p.stderr)
    if "the listing is written with the results of the steps solved" not in p.stderr:
        fails.append("stderr does not say the listing is written")
    text = open(deck).read()
    good = os.path.join(outdir, "good.deck")
    with open(good, "w") as f:
        f.write(text.replace("1.0e3, 0.0, 1.0e4", "1.0e3, 1.0e4"))
    q, glst, gcsv = run(binary, good, os.path.join(outdir, "good"))
    if q.returncode != 0:
        fails.append(f"the deck without the value 0 exits {q.returncode}: {q.stderr}")
    if not fails:
        b, g = blocks(lst), blocks(glst)
        bad = b.get("STUDY-2", [])
        if not any(line.startswith("NOT SOLVED") for line in bad):
            fails.append("STUDY-2 is not marked NOT SOLVED: " + repr(bad[:3]))
        elif not any("cannot be solved" in line for line in bad):
            fails.append("STUDY-2 does not carry the mechanism message")
        if "  J                        2         1     6  0.000000E+000" not in bad:
            fails.append("STUDY-2's header does not show its g = 0")
        for mine, ref in (("STUDY-1", "STUDY-1"), ("STUDY-3", "STUDY-2")):
            if b.get(mine) != g.get(ref):
                fails.append(f"{mine} differs from {ref} of the run without 0")
        for table in ("displacements.csv", "contact_forces.csv", "reactions.csv"):
            mine = rows(csvdir, table)
            ref = rows(gcsv, table)
            ref = [r if r[0] != "STUDY-2" else ["STUDY-3"] + r[1:] for r in ref]
            if mine != ref:
                fails.append(f"{table} differs from the run without 0 (STUDY-2 renamed)")
        ei, load = 2.1e11 * 1.0e-6, 1.0
        for name, gval in (("STUDY-1", 1.0e3), ("STUDY-3", 1.0e4)):
            want = -(load * 8.0 / (3.0 * ei) + load / gval)
            got = [float(r[4]) for r in rows(csvdir, "displacements.csv")
                   if r[0] == name and r[1] == "C" and r[2] == "2"]
            if len(got) != 1 or abs(got[0] - want) > 1e-9 * abs(want):
                fails.append(f"{name}: tip u2 {got}, closed form {want}")
    fails += combinations(binary, text, outdir)
    return report(fails, "the failed sweep value is marked, the others are as without it")


def report(fails, ok):
    """Print each failure (or the ok line); the exit status."""
    for f in fails:
        print("FAIL: " + f)
    if not fails:
        print("ok: " + ok)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
