#!/usr/bin/env python3
"""Clapeyron's energy balance on every deck of the test suite.

usage: energy_balance_all.py SUPERJOIN SOURCE_DIR WORKDIR

Each deck of tests/decks and decks/ is run through a wrapper deck that
includes it and adds `*EL PRINT` / `ENER` (outside *STEP: every step without
an *EL PRINT of its own; a deck whose steps all have one is skipped). In every step of energies.csv the total strain
energy (elements + contacts + spring supports, summed from element matrices
and contact forces) must equal the work of the loads and prescribed
displacements (1/2 f.u + 1/2 R.u, summed from loads and reactions) to 1e-9
relative: the two sides are computed independently, so this checks the
energies, the recovered contact forces and reactions on condensed parts,
shells, springs, self weight, prescribed displacements and loops.
"""
import csv
import glob
import os
import subprocess
import sys

RTOL = 1e-9


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, src, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    decks = sorted(glob.glob(os.path.join(src, "tests", "decks", "*.deck")) +
                   glob.glob(os.path.join(src, "decks", "*.deck")))
    fails = steps = 0
    worst = (0.0, "")
    for deck in decks:
        name = os.path.splitext(os.path.basename(deck))[0]
        wrap = os.path.join(work, name + ".deck")
        with open(wrap, "w") as f:
            f.write(f"*INCLUDE, INPUT={os.path.abspath(deck)}\n*EL PRINT\nENER\n")
        csvdir = os.path.join(work, name + ".csv")
        r = subprocess.run([exe, "-q", wrap, "-o", os.path.join(work, name + ".lst"), "--csv", csvdir],
                           stderr=subprocess.PIPE, text=True)
        if r.returncode != 0:
            print(f"FAIL: {name}: exit status {r.returncode}\n{r.stderr}")
            fails += 1
            continue
        path = os.path.join(csvdir, "energies.csv")
        if not os.path.exists(path):
            with open(deck) as f:
                own = "*ELPRINT" in f.read().upper().replace(" ", "")   # blanks in keywords do not count
            if own:   # every step has an *EL PRINT of its own, without ENER
                print(f"skipped: {name} (its steps have their own *EL PRINT)")
                continue
            print(f"FAIL: {name}: no energies.csv")
            fails += 1
            continue
        sides, unchecked = {}, set()
        with open(path) as f:
            for row in csv.DictReader(f):
                if row["kind"] in ("total", "load_work", "prescribed_work"):
                    sides.setdefault(row["step"], {})[row["kind"]] = float(row["energy"])
                elif row["kind"] == "balance_not_checked":   # a combination, thermal strains: says why
                    unchecked.add(row["step"])
        for step, s in sides.items():
            if step in unchecked:
                continue
            steps += 1
            work_done = s["load_work"] + s["prescribed_work"]
            big = max(abs(s["total"]), abs(work_done))
            rel = abs(s["total"] - work_done) / big if big > 0 else 0.0
            if rel > worst[0]:
                worst = (rel, f"{name} step {step}")
            if not (rel <= RTOL) or s["total"] < 0:
                print(f"FAIL: {name} step {step}: strain energy {s['total']!r}, work {work_done!r} "
                      f"(relative difference {rel:.2e})")
                fails += 1
    print(f"{len(decks)} decks, {steps} steps; largest relative difference {worst[0]:.1e} ({worst[1]})")
    if fails:
        return 1
    print("ok: strain energy = 1/2 f.u + 1/2 R.u in every step")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
