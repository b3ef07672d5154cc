#!/usr/bin/env python3
"""The order of a deck's lines does not change its results.

usage: check_order.py SUPERJOIN MODE WORKDIR [DECK ...]

MODE is what is put in another order, in every deck given (default: the
verification decks, tests/decks and decks/):

  nodes    the data lines of each *NODE block
  elements the data lines (with their continuation lines) of each *ELEMENT block
  blocks   the whole *SUBSTRUCTURE ... *END SUBSTRUCTURE and *PART ... *END PART
           blocks among themselves

(a block read with GENERATE or INPUT= is left as it is). Not the sets: the
order of a set's entries is meaningful (two node sets of a contact are paired
in their order; a pretension section numbers its copies in the order of its
faces, as ccx). Each deck and its
variant (a seeded shuffle: the same variant in every run) are solved with
--csv; both runs must end with the same exit status, and every CSV file must
hold the same rows, matched by their identifier columns (node, element, dof,
...: the rows' order may follow the input) and equal to 1e-9 of the file's
largest value, or the deck's own "** csv-tolerance:", above an absolute 1e-12
(round-off of the assembly's other order). A variant equal to its deck is
skipped. Found by it (2026-12-03): the copies of a *PRE-TENSION SECTION's
nodes were numbered in the order of the *NODE lines.
"""
import glob
import os
import random
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "tools"))
from equiv import ID_COLUMNS, as_float, deck_csv_tolerance, read_csv   # noqa: E402

RTOL, ATOL = 1e-9, 1e-12
SHUFFLED = {"nodes": ("*NODE",), "elements": ("*ELEMENT",)}


def keyword(line):
    return line.strip().upper().split(",")[0].strip()


def shuffle_data(lines, rng, mode):
    """The deck with the data lines of the blocks of MODE's keywords shuffled."""
    out, i = [], 0
    while i < len(lines):
        line = lines[i]
        out.append(line)
        i += 1
        upper = line.strip().upper()
        if not upper.startswith("*") or upper.startswith("**") or keyword(line) not in SHUFFLED[mode]:
            continue
        if "GENERATE" in upper or "INPUT=" in upper:
            continue
        records, cur = [], []
        while i < len(lines) and not lines[i].lstrip().startswith("*"):
            cur.append(lines[i])
            i += 1
            if mode != "elements" or not cur[-1].rstrip().endswith(","):   # an element's line continues
                records.append(cur)
                cur = []
        if cur:
            records.append(cur)
        rng.shuffle(records)
        for r in records:
            out.extend(r)
    return out


def shuffle_blocks(lines, rng):
    """The deck with its substructure and part blocks in another order."""
    spans, i = [], 0
    while i < len(lines):
        kw = keyword(lines[i])
        if kw in ("*SUBSTRUCTURE", "*PART"):
            j = i + 1
            while j < len(lines) and keyword(lines[j]) != "*END " + kw[1:]:
                j += 1
            spans.append((i, j + 1))
            i = j + 1
        else:
            i += 1
    if len(spans) < 2:
        return lines
    order = list(range(len(spans)))
    while order == sorted(order):
        rng.shuffle(order)
    out, prev = [], 0
    for k, (a, b) in enumerate(spans):
        out.extend(lines[prev:a])
        out.extend(lines[spans[order[k]][0]:spans[order[k]][1]])
        prev = b
    out.extend(lines[prev:])
    return out


def solve(binary, deck, outdir):
    os.makedirs(outdir, exist_ok=True)
    p = subprocess.run([binary, "-q", os.path.basename(deck), "-o", os.path.join(outdir, "out.lst"),
                        "--csv", os.path.join(outdir, "csv")], cwd=os.path.dirname(deck),
                       capture_output=True, text=True, timeout=300)
    return p.returncode, p.stderr


def keyed(path):
    header, rows = read_csv(path)
    ids = [c for c, h in enumerate(header) if h in ID_COLUMNS]
    table = {}
    for r in rows:
        table.setdefault(tuple(r[c] for c in ids), []).append(r)
    return header, table


def compare(fa, fb, tol):
    """None if the two CSV files hold the same rows to tol, else what differs."""
    ha, ta = keyed(fa)
    hb, tb = keyed(fb)
    name = os.path.basename(fa)
    if ha != hb:
        return f"{name}: header differs"
    if set(ta) != set(tb):
        return f"{name}: rows {sorted(set(ta) ^ set(tb))[:3]} in one run only"
    values = [abs(v) for rs in ta.values() for r in rs for c, x in enumerate(r)
              if ha[c] not in ID_COLUMNS and (v := as_float(x)) is not None]
    top = max(values, default=0.0)
    for key, ra in ta.items():
        rb = tb[key]
        if len(ra) != len(rb):
            return f"{name} {key}: {len(ra)} rows against {len(rb)}"
        for x, y in zip(sorted(ra), sorted(rb)):
            for c, h in enumerate(ha):
                if h in ID_COLUMNS:
                    continue
                a, b = as_float(x[c]), as_float(y[c])
                if a is None or b is None:
                    if x[c] != y[c]:
                        return f"{name} {key} {h}: {x[c]!r} against {y[c]!r}"
                elif not (abs(a - b) <= ATOL or abs(a - b) <= tol*max(top, (abs(a) + abs(b))/2)):
                    return f"{name} {key} {h}: {x[c]} against {y[c]}"
    return None


def main():
    if len(sys.argv) < 4 or sys.argv[2] not in (*SHUFFLED, "blocks"):
        print(__doc__)
        return 2
    binary, mode, work = os.path.abspath(sys.argv[1]), sys.argv[2], sys.argv[3]
    decks = sys.argv[4:] or sorted(glob.glob(os.path.join(ROOT, "tests/decks/*.deck")) +
                                   glob.glob(os.path.join(ROOT, "decks/*.deck")))
    shutil.rmtree(work, ignore_errors=True)
    copies = {}   # each deck's folder copied once: the variants sit beside their includes, not in the sources
    npass = nfail = nsame = 0
    for deck in map(os.path.abspath, decks):
        base = os.path.splitext(os.path.basename(deck))[0]
        src = os.path.dirname(deck)
        if src not in copies:
            copies[src] = os.path.join(work, f"src{len(copies)}")
            shutil.copytree(src, copies[src])
        deck = os.path.join(copies[src], os.path.basename(deck))
        lines = open(deck, encoding="utf-8", errors="replace").read().splitlines(True)
        if lines and not lines[-1].endswith("\n"):
            lines[-1] += "\n"
        rng = random.Random(f"{mode}:{base}")
        variant = shuffle_blocks(lines, rng) if mode == "blocks" else shuffle_data(lines, rng, mode)
        if variant == lines:
            nsame += 1
            continue
        wd = os.path.join(work, base)
        os.makedirs(wd)
        shuffled = os.path.join(os.path.dirname(deck), f"{base}.{mode}")
        with open(shuffled, "w") as f:
            f.write("".join(variant))
        rca, erra = solve(binary, deck, os.path.join(wd, "a"))
        rcb, errb = solve(binary, shuffled, os.path.join(wd, "b"))
        why = None
        if rca != rcb:
            why = f"exit {rca} against {rcb}: {errb.strip()[:300]}"
        elif rca in (0, 3):
            tol = max(RTOL, deck_csv_tolerance(deck))
            for fa in sorted(glob.glob(os.path.join(wd, "a", "csv", "*.csv"))):
                fb = fa.replace(os.path.join(wd, "a"), os.path.join(wd, "b"))
                why = compare(fa, fb, tol) if os.path.exists(fb) else f"{os.path.basename(fb)} missing"
                if why:
                    break
        if why:
            print(f"FAIL {base}: {why} (variant: {shuffled})")
            nfail += 1
        else:
            npass += 1
    print(f"{npass} passed, {nfail} failed ({nsame} decks without {mode} to reorder)")
    return 1 if nfail or npass == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
