#!/usr/bin/env python3
"""Joint study with output requests: a requested interior result against independent runs.

usage: joint_requests.py SUPERJOIN GEN_PANELS WORKDIR

A joint study's further values do only what the output needs (the interface
matrix kept, the interface refactored, the condensed interiors recovered for
the whole-system health and the requested rows). This script makes sure no
such saving ever hides a requested result: two CPS4 panels
(bench/gen_panels.py --plane) with the joint's shear g swept through
finite values and RIGID, condensed (--condense yes), no --csv, and
requests that name only interior results: the displacements of one interior
node of panel A (*NODE PRINT) and the stresses of one interior element of
panel B (*EL PRINT). (Not g = 0: the panels would slide along the joint.)
Every printed row of every step is compared to 1e-10
(relative to the largest value of its block) with an independent
monolithic run (--condense no) of that step's g alone.
"""
import os
import re
import subprocess
import sys

MESH = 6
VALUES = ["1.0e4", "1.0e7", "1.0e9", "RIGID", "1.0e5", "3.0e5"]
PROBE_NODE = 3 * (MESH + 1) + 3       # the middle of panel A (interior)
PROBE_ELEMENT = 2 * MESH + 4          # an element of panel B away from its edges
TOL = 1e-10


def panels(gen, args):
    r = subprocess.run([sys.executable, gen, "--plane", "--mesh", str(MESH), *args],
                       stdout=subprocess.PIPE, text=True, check=True)
    return r.stdout


def with_probes(deck):
    """The deck with its requests replaced by the interior probes."""
    first = deck.index("*NSET, NSET=RIGHT")   # panel A's first set
    deck = deck[:first] + f"*NSET, NSET=PROBE\n{PROBE_NODE}\n" + deck[first:]
    second = deck.index("*NSET, NSET=RIGHT", deck.index("*SUBSTRUCTURE, NAME=B"))
    deck = deck[:second] + f"*ELSET, ELSET=PROBE\n{PROBE_ELEMENT}\n" + deck[second:]
    requests = "*NODE PRINT, NSET=A.PROBE\nU\n*EL PRINT, ELSET=B.PROBE\nS\n"
    if "*NODE PRINT" in deck:
        deck = deck.replace("*NODE PRINT, NSET=B.RIGHT\nU\n", requests)
    else:
        deck = deck.replace("*END STEP", requests + "*END STEP")
    return deck


def run(exe, deck, work, name, options):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(deck)
    lst = os.path.join(work, name + ".lst")
    r = subprocess.run([exe, "-q", path, "-o", lst, *options], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {name}: exit {r.returncode}\n{r.stderr}")
    with open(lst) as f:
        return f.read()


NUMBER = re.compile(r"-?\d\.\d{6}E[+-]\d{3}")


def requested_rows(text):
    """The number rows of each step's REQUESTED OUTPUT block: {step: [[floats]]}."""
    steps = {}
    for block in text.split("REQUESTED OUTPUT")[1:]:
        step = int(re.match(r" \(\*NODE PRINT, \*EL PRINT\) of step (\d+)", block).group(1))
        body = block.split("\n=====")[0]
        steps[step] = [[float(x) for x in NUMBER.findall(line)] for line in body.splitlines()
                       if NUMBER.search(line)]
    return steps


def compare(a, b):
    """Largest difference of the rows a and b relative to their largest value."""
    if len(a) != len(b) or any(len(x) != len(y) for x, y in zip(a, b)) or not a:
        return float("inf")
    scale = max(max(abs(v) for v in row) for row in a + b) or 1.0
    return max(abs(x - y) for ra, rb in zip(a, b) for x, y in zip(ra, rb)) / scale


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, gen, work = argv[1:]
    os.makedirs(work, exist_ok=True)
    study = run(exe, with_probes(panels(gen, ["--requests", "--values", ",".join(VALUES)])), work, "study",
                ("--condense", "yes"))
    if "element results listed for 1 of" not in study:
        print("FAIL: the study lists the results of other elements than the probe")
        return 1
    got = requested_rows(study)
    ok = len(got) == len(VALUES)
    if not ok:
        print(f"FAIL: {len(got)} requested blocks for {len(VALUES)} values")
    for i, g in enumerate(VALUES):
        single = run(exe, with_probes(panels(gen, ["--single", g])), work, f"single_{i + 1}", ("--condense", "no"))
        want = requested_rows(single).get(1, [])
        worst = compare(got.get(i + 1, []), want)
        good = worst <= TOL
        ok = ok and good
        print(f"{'ok' if good else 'FAIL'}: value {i + 1} (g = {g}): {len(want)} requested rows, "
              f"largest difference {worst:.1e} of the block's largest value")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
