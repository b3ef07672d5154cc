#!/usr/bin/env python3
"""Identical parts found by their geometry (--twins, issue 26): the time saved
on N copies of one part written as substructures, and what the detection
itself costs.

usage: twins.py [--bin BUILD/superjoin] [--mesh M] [--copies N,N..] [--repeat R]
                [--monolithic] [--callgrind] [--work DIR]

For each N: bench/gen_twins.py --mesh M --copies N (every copy CONDENSE=YES;
copy 2 moved, copies 3..N turned by arbitrary proper rotations), solved with
--twins yes (one condensation, N - 1 reused) and --twins no (N condensations).
Each run is timed around the process (CPU time of the child, user + system,
best of --repeat interleaved rounds; wall clock beside it). Run it with one BLAS thread
(OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1: the script sets them for its
children) so that the CPU time is the work done.

With --monolithic a third run, --condense no (no part condensed: the one
sparse matrix of the whole model), and the ratio monolithic / twins yes: where
it exceeds 1 condensing the copies pays, what CONDENSE=AUTO's twin rule
(src/analysis/policy.f90, AUTO_TWIN_*) is drawn from.

With --callgrind the detection's own cost is counted in instructions
(valgrind --tool=callgrind, deterministic, unlike a time under load) on the
deck with N = the first of --copies: the fingerprints (twin_print) and the
exact checks (twin_turn) against the condensation of one part (condense, the
factorization and K*) and its local system (build_local_system, the assembly
of its stiffness); and on the same deck with --rect-brace, where every
turned copy goes through the whole check (nodes, orientation vectors, the
brace's stiffness turned) and is refused at its last step (the worst case:
the check is paid and nothing is saved).
"""
import argparse
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
from library_study import timed  # noqa: E402  (best of repeat: wall and CPU seconds of the child)


def gen(work, mesh, copies, extra=()):
    path = os.path.join(work, f"twins_m{mesh}_n{copies}{''.join(extra).replace('-', '_')}.deck")
    with open(path, "w") as fh:
        subprocess.run([sys.executable, os.path.join(HERE, "gen_twins.py"), "--mesh", str(mesh), "--copies",
                        str(copies)] + list(extra), stdout=fh, check=True)
    return path


def inclusive(binary, deck, work, tag):
    """Inclusive instruction counts of the procedures of interest, and the total."""
    out = os.path.join(work, f"callgrind.{tag}")
    subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", binary, "-q", deck, "-o",
                    os.path.join(work, f"{tag}.lst")], capture_output=True, check=True)
    text = subprocess.run(["callgrind_annotate", "--inclusive=yes", "--threshold=100", out],
                          capture_output=True, text=True, check=True).stdout
    os.remove(out)
    counts = {}
    for line in text.splitlines():
        m = re.match(r"\s*([\d,]+)\s+\(.*?\)\s+\S*?:(\S+)", line) or re.match(r"\s*([\d,]+)\s+\S*?:(\S+)", line)
        if not m:
            continue
        n, name = int(m.group(1).replace(",", "")), m.group(2)
        for key, sym in (("twin_print", "twins_MOD_twin_print"), ("twin_turn", "twins_MOD_twin_turn"),
                         ("condense", "condensed_MOD_condense"), ("local_system", "MOD_build_local_system"),
                         ("total", "main")):
            if name.endswith(sym) or (key == "total" and name == "main"):
                counts[key] = max(counts.get(key, 0), n)
    return counts


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", default=os.path.join(ROOT, "build", "superjoin"))
    ap.add_argument("--mesh", type=int, default=40)
    ap.add_argument("--copies", default="2,4,8,16")
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--callgrind", action="store_true")
    ap.add_argument("--monolithic", action="store_true")
    ap.add_argument("--work", default=os.path.join(ROOT, "build", "bench_twins"))
    args = ap.parse_args()
    os.environ.update(OPENBLAS_NUM_THREADS="1", OMP_NUM_THREADS="1")
    os.makedirs(args.work, exist_ok=True)
    binary = os.path.abspath(args.bin)
    counts = [int(c) for c in args.copies.split(",")]
    dofs = 6 * ((args.mesh + 1) ** 2 + 4)
    print(f"part: {args.mesh}x{args.mesh} S4 slab on 4 B33 columns and a brace, {dofs} DOFs; CPU seconds, "
          f"best of {args.repeat}")
    mono_head = " --condense no | monolithic/yes |" if args.monolithic else ""
    print(f"| copies | DOFs | --twins no | --twins yes | no/yes | wall no | wall yes |{mono_head}")
    print("|---|---|---|---|---|---|---|" + ("---|---|" if args.monolithic else ""))
    runs = (("no", ["--twins", "no"]), ("yes", ["--twins", "yes"]))
    if args.monolithic:
        runs += (("mono", ["--condense", "no"]),)
    for n in counts:
        deck = gen(args.work, args.mesh, n)
        res = {}
        for _ in range(args.repeat):   # interleaved rounds: the load moves all runs alike
            for t, extra in runs:
                w, c = timed([binary, "-q", deck, "-o", os.path.join(args.work, f"n{n}_{t}.lst")] + extra, 1)
                res[t] = (min(res[t][0], w), min(res[t][1], c)) if t in res else (w, c)
        mono = f" {res['mono'][1]:.2f} s | **{res['mono'][1] / res['yes'][1]:.2f}** |" if args.monolithic else ""
        print(f"| {n} | {n * dofs + 6 * (n + 1)} | {res['no'][1]:.2f} s | {res['yes'][1]:.2f} s | "
              f"**{res['no'][1] / res['yes'][1]:.2f}** | {res['no'][0]:.2f} s | {res['yes'][0]:.2f} s |{mono}",
              flush=True)
        os.remove(deck)
    if not args.callgrind:
        return 0
    n = counts[0]
    print(f"\ninstructions (callgrind, inclusive), {n} copies of {args.mesh}x{args.mesh}:")
    for tag, extra in (("twins", ()), ("refused", ("--rect-brace",))):
        deck = gen(args.work, args.mesh, n, extra)
        c = inclusive(binary, deck, args.work, tag)
        os.remove(deck)
        detect = c.get("twin_print", 0) + c.get("twin_turn", 0)
        print(f"  {tag}: detection {detect:,} (twin_print {c.get('twin_print', 0):,}, twin_turn "
              f"{c.get('twin_turn', 0):,}); condense {c.get('condense', 0):,}; build_local_system "
              f"{c.get('local_system', 0):,}; whole run {c.get('total', 0):,}; detection / condense "
              f"{detect / max(c.get('condense', 1), 1):.4f}, / whole run {detect / max(c.get('total', 1), 1):.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
