#!/usr/bin/env python3
"""Superelements that travel (issue 26): CalculiX's substructure layout.

blk_ccx.mtx was written by CalculiX 2.20 (`ccx -i blk_ccx`, Debian 12
calculix-ccx) for blk_ccx.inp, a block of three C3D8 clamped at x = 0 with its
tip face retained (*SUBSTRUCTURE GENERATE). blk_static.inp is the same block
loaded at the tip, and blk_static.dat.ref the .dat that ccx 2.20 writes for it.

1. import: blk_ccx.mtx read with *MATRIX INPUT, FORMAT=CALCULIX, loaded as in
   blk_static.inp: the tip displacements must equal the solution of that
   matrix, read and solved here independently, to 1e-10.
2. reproduce CalculiX's result: blk_static.inp's block (our deck reader takes
   it as written) with its tip joined rigidly to a LOAD substructure that
   carries the loads is exported with FORMAT=CALCULIX (K* on the clamped and
   the tip nodes), imported again (the clamp as *BOUNDARY, the same joints):
   the LOAD displacements must equal the explicit run to 1e-10 and CalculiX's
   .dat to its 7 printed digits.
3. RETAIN=TIP: the block exported with its tip retained by a node set (no
   joint), imported with the clamp as *BOUNDARY: equal to the explicit run.
(CalculiX 2.20's own matrix is not the condensed stiffness of its own static
model: its solution differs from blk_static.dat.ref by a factor of about four;
see the README.)

usage: ccx_import.py SUPERJOIN WORKDIR
"""
import csv
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TIP = (13, 14, 15, 16)
LOADS = [(13, 1, 100.0), (14, 2, -50.0), (15, 3, 200.0), (16, 1, -30.0), (16, 3, 40.0)]


def solve(a, b):
    n = len(b)
    a = [r[:] for r in a]
    b = b[:]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(a[i][k]))
        a[k], a[p] = a[p], a[k]
        b[k], b[p] = b[p], b[k]
        for i in range(k + 1, n):
            m = a[i][k] / a[k][k]
            for j in range(k, n):
                a[i][j] -= m * a[k][j]
            b[i] -= m * b[k]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (b[i] - sum(a[i][j] * x[j] for j in range(i + 1, n))) / a[i][i]
    return x


def read_ccx_mtx(path):
    """(node, dof) per row and the full matrix of a CalculiX .mtx (one DOF per position)."""
    text = open(path).read().splitlines()
    nodes, rows, vals, section = [], [], [], 0
    for ln in text:
        s = ln.strip()
        if s.upper().startswith("** ELEMENT NODES"):
            section = 1
        elif s.startswith("**") and section == 1:
            nodes += [int(x) for x in s[2:].split(",") if x.strip()]
        elif s.upper().startswith("*USER ELEMENT"):
            section = 2
        elif s.upper().startswith("*MATRIX"):
            section = 3
        elif section in (1, 2) and s and not s.startswith("*"):
            f = [int(x) for x in s.split(",") if x.strip()]
            rows.append(f[-1])
        elif section == 3 and s:
            vals += [float(x) for x in s.split(",") if x.strip()]
    keys = list(zip(nodes, rows))
    n = len(keys)
    k = [[0.0] * n for _ in range(n)]
    c = 0
    for i in range(n):
        for j in range(i + 1):
            k[i][j] = k[j][i] = vals[c]
            c += 1
    assert c == len(vals)
    return keys, k


def run(binary, work, name, text):
    path = os.path.join(work, name + ".inp")
    with open(path, "w") as fh:
        fh.write(text)
    out = os.path.join(work, name)
    p = subprocess.run([binary, "-q", path, "-o", out + ".lst", "--csv", out], capture_output=True, text=True,
                       cwd=work)
    if p.returncode != 0:
        raise SystemExit(f"FAIL: {name} exited with {p.returncode}: {(p.stderr or p.stdout).strip()[:600]}")
    res = {}
    with open(os.path.join(out, "displacements.csv")) as fh:
        for row in csv.DictReader(fh):
            res[(row["substructure"], int(row["node"]))] = [float(row[c]) for c in ("u1", "u2", "u3")]
    return res


def report(ok, what):
    print(f"{'ok' if ok else 'FAIL'}: {what}")
    return ok


def import_ccx(binary, work):
    keys, k = read_ccx_mtx(os.path.join(HERE, "blk_ccx.mtx"))
    f = [0.0] * len(keys)
    for nd, dof, v in LOADS:
        f[keys.index((nd, dof))] = v
    x = solve(k, f)
    deck = ["*SUBSTRUCTURE, NAME=BLK", "*NODE"] + [f"{n}, 3.0, {y}, {z}" for n, y, z in
                                                  ((13, 0, 0), (14, 1, 0), (15, 1, 1), (16, 0, 1))]
    deck += [f"*MATRIX INPUT, INPUT={os.path.join(HERE, 'blk_ccx.mtx')}, FORMAT=CALCULIX", "*END SUBSTRUCTURE",
             "*STEP", "*CLOAD"] + [f"BLK.{n}, {d}, {v}" for n, d, v in LOADS] + ["*END STEP"]
    got = run(binary, work, "import_ccx", "\n".join(deck) + "\n")
    scale = max(abs(v) for v in x)
    worst = max(abs(got[("BLK", n)][d - 1] - x[keys.index((n, d))]) for n, d in keys) / scale
    return report(worst <= 1e-10, f"CalculiX's .mtx imported: {len(keys)} DOFs, largest difference {worst:.2e} "
                  "from the independent solve of that matrix")


def static_deck(export=None, matrix=None):
    """blk_static.inp with the tip joined rigidly to LOAD (which carries the loads)."""
    text = open(os.path.join(HERE, "blk_static.inp")).read().split("*STEP")[0]
    if matrix is not None:
        text = text.split("*ELEMENT")[0] + f"*MATRIX INPUT, INPUT={matrix}, FORMAT=CALCULIX\n" + \
            "*NSET, NSET=FIX\n1, 2, 3, 4\n*BOUNDARY\nFIX, 1, 3\n"
    d = [text.rstrip("\n"), "*SUBSTRUCTURE, NAME=LOAD", "*NODE"]
    d += [f"{n}, 3.0, {y}, {z}" for n, y, z in ((13, 0, 0), (14, 1, 0), (15, 1, 1), (16, 0, 1))]
    d += ["*END SUBSTRUCTURE", "*CONTACT, NAME=TIE, MASTER=MAIN, SLAVE=LOAD"] + [f"{n}, {n}, 1, 3, RIGID" for n in TIP]
    if export:
        d.append(f"*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=MAIN, FILE NAME={export}, FORMAT=CALCULIX")
    d += ["*STEP", "*STATIC", "*CLOAD"] + [f"LOAD.{n}, {dd}, {v}" for n, dd, v in LOADS] + ["*END STEP"]
    return "\n".join(d) + "\n"


def reproduce_ccx(binary, work):
    ref = {}
    for ln in open(os.path.join(HERE, "blk_static.dat.ref")):
        f = ln.split()
        if len(f) == 4 and f[0].isdigit():
            ref[int(f[0])] = [float(v) for v in f[1:]]
    explicit = run(binary, work, "static_export", static_deck(export="blk_sj"))
    imported = run(binary, work, "static_import", static_deck(matrix="blk_sj.mtx"))
    scale = max(abs(v) for vals in ref.values() for v in vals)
    worst_e = max(abs(a - b) for n in TIP for a, b in zip(explicit[("LOAD", n)], imported[("LOAD", n)])) / scale
    worst_c = max(abs(a - b) for n in TIP for a, b in zip(ref[n], imported[("LOAD", n)])) / scale
    ok1 = report(worst_e <= 1e-10, f"our CALCULIX-layout export imported: largest difference {worst_e:.2e} "
                 "from the explicit block")
    ok2 = report(worst_c <= 1e-6, f"... and {worst_c:.2e} from CalculiX's blk_static.dat.ref (7 digits)")
    return ok1 and ok2


def retained_export(binary, work):
    """RETAIN=TIP: the tip kept on the boundary without a joint; the imported
    matrix (clamp as *BOUNDARY, loads on the tip nodes) gives CalculiX's result."""
    text = open(os.path.join(HERE, "blk_static.inp")).read()
    head, step = text.split("*STEP")
    head += "*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=MAIN, FILE NAME=blk_r, RETAIN=TIP\n"
    explicit = run(binary, work, "retain_export", head + "*STEP" + step)
    deck = head.split("*ELEMENT")[0] + "*MATRIX INPUT, INPUT=blk_r.mtx\n*NSET, NSET=FIX\n1, 2, 3, 4\n*NSET, NSET=TIP\n13, 14, 15, 16\n" + \
        "*BOUNDARY\nFIX, 1, 3\n*STEP" + step
    imported = run(binary, work, "retain_import", deck)
    scale = max(abs(v) for n in TIP for v in explicit[("MAIN", n)])
    worst = max(abs(a - b) for n in TIP for a, b in zip(explicit[("MAIN", n)], imported[("MAIN", n)])) / scale
    return report(worst <= 1e-10, f"RETAIN=TIP export imported: largest difference {worst:.2e} from the explicit block")


def main():
    binary, work = sys.argv[1], os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    results = [import_ccx(binary, work), reproduce_ccx(binary, work), retained_export(binary, work)]
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
