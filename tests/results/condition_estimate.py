#!/usr/bin/env python3
"""The condition estimate of the NUMERICAL HEALTH block against its closed form.

A chain of n bars (T3D2, EA/L = k) fixed at one end, loaded at the other,
only its axial DOFs free: K = k tridiag(-1, 2, -1) with K_nn = k, so
||K||_1 = 4k, (K^-1)_ij = min(i, j)/k and ||K^-1||_1 = n(n+1)/(2k): the
1-norm condition number is 2 n (n + 1), whatever k.

- n = 15 000 (at most COND_FULL_MAX = 20 000 equations): Hager-Higham's
  estimate, which is exact for a matrix whose inverse is positive; no note.
- n = 30 000: the free lower bound ||K||_1 max(||q||_1/||f||_1, 1/min D_jj)
  (the tip load's solution is K^-1's largest column: the bound is exact here),
  and the listing's note says it is that bound, not Hager's estimate.
- n = 30 000 loaded next to the fixed end instead: the bound is far below
  (||q||_1/||f||_1 = n/k there: 4n), still under the note; the listing prints
  what it computed, a lower bound of the true value.
- n = 75 000: the bound, 2 n (n + 1) = 1.1e10, is above COND_BOUND_LIMIT
  (1e10): Hager-Higham's estimate runs (no note) and is exact.

The printed figure (3 digits) is compared to 1 %.

usage: condition_estimate.py SUPERJOIN WORKDIR
"""
import os
import re
import shutil
import subprocess
import sys

NOTE = "condition estimate: a lower bound from the solutions and the pivots"
FAILED = []


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        FAILED.append(what)


def chain(n, load_node):
    lines = ["** a chain of n bars, axial DOFs free", "*NODE, NSET=ALL"]
    lines += [f"{i}, {i - 1}., 0., 0." for i in range(1, n + 2)]
    lines.append("*ELEMENT, TYPE=T3D2, ELSET=BARS")
    lines += [f"{i}, {i}, {i + 1}" for i in range(1, n + 1)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", "1000., 0.3",
              "*SOLID SECTION, ELSET=BARS, MATERIAL=M", "1.",
              "*BOUNDARY", "1, 1, 3", "ALL, 2, 3",
              "*STEP", "*STATIC", "*CLOAD", f"{load_node}, 1, 1.", "*END STEP"]
    return "\n".join(lines) + "\n"


def run(binary, work, name, n, load_node):
    deck = os.path.join(work, name + ".deck")
    with open(deck, "w") as fh:
        fh.write(chain(n, load_node))
    lst = os.path.join(work, name + ".lst")
    p = subprocess.run([binary, "-q", deck, "-o", lst], capture_output=True, text=True)
    if p.returncode != 0:
        check(False, f"{name}: exit {p.returncode}: {p.stderr.strip()[:200]}")
        return None, False, None
    text = open(lst).read()
    m = re.search(r"condition estimate \(1-norm\)\s+(\S+)", text)
    eq = re.search(r"^  equations\s+(\d+)", text, re.M)
    return (float(m.group(1)) if m else None), NOTE in text, (int(eq.group(1)) if eq else None)


def close(a, b):
    return a is not None and abs(a - b) <= 0.01 * b


def main():
    binary, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for name, n, load, note, exact in [("hager", 15000, "tip", False, True),
                                       ("bound", 30000, "tip", True, True),
                                       ("crude", 30000, "root", True, False),
                                       ("escalated", 75000, "tip", False, True)]:
        cond, has_note, neq = run(binary, work, name, n, n + 1 if load == "tip" else 2)
        true = 2.0 * n * (n + 1)
        check(neq == n, f"{name}: {n} equations (listing: {neq})")
        check(has_note == note, f"{name}: the lower-bound note {'present' if note else 'absent'}")
        if exact:
            check(close(cond, true), f"{name}: condition estimate {cond} = 2n(n+1) = {true:.3e} to 1 %")
        else:
            check(cond is not None and close(cond, 4.0 * n) and cond < true,
                  f"{name}: condition estimate {cond} = the bound 4n = {4.0 * n:.3e}, below 2n(n+1) = {true:.3e}")
    print(f"{len(FAILED)} failed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
