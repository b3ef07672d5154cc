#!/usr/bin/env python3
"""What results cost, and what output requests save (doc/performance.md, "Output requests").

usage: bench/output_cost.py [--bin build/superjoin] [--dofs 1e6] [--work DIR]

The frame of bench/gen_frame.f90 (--dofs N, tower) solved three ways in one
run: (1) the full output, listing + --csv + --vtk; (2) the listing alone;
(3) the deck with output requests (the base reactions with their totals and
the windward column line's displacements, *NODE PRINT), listing alone; (4) the
same with file requests (*NODE FILE U of the windward column line, *EL FILE SF
of the columns), listing + CSV + VTK, which the requests narrow. Prints
each run's wall time, peak memory and superjoin's own phase times (its
progress lines on stderr): the solve is the same in all three, the
difference is recovery and writing.
"""
import argparse
import os
import re
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
REQUESTS = """*NODE PRINT, NSET=COLUMNS.BASE, TOTALS=YES
RF
*NODE PRINT, NSET=COLUMNS.WINDWARD
U
"""
FILE_REQUESTS = """*NODE FILE, NSET=COLUMNS.WINDWARD
U
*EL FILE, ELSET=COLUMNS.COLS
SF
"""


def run(cmd, cwd):
    t0 = time.perf_counter()
    p = subprocess.run(["/usr/bin/time", "-f", "MAXRSS %M"] + cmd, cwd=cwd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        sys.exit(f"exit {p.returncode}: {p.stderr[-500:]}")
    phases = {}
    for name, sec in re.findall(r"superjoin: (read|assemble|order|factor|solve|health|recover|write) ([0-9.]+) s",
                                p.stderr):
        phases[name] = phases.get(name, 0.0) + float(sec)
    rss = int(re.search(r"MAXRSS (\d+)", p.stderr).group(1)) / 1024
    return wall, rss, phases


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--gen", default=os.path.join(ROOT, "build", "gen_frame"))
    ap.add_argument("--dofs", default="1e6")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench-output"))
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    deck = os.path.join(args.work, "frame.deck")
    subprocess.run([args.gen, "--dofs", args.dofs, deck], check=True, capture_output=True)
    text = open(deck).read()
    # the requests go before the first *STEP: they apply to every step
    at = text.index("*STEP")
    with open(os.path.join(args.work, "frame_req.deck"), "w") as fh:
        fh.write(text[:at] + REQUESTS + text[at:])
    with open(os.path.join(args.work, "frame_file.deck"), "w") as fh:
        fh.write(text[:at] + REQUESTS + FILE_REQUESTS + text[at:])
    binary = os.path.abspath(args.bin)
    runs = [("full output: listing + CSV + VTK", ["frame.deck", "-o", "full.lst", "--csv", "full_csv",
                                                  "--vtk", "full"]),
            ("listing only", ["frame.deck", "-o", "plain.lst"]),
            ("output requests (*NODE PRINT), listing", ["frame_req.deck", "-o", "req.lst"]),
            ("output and file requests (*NODE FILE U, *EL FILE SF of the columns): listing + CSV + VTK",
             ["frame_file.deck", "-o", "file.lst", "--csv", "file_csv", "--vtk", "file"])]
    print(f"## Output cost: gen_frame --dofs {args.dofs} (tower)")
    print("| run | wall s | peak MiB | assemble+order+factor+solve s | recover s | write s |")
    print("|---|---|---|---|---|---|")
    for label, cmd in runs:
        wall, rss, ph = run([binary] + cmd, args.work)
        core = sum(ph.get(k, 0.0) for k in ("assemble", "order", "factor", "solve", "health"))
        print(f"| {label} | {wall:.2f} | {rss:.0f} | {core:.2f} | {ph.get('recover', 0.0):.2f} | "
              f"{ph.get('write', 0.0):.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
