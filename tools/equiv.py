#!/usr/bin/env python3
"""Compare the solutions of two superjoin runs of the same decks, value by value.

    tools/equiv.py --a "OLD_BINARY [ARGS]" --b "NEW_BINARY [ARGS]" [--rtol 1e-12] [DECK ...]

Each deck (default: every deck under tests/decks, decks/ and decks/plate_hole,
and tests/extreme; --set verification or extreme for one group) is solved by both commands with --csv; every numeric field of
every CSV file is compared with

    |a - b| <= rtol * ((|a| + |b|)/2 + max|file|) + atol

(the second term: entries that are round-off next to the file's largest result;
identifier columns such as node, element and dof are compared exactly; atol,
default 1e-14, is a floor for files whose every value is round-off of an exact 0,
as the deck tests' absolute tolerance 1e-12). A deck that declares its
conditioning with a header line "** csv-tolerance: X" (as for the deck tests,
tests/run_deck_test.sh) is compared with max(rtol, X). The largest relative
difference printed is over every entry, the floor aside.
Both runs must end with the same exit status. Uses: the proof that a
restructuring changed no result (old binary against new), and the proof that the
condensed path equals the monolithic one (same binary, --b "BIN --condense yes").
Prints one line per deck with the largest relative difference, then
'N passed, N failed'.
"""
import argparse
import csv
import glob
import os
import shlex
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ID_COLUMNS = {"step", "substructure", "node", "element", "type", "end", "dof", "contact",
              "master_node", "slave_node"}
DECK_SETS = {
    "verification": ["tests/decks/*.deck", "decks/*.deck", "decks/plate_hole/*.deck"],
    "extreme": ["tests/extreme/*.deck"],
}
DECK_SETS["all"] = DECK_SETS["verification"] + DECK_SETS["extreme"]


def run(cmd, deck, outdir):
    os.makedirs(outdir, exist_ok=True)
    args = shlex.split(cmd)
    if os.path.exists(args[0]):
        args[0] = os.path.abspath(args[0])
    args = args + ["-q", os.path.basename(deck), "-o", os.path.join(outdir, "out.lst"),
                               "--csv", os.path.join(outdir, "csv")]
    p = subprocess.run(args, cwd=os.path.dirname(os.path.abspath(deck)), stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE, text=True, timeout=600)
    return p.returncode, p.stderr


def read_csv(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def as_float(s):
    try:
        return float(s)
    except ValueError:
        return None


def compare_file(fa, fb, rtol, atol):
    """Largest scaled difference of two CSV files, or an error string."""
    ha, ra = read_csv(fa)
    hb, rb = read_csv(fb)
    if ha != hb:
        return None, "header differs"
    if len(ra) != len(rb):
        return None, f"{len(ra)} rows against {len(rb)}"
    ncol = len(ha)
    filemax = 0.0
    for row in ra + rb:
        for c in range(min(ncol, len(row))):
            v = as_float(row[c])
            if v is not None and ha[c] not in ID_COLUMNS:
                filemax = max(filemax, abs(v))
    worst = 0.0
    bad = None
    for i, (x, y) in enumerate(zip(ra, rb)):
        for c in range(ncol):
            a, b = as_float(x[c]), as_float(y[c])
            if a is None or b is None or ha[c] in ID_COLUMNS:
                if x[c] != y[c]:
                    return None, f"row {i + 2} column {ha[c]}: {x[c]!r} against {y[c]!r}"
                continue
            scale = (abs(a) + abs(b)) / 2 + filemax
            if scale == 0.0:
                continue
            rel = abs(a - b) / scale
            worst = max(worst, rel)
            if not (rel <= rtol or abs(a - b) <= atol) and bad is None:   # NaN or Inf: never within
                bad = f"row {i + 2} column {ha[c]}: {x[c]} against {y[c]} (relative {rel:.2e} > {rtol:.0e})"
    return worst, bad


def deck_csv_tolerance(deck):
    """The relative CSV tolerance a deck declares ("** csv-tolerance: X"), 0 if none."""
    try:
        with open(deck, encoding="utf-8", errors="replace") as f:
            for line in f:
                if line.startswith("** csv-tolerance:"):
                    return float(line.split(":", 1)[1].split()[0])
    except OSError:
        pass
    return 0.0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--a", required=True, help="reference command (binary and options)")
    ap.add_argument("--b", required=True, help="command under test")
    ap.add_argument("--rtol", type=float, default=1e-12)
    ap.add_argument("--atol", type=float, default=1e-14)
    ap.add_argument("--set", choices=sorted(DECK_SETS), default="all",
                    help="decks to run when none are named (default: all)")
    ap.add_argument("decks", nargs="*")
    args = ap.parse_args()
    decks = args.decks or sorted(d for g in DECK_SETS[args.set] for d in glob.glob(os.path.join(ROOT, g)))
    npass = nfail = 0
    with tempfile.TemporaryDirectory() as tmp:
        for k, deck in enumerate(decks):
            name = os.path.relpath(deck, ROOT) if deck.startswith(ROOT) else deck
            da, db = os.path.join(tmp, f"{k}a"), os.path.join(tmp, f"{k}b")
            rca, erra = run(args.a, deck, da)
            rcb, errb = run(args.b, deck, db)
            if rca != rcb:
                print(f"FAIL {name}: exit {rca} against {rcb}\n  {errb.strip()[:300]}")
                nfail += 1
                continue
            if rca != 0:
                print(f"ok   {name}: both exit {rca}")
                npass += 1
                continue
            worst, msg = 0.0, None
            files = sorted(os.listdir(os.path.join(da, "csv")))
            if files != sorted(os.listdir(os.path.join(db, "csv"))):
                msg = "different CSV files"
            rtol = max(args.rtol, deck_csv_tolerance(deck))
            for f in files if msg is None else []:
                w, m = compare_file(os.path.join(da, "csv", f), os.path.join(db, "csv", f), rtol, args.atol)
                if m:
                    msg = f"{f}: {m}"
                    break
                worst = max(worst, w)
            if msg:
                print(f"FAIL {name}: {msg}")
                nfail += 1
            else:
                print(f"ok   {name}: largest relative difference {worst:.2e}")
                npass += 1
    print(f"{npass} passed, {nfail} failed")
    return 1 if nfail else 0


if __name__ == "__main__":
    sys.exit(main())
