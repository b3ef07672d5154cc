#!/usr/bin/env python3
"""Identical parts: a 10-storey tower of one storey module (bench/gen_modules.py,
S4 slab on B33 columns, storeys turned by 0, 90, 180, 270 degrees) written with
*PART/*INSTANCE and written explicitly (one *SUBSTRUCTURE per storey, nodes
placed by the generator). The instance deck is solved with CONDENSE=AUTO: one
condensation of the part, reused by the other nine instances (seven of them
turned); the explicit deck monolithically. Every CSV file must agree to 1e-10,
and the listing must say that one condensation was computed and nine reused.

usage: modules.py SUPERJOIN WORKDIR
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import equiv  # noqa: E402

RTOL = 1e-10


def main():
    binary, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    gen = os.path.join(ROOT, "bench", "gen_modules.py")
    runs = {}
    for name, extra in (("instances", []), ("explicit", ["--explicit"])):
        deck = os.path.join(work, name + ".deck")
        with open(deck, "w") as fh:
            subprocess.run([sys.executable, gen, "--mesh", "4", "--storeys", "10"] + extra, stdout=fh, check=True)
        csvdir = os.path.join(work, name)
        p = subprocess.run([binary, "-q", deck, "-o", os.path.join(work, name + ".lst"), "--csv", csvdir],
                           capture_output=True, text=True)
        if p.returncode != 0:
            print(f"FAIL: {name} exited with {p.returncode}: {p.stderr.strip()[:300]}")
            return 1
        runs[name] = csvdir
    failed = 0
    for f in sorted(os.listdir(runs["explicit"])):
        worst, msg = equiv.compare_file(os.path.join(runs["explicit"], f), os.path.join(runs["instances"], f),
                                        RTOL, 1e-14)
        if msg:
            print(f"FAIL: {f}: {msg or f'largest relative difference {worst:.2e}'}")
            failed += 1
        else:
            print(f"ok: {f}: largest relative difference {worst:.2e}")
    want = "condensations: 1 computed, 9 reused (7 turned by their instance's placement)"
    with open(os.path.join(work, "instances.lst")) as fh:
        if want not in fh.read():
            print(f"FAIL: the listing does not say '{want}'")
            failed += 1
        else:
            print(f"ok: listing: {want}")
    print(f"{5 + 1 - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
