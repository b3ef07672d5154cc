#!/usr/bin/env python3
"""Each step's NUMERICAL HEALTH block reports the matrix that step was solved with.

usage: step_health.py SUPERJOIN GEN_PANELS WORKDIR

A joint study (bench/gen_panels.py --values, two S4 panels joined along an
edge) solves one matrix per value of the joint's rotational stiffness g.
Every step's MAXRATIO (value and place) and condition estimate must be those
of the same g solved alone, monolithic and condensed, and the study's
MODEL block says so. Until 2026-11-29 every step printed the run's largest
(and the MODEL block said "the counts above and MAXRATIO are the largest
over them"), so a well-conditioned value showed the figures of the worst one. The values are chosen so that the lone runs' figures differ
(checked: otherwise the test could not fail): monolithic, MAXRATIO and the
estimate; condensed, the estimate (MAXRATIO there is a panel interior's).
"""
import os
import re
import subprocess
import sys

MESH = 6
VALUES = ["1.0e4", "1.0e11", "1.0e7"]
RTOL = 1e-6   # the same matrix: equal but for the last digits of the estimate's arithmetic


def panels(gen, args):
    r = subprocess.run([sys.executable, gen, "--mesh", str(MESH), *args],
                       stdout=subprocess.PIPE, text=True, check=True)
    return r.stdout


def solve(bin_, work, name, deck, condense):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(deck)
    lst = os.path.join(work, name + ".lst")
    r = subprocess.run([bin_, "-q", path, "-o", lst, "--condense", condense],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("FAIL: %s (--condense %s) exited with %d\n%s" % (name, condense, r.returncode, r.stderr))
    with open(lst) as f:
        return f.read()


def health(listing):
    """[(maxratio, place, condition estimate)] of each step's NUMERICAL HEALTH block."""
    out = []
    for block in listing.split("NUMERICAL HEALTH\n")[1:]:
        m = re.search(r"^  MAXRATIO +(\S+)  at (.*)$", block, re.M)
        c = re.search(r"^  condition estimate \(1-norm\) +(\S+)$", block, re.M)
        if not m or not c:
            sys.exit("FAIL: a NUMERICAL HEALTH block without MAXRATIO or condition estimate")
        out.append((float(m.group(1)), m.group(2), float(c.group(1))))
    return out


def close(a, b):
    return abs(a - b) <= RTOL * max(abs(a), abs(b))


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    bin_, gen, work = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    os.makedirs(work, exist_ok=True)
    fail = 0
    for condense in ("no", "yes"):
        study = health(solve(bin_, work, "study_" + condense, panels(gen, ["--values", ",".join(VALUES)]), condense))
        if len(study) != len(VALUES):
            sys.exit("FAIL: %d health blocks for %d values" % (len(study), len(VALUES)))
        alone = []
        for i, g in enumerate(VALUES):
            h = health(solve(bin_, work, "alone%d_%s" % (i, condense), panels(gen, ["--values", g]), condense))
            alone.append(h[0])
        if all(a[1] == alone[0][1] and close(a[0], alone[0][0]) and close(a[2], alone[0][2]) for a in alone):
            print("FAIL: the lone runs of the values have the same health figures: the test would not see the run's largest")
            fail += 1
        for i, (s, a) in enumerate(zip(study, alone)):
            ok = s[1] == a[1] and close(s[0], a[0]) and close(s[2], a[2])
            print("%s  --condense %s  g = %-7s  step: MAXRATIO %.3e at %s, condition %.3e; alone: %.3e at %s, %.3e"
                  % ("ok  " if ok else "FAIL", condense, VALUES[i], s[0], s[1], s[2], a[0], a[1], a[2]))
            fail += not ok
        with open(os.path.join(work, "study_%s.lst" % condense)) as f:
            model_block = f.read().split("\nNUMERICAL HEALTH\n")[0]
        if "each step's NUMERICAL HEALTH that of its own factorization" not in model_block:
            print("FAIL: --condense %s: the MODEL block does not say whose health each step reports" % condense)
            fail += 1
    print("step_health: %s" % ("passed" if fail == 0 else "%d failures" % fail))
    return 1 if fail else 0


if __name__ == "__main__":
    sys.exit(main())
