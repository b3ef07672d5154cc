#!/usr/bin/env python3
"""CONDENSE=AUTO counts identical parts found by their geometry (twins) where
condensing pays: at least 2 copies, each with 1000 interior DOFs or more and
at least 10 times its boundary (src/analysis/policy.f90, AUTO_TWIN_*; the
measurement: doc/performance.md, bench/twins.py --monolithic).

Three copies of bench/gen_twins.py's slab-on-columns part (P2 moved, P3 turned),
their CONDENSE=YES removed (the default, AUTO):
- mesh 12 (1038 DOFs: 1008 interior, 30 boundary): AUTO condenses the three
  (one condensation, two reused: the twins note names P2 and P3) and the
  results equal those of --condense no to 1e-10; with --twins no AUTO
  condenses none;
- mesh 4 (174 DOFs: 144 interior): AUTO condenses none (nothing to gain).

usage: twins_auto.py SUPERJOIN WORKDIR
"""
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, HERE)
import equiv  # noqa: E402
from building import exe_and_work  # noqa: E402
from twins import solve  # noqa: E402

RTOL = 1e-10
NOTE = "identical parts share a condensation (found by their geometry; --twins no: each its own): P2 as P1, P3 as P1 turned"
WHY = "condensed (AUTO: one of 3 identical parts (twins, found by their geometry))"


def deck(work, name, mesh):
    path = os.path.join(work, name, "twins.deck")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    text = subprocess.run([sys.executable, os.path.join(ROOT, "bench", "gen_twins.py"), "--mesh", str(mesh),
                           "--copies", "3"], capture_output=True, text=True, check=True).stdout
    with open(path, "w") as fh:
        fh.write(text.replace(", CONDENSE=YES", ""))
    return path


def main(argv):
    args = exe_and_work(argv, __doc__)
    if args is None:
        return 2
    binary, work = args
    results = []

    def check(ok, text):
        print(("ok: " if ok else "FAIL: ") + text)
        results.append(ok)

    big = solve(binary, deck(work, "big", 12), [])
    for part in ("P1", "P2", "P3"):
        check(f"substructure {part} {WHY}: 1008 interior DOFs eliminated" in big,
              f"mesh 12: AUTO condenses {part} as one of 3 twins")
    check(NOTE in big, "mesh 12: the twins note names P2 and P3 (turned)")
    check("condensations: 1 computed, 2 reused" in big, "mesh 12: one condensation computed, two reused")
    mono = solve(binary, deck(work, "mono", 12), ["--condense", "no"])
    check(" condensed (" not in mono, "mesh 12, --condense no: no part condensed")
    for f in sorted(os.listdir(os.path.join(work, "big", "csv"))):
        worst, msg = equiv.compare_file(os.path.join(work, "mono", "csv", f), os.path.join(work, "big", "csv", f),
                                        RTOL, 1e-14)
        check(not msg, f"mesh 12: {f} against --condense no: largest relative difference {worst:.2e} {msg or ''}")
    off = solve(binary, deck(work, "off", 12), ["--twins", "no"])
    check(" condensed (" not in off and "identical parts" not in off,
          "mesh 12, --twins no: AUTO condenses none (no instances, no twins counted)")
    small = solve(binary, deck(work, "small", 4), [])
    check(" condensed (" not in small and "identical parts" not in small,
          "mesh 4 (144 interior DOFs): AUTO condenses none")
    print(f"{results.count(True)} passed, {results.count(False)} failed")
    return 0 if all(results) else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
