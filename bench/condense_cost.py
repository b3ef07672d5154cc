#!/usr/bin/env python3
"""First condensed solve against the monolithic solve of the same model, and a
two-value joint sweep against two monolithic solves (issue 24; doc/performance.md,
"Superelements: condensation at the price of a factorization").

usage: bench/condense_cost.py [--bin build/superjoin] [--base OTHER_BIN] [--repeat N]
                              [--work DIR] [--models plane,shell,modules]

Models: plane = gen_panels.py --plane --mesh 224 (two CPS4 panels, 202 500 DOFs,
900 boundary DOFs); shell = gen_panels.py --mesh 130 (two S4 panels, 205 932
DOFs, 786 boundary DOFs); modules = gen_modules.py --row --mesh 56 --storeys 20
(twenty instances of one storey module, 390 360 DOFs). For each model the runs
(--condense yes with one joint value, --condense no, and for the panels
--condense yes with two values of a sweep) are repeated N times, interleaved,
so that a loaded machine slows all alike; wall-clock medians and their ratios
are printed, and the medians of the CPU time (user + system of the run, which
a loaded machine inflates less). With --base, the same condensed runs (one
value, and two for the panels) of another binary (e.g. the previous main) are
interleaved too.
"""
import argparse
import os
import resource
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cpu_children():
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run(cmd):
    """Wall-clock and CPU seconds of one run."""
    t0, c0 = time.perf_counter(), cpu_children()
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode not in (0, 5):
        sys.exit("failed (%d): %s\n%s" % (p.returncode, " ".join(cmd), p.stderr[-2000:]))
    return time.perf_counter() - t0, cpu_children() - c0


def deck(work, name, script, args):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as fh:
        subprocess.run([sys.executable, os.path.join(ROOT, "bench", script)] + args, stdout=fh, check=True)
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--base")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "condense_cost"))
    ap.add_argument("--models", default="plane,shell,modules")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    specs = {
        "plane": ("gen_panels.py", ["--plane", "--mesh", "224"], True),
        "shell": ("gen_panels.py", ["--mesh", "130"], True),
        "modules": ("gen_modules.py", ["--row", "--mesh", "56", "--storeys", "20"], False),
    }
    for name in args.models.split(","):
        script, gargs, sweep = specs[name]
        runs = {}
        if sweep:
            one = deck(args.work, name + "1", script, gargs + ["--values", "1e6"])
            two = deck(args.work, name + "2", script, gargs + ["--values", "1e6,1e7"])
        else:
            one = deck(args.work, name + "1", script, gargs)
        lst = os.path.join(args.work, name + ".lst")
        runs["condensed"] = [args.bin, "-q", one, "--condense", "yes", "-o", lst]
        runs["monolithic"] = [args.bin, "-q", one, "--condense", "no", "-o", lst]
        if sweep:
            runs["sweep2"] = [args.bin, "-q", two, "--condense", "yes", "-o", lst]
        if args.base:
            runs["base condensed"] = [args.base, "-q", one, "--condense", "yes", "-o", lst]
            if sweep:
                runs["base sweep2"] = [args.base, "-q", two, "--condense", "yes", "-o", lst]
        times = {k: [] for k in runs}
        for _ in range(args.repeat):
            for k, cmd in runs.items():
                times[k].append(run(cmd))
        med = {k: statistics.median(t[0] for t in v) for k, v in times.items()}
        cpu = {k: statistics.median(t[1] for t in v) for k, v in times.items()}
        print("== %s (%d rounds, load %.1f)" % (name, args.repeat, os.getloadavg()[0]))
        for k, v in times.items():
            print("  %-15s median %7.2f s (CPU %7.2f s)   %s" % (k, med[k], cpu[k], " ".join("%.2f" % t[0] for t in v)))
        for m, label in ((med, "wall"), (cpu, "CPU")):
            print("  %s: condensed / monolithic: %.2f" % (label, m["condensed"] / m["monolithic"]))
            if sweep:
                print("  %s: sweep of 2 values / 2 monolithic solves: %.2f" % (label, m["sweep2"] / (2 * m["monolithic"])))
            if args.base:
                print("  %s: base condensed / monolithic: %.2f" % (label, m["base condensed"] / m["monolithic"]))
                if sweep:
                    print("  %s: base sweep of 2 values / 2 monolithic solves: %.2f"
                          % (label, m["base sweep2"] / (2 * m["monolithic"])))


if __name__ == "__main__":
    main()
