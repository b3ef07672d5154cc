#!/usr/bin/env python3
"""The condensation library across runs (issue 26, --library DIR).

A design study on a grid of plane-stress panels (bench/gen_panel_grid.py,
3 x 2 panels, each a substructure of its own, all condensed):

1. run twice with the same --library: the first run condenses and stores
   every panel, the second loads every one; the listings are byte-identical
   apart from those notes, and the CSV files are byte-identical (on several
   processes: within round-off, below).
2. one panel changed (its thickness): that panel alone is condensed and
   stored, the five others are loaded; the results equal those of a run with
   a fresh library, to the byte.
3. an entry with a byte flipped, a truncated entry, and (checksum made right
   again) an entry of another format version, magic or key, with counts
   beyond the file's size or bytes after its last field are never used (and
   never allocated by those counts): one note each,
   the panel condensed anew, and the same results to the byte.
4. no temporary file is left in the library, and the results with the
   library equal those without it to round-off (1e-10: recovery goes through
   the stored operator k_ii^-1 k_ib, not through the factor).

Every entry a run condenses anew (the changed study's fresh library, a
damaged entry replaced) is byte-identical to the entry condensed before: the
library hands back the very K* that condensation forms.

usage: library.py SUPERJOIN WORKDIR [--lstdiff LSTDIFF LAUNCHER ...]

With a launcher (`mpirun -np 2`, the MPI build's test mpi.library) every run
is started through it: each process loads and stores the entries of the
parts it owns, and rank 0 lists every part's library note in order. There
"the same results" is within round-off, not to the byte: MUMPS's parallel
factorization of the interface system is asynchronous (contributions summed
in the order they arrive), so two runs on several processes may differ in
the last bits whatever the library did (measured: 1 run in 8 under load,
CSV values 6e-15 apart relative to each file's largest, the listing's
round-off figures such as the relative residual 3.40e-14 against 3.43e-14).
The listings are then compared by LSTDIFF (numbers to 1e-6 relative and
1e-13 absolute, the health block's round-off figures to 2e-2: below) and
the CSV files, which hold every listed result at full precision, to 1e-12
of each file's largest value; the entries stay byte-identical (each process
condenses alone).
"""
import glob
import hashlib
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import equiv  # noqa: E402

RTOL = 1e-10
PARALLEL_RTOL = 1e-12   # two runs on several processes: MUMPS's round-off (measured 6e-15)
PANELS = 6
FAILED = []
LAUNCHER = []
LSTDIFF = []
# lstdiff's tolerances for two runs on several processes: numbers to 1e-6
# relative (the listing prints 7 digits: its last may flip) and 1e-13
# absolute (the residual-check table's round-off figures, ~1e-14, may
# differ; a displacement of 1e-7 may not), the health block's round-off
# figures to 2e-2 relative or both below 1e-9 (as the deck tests).
LSTDIFF_TOLERANCES = ["--rtol", "1e-6", "--atol", "1e-13", "--health-rtol", "2e-2", "--health-floor", "1e-9"]


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        FAILED.append(what)


def solve(binary, deck, name, work, library=None):
    lst = os.path.join(work, name + ".lst")
    csvdir = os.path.join(work, name + ".csv")
    cmd = LAUNCHER + [binary, "-q", "--condense", "yes", deck, "-o", lst, "--csv", csvdir]
    if library:
        cmd += ["--library", library]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        print(f"FAIL: {name} exited with {p.returncode}: {p.stderr.strip()[:300]}")
        sys.exit(1)
    with open(lst) as fh:
        lines = fh.read().splitlines()
    return lines, csvdir


def notes(lines, text):
    return sum(1 for line in lines if "library:" in line and text in line)


def body(lines):
    return [line for line in lines if "library:" not in line]


def same_csv(a, b):
    fa, fb = sorted(os.listdir(a)), sorted(os.listdir(b))
    if fa != fb:
        return False
    if LAUNCHER:
        bad = [(f, equiv.compare_file(os.path.join(a, f), os.path.join(b, f), PARALLEL_RTOL, 0.0)[1]) for f in fa]
        for f, msg in bad:
            if msg:
                print(f"  {f}: {msg}")
        return not any(msg for _, msg in bad)
    return all(open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read() for f in fa)


def same_listing(a, b, work):
    """Bodies equal: to the byte on one process, within LSTDIFF_TOLERANCES on several."""
    if not LAUNCHER:
        return body(a) == body(b)
    paths = []
    for k, lines in enumerate((a, b)):
        paths.append(os.path.join(work, f"body{k}.lst"))
        with open(paths[-1], "w") as fh:
            fh.write("\n".join(body(lines)) + "\n")
    p = subprocess.run(LSTDIFF + LSTDIFF_TOLERANCES + paths, capture_output=True, text=True)
    if p.returncode != 0:
        print("  " + (p.stdout + p.stderr).strip().replace("\n", "\n  ")[:2000])
    return p.returncode == 0


def same_results(x, y, work):
    (a, a_csv), (b, b_csv) = x, y
    return same_listing(a, b, work) and same_csv(a_csv, b_csv)


def entry_bytes(lib):
    return {os.path.basename(f): open(f, "rb").read() for f in glob.glob(os.path.join(lib, "*.sjc"))}


def rewrite(path, edit):
    data = bytearray(open(path, "rb").read())
    data = edit(data)
    with open(path, "wb") as fh:
        fh.write(data)


def restamp(data):
    """The checksum (last 64 bytes: SHA-256 of what precedes, hexadecimal) made right again."""
    return data[:-64] + hashlib.sha256(bytes(data[:-64])).hexdigest().encode()


def main():
    binary, work = sys.argv[1], sys.argv[2]
    rest = sys.argv[3:]
    if rest:
        if len(rest) < 3 or rest[0] != "--lstdiff":
            print(__doc__)
            return 2
        LSTDIFF.append(rest[1])
        LAUNCHER.extend(rest[2:])
    exact = "within round-off (several processes)" if LAUNCHER else "to the byte"
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    gen = os.path.join(ROOT, "bench", "gen_panel_grid.py")
    deck = os.path.join(work, "grid.deck")
    with open(deck, "w") as fh:
        subprocess.run([sys.executable, gen, "--nx", "3", "--ny", "2", "--mesh", "6"], stdout=fh, check=True)
    lib = os.path.join(work, "lib")

    a, a_csv = solve(binary, deck, "first", work, lib)
    b, b_csv = solve(binary, deck, "second", work, lib)
    check(notes(a, "condensed and stored") == PANELS, f"first run: {PANELS} panels condensed and stored")
    check(notes(b, "loaded from library") == PANELS, f"second run: {PANELS} panels loaded from library")
    check(same_listing(a, b, work), f"listings equal apart from the library notes, {exact}")
    check(same_csv(a_csv, b_csv), f"CSV files equal, {exact}")
    entries = sorted(glob.glob(os.path.join(lib, "*.sjc")))
    check(len(entries) == PANELS, f"{PANELS} entries in the library")
    stored = entry_bytes(lib)

    # one panel changed: its thickness
    text = open(deck).read()
    first = text.index("*SOLID SECTION")
    cut = text.index("\n", first) + 1
    changed = os.path.join(work, "changed.deck")
    with open(changed, "w") as fh:
        fh.write(text[:cut] + text[cut:].replace("0.05", "0.06", 1))
    c, c_csv = solve(binary, changed, "changed", work, lib)
    check(notes(c, "condensed and stored") == 1 and notes(c, "loaded from library") == PANELS - 1,
          "one panel changed: 1 condensed and stored, the others loaded")
    d, d_csv = solve(binary, changed, "fresh", work, os.path.join(work, "lib_fresh"))
    check(same_results((c, c_csv), (d, d_csv), work), f"changed study equals a run with a fresh library, {exact}")
    fresh, now = entry_bytes(os.path.join(work, "lib_fresh")), entry_bytes(lib)
    unchanged = set(fresh) & set(stored)
    check(len(unchanged) == PANELS - 1 and all(fresh[k] == stored[k] for k in unchanged)
          and set(fresh) <= set(now) and all(fresh[k] == now[k] for k in fresh),
          f"a fresh library's {PANELS} entries byte-identical to those stored before ({len(unchanged)} unchanged panels)")

    # stale and corrupt entries
    victims = [("a flipped byte", "corrupt", lambda x: x[:300] + bytes([x[300] ^ 1]) + x[301:]),
               ("a truncated entry", "corrupt", lambda x: x[:len(x) // 2]),
               ("another format version", "stale", lambda x: restamp(x[:8] + bytes([0] * 8) + x[16:])),
               ("another magic", "not a library entry", lambda x: restamp(b"XXXXXXXX" + x[8:])),
               ("another key", "key mismatch", lambda x: restamp(x[:16] + b"0" * 64 + x[80:])),
               ("a count of load sets beyond the file", "malformed",
                lambda x: restamp(x[:112] + (1 << 62).to_bytes(8, "little") + x[120:])),
               ("a count of DOFs without stiffness beyond the file", "malformed",
                lambda x: restamp(x[:96] + (1 << 61).to_bytes(8, "little") + x[104:])),
               ("bytes after the last field", "malformed", lambda x: restamp(x[:-64] + bytes(8) + x[-64:]))]
    for what, word, edit in victims:
        entry = entries[0]
        rewrite(entry, edit)
        e, e_csv = solve(binary, deck, "damaged", work, lib)
        check(notes(e, "not used") == 1 and notes(e, word) == 1 and notes(e, "condensed and stored") == 1
              and notes(e, "loaded from library") == PANELS - 1, f"{what}: one note ({word}), the panel condensed anew")
        check(same_results((e, e_csv), (a, a_csv), work), f"{what}: the same results, {exact}")
        check(open(entry, "rb").read() == stored[os.path.basename(entry)],
              f"{what}: the entry stored anew byte-identical to the first")
    check(not [f for f in os.listdir(lib) if not f.endswith((".sjc", ".sjg"))], "no temporary file left in the library")

    n, n_csv = solve(binary, deck, "nolibrary", work)
    worst = 0.0
    for f in sorted(os.listdir(n_csv)):
        w, msg = equiv.compare_file(os.path.join(n_csv, f), os.path.join(a_csv, f), RTOL, 1e-14)
        worst = max(worst, w)
        if msg:
            check(False, f"{f} without the library: {msg}")
    check(True, f"without the library: every CSV value agrees to 1e-10 (largest relative difference {worst:.2e})")
    print(f"{len(FAILED)} failed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
