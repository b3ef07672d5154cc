#!/usr/bin/env python3
"""Superelements that travel (issue 26): CalculiX's substructure layout.

Every .mtx here was written by CalculiX 2.20 (Debian 12 calculix-ccx 2.20-1,
`ccx -i NAME`, unchanged) for the .inp of the same name, written for this
test; blk_static.dat.ref is the .dat of `ccx -i blk_static`.

CalculiX 2.20's *SUBSTRUCTURE GENERATE does not condense: the matrix it writes
is the retained block K_bb of the assembled stiffness with every other free
DOF held at zero, not K_bb - K_bi K_ii^-1 K_ib (see the README). The closed
forms are the referee:

1. truss_ccx: 4 T3D2 in a chain (L = 4, A = 2, E = 1000), clamped, tip node
   retained in x. K* = EA/L = 500: superjoin's K* to 1e-12; CalculiX's
   .mtx holds 2000 = EA/(L/4), the tip bar alone. CalculiX's own static run
   (truss_static.inp, 50 at the tip) gives PL/(EA) = 0.1 (its .dat); the
   .mtx imported with *MATRIX INPUT and loaded alike gives 0.025.
2. bar_ccx: 4 unit C3D8 in a row (nu = 0, DOFs 2, 3 held), tip face retained
   in x: the entries of K* sum to EA/L = 250 (superjoin, 1e-12); those of
   CalculiX's .mtx to 1000 = EA/(L/4).
3. blk_ccx: the clamped block of three C3D8, tip face retained: CalculiX's
   .mtx equals, entry by entry to 1e-12 of its largest entry (13 printed
   digits), superjoin's K* of the same block with the interior nodes 5-12
   clamped too, and is far (> 0.1) from superjoin's K* of the block.
4. import: blk_ccx.mtx read with *MATRIX INPUT, FORMAT=CALCULIX, loaded as
   blk_static.inp: equal to the solution of that matrix, read and solved
   here independently, to 1e-10.
5. blk_all: the block with every free node retained (no interior DOF; the
   defect cannot bite) is CalculiX's genuine stiffness: equal to superjoin's
   K* (RETAIN=FREE) entry by entry to 1e-12, and, condensed to the tip here,
   to superjoin's K* of the tip (RETAIN=TIP) to 1e-10; imported with
   *MATRIX INPUT, FORMAT=CALCULIX and loaded as blk_static.inp, it gives
   CalculiX's own static result (blk_static.dat.ref) to its 7 printed digits,
   and the independent solve of the matrix to 1e-10. Negative control: the
   same file with nodes 13 and 14 swapped in its node list misses the
   reference by more than 1e-2.
6. reproduce CalculiX's result through superjoin's own export: blk_static.inp's
   block with its tip joined rigidly to a LOAD substructure that carries the
   loads, exported with FORMAT=CALCULIX and imported again: equal to the
   explicit run to 1e-10 and to CalculiX's .dat to its printed digits.
7. RETAIN=TIP: the block exported with its tip retained by a node set (no
   joint), imported with the clamp as *BOUNDARY: equal to the explicit run.

usage: ccx_import.py SUPERJOIN WORKDIR
"""
import csv
import math
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


def read_sj_mtx(path):
    """superjoin's ABAQUS-layout K*: {(node, dof, node, dof): value}, both triangles."""
    k = {}
    for ln in open(path):
        if ln.startswith("**") or not ln.strip():
            continue
        a, b, c, d, v = [x.strip() for x in ln.split(",")]
        k[(int(a), int(b), int(c), int(d))] = k[(int(c), int(d), int(a), int(b))] = float(v)
    return k


def ccx_model(name):
    """The model data of a CalculiX deck here (everything before its *STEP)."""
    return open(os.path.join(HERE, name + ".inp")).read().split("*STEP")[0]


def sj_export(binary, work, name, model, retain, bcs=""):
    """superjoin's K* of MAIN (the ccx model data as written, extra *BOUNDARY
    lines `bcs`) with node set `retain` kept, as {(node, dof, node, dof): value}."""
    deck = model + (f"*BOUNDARY\n{bcs}" if bcs else "") + \
        f"*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=MAIN, FILE NAME={name}, RETAIN={retain}\n" + \
        "*STEP\n*STATIC\n*END STEP\n"
    run(binary, work, name, deck)
    return read_sj_mtx(os.path.join(work, name + ".mtx"))


def ccx_entries(path):
    """CalculiX's .mtx as {(node, dof, node, dof): value} and its (node, dof) keys."""
    keys, k = read_ccx_mtx(path)
    return keys, {(a, b, c, d): k[i][j] for i, (a, b) in enumerate(keys) for j, (c, d) in enumerate(keys)}


def matrix_gap(keys, a, b):
    """Largest |a - b| over keys x keys, relative to the largest |a|."""
    scale = max(abs(a.get((n1, d1, n2, d2), 0.0)) for n1, d1 in keys for n2, d2 in keys)
    return max(abs(a.get((n1, d1, n2, d2), 0.0) - b.get((n1, d1, n2, d2), 0.0))
               for n1, d1 in keys for n2, d2 in keys) / scale


def closed_form_truss(binary, work):
    """4 T3D2, L = 4, A = 2, E = 1000: K* = EA/L = 500; ccx 2.20 writes EA/(L/4)."""
    ea_l, n = 1000.0 * 2.0 / 4.0, 4
    sj = sj_export(binary, work, "truss_sj", ccx_model("truss_ccx"), "TIP")[(5, 1, 5, 1)]
    keys, ccx = ccx_entries(os.path.join(HERE, "truss_ccx.mtx"))
    ok1 = report(keys == [(5, 1)] and abs(sj - ea_l) <= 1e-12 * ea_l,
                 f"truss chain: superjoin's K* {sj!r} = EA/L = {ea_l}")
    ok2 = report(abs(ccx[(5, 1, 5, 1)] - n * ea_l) <= 1e-12 * n * ea_l,
                 f"... CalculiX 2.20's .mtx {ccx[(5, 1, 5, 1)]!r} = {n} EA/L (the tip bar alone), "
                 f"not EA/L")
    ref = [float(ln.split()[1]) for ln in open(os.path.join(HERE, "truss_static.dat.ref"))
           if ln.split() and ln.split()[0] == "5"][0]
    deck = ["*SUBSTRUCTURE, NAME=TR", "*NODE", "5, 4., 0., 0.",
            f"*MATRIX INPUT, INPUT={os.path.join(HERE, 'truss_ccx.mtx')}, FORMAT=CALCULIX", "*END SUBSTRUCTURE",
            "*STEP", "*CLOAD", "TR.5, 1, 50.", "*END STEP"]
    u = run(binary, work, "import_truss", "\n".join(deck) + "\n")[("TR", 5)][0]
    ok3 = report(abs(ref - 50.0 / ea_l) <= 5e-7 * abs(ref) and abs(u - 50.0 / (n * ea_l)) <= 1e-12 * abs(u),
                 f"... CalculiX's own static tip displacement {ref} = PL/(EA); its .mtx imported gives {u!r}, "
                 f"1/{n} of it")
    return ok1 and ok2 and ok3


def closed_form_bar(binary, work):
    """4 unit C3D8, nu = 0, lateral DOFs held: the tip entries of K* sum to EA/L."""
    ea_l, n, tip = 1000.0 * 1.0 / 4.0, 4, (17, 18, 19, 20)
    sj = sj_export(binary, work, "bar_sj", ccx_model("bar_ccx"), "TIP")
    keys, ccx = ccx_entries(os.path.join(HERE, "bar_ccx.mtx"))
    total_sj = sum(sj[(a, 1, b, 1)] for a in tip for b in tip)
    total_ccx = sum(ccx[(a, 1, b, 1)] for a in tip for b in tip)
    ok1 = report(keys == [(t, 1) for t in tip] and abs(total_sj - ea_l) <= 1e-12 * ea_l,
                 f"C3D8 bar: superjoin's K* sums to {total_sj!r} = EA/L = {ea_l}")
    ok2 = report(abs(total_ccx - n * ea_l) <= 1e-12 * n * ea_l,
                 f"... CalculiX 2.20's .mtx to {total_ccx!r} = {n} EA/L (the tip element alone)")
    return ok1 and ok2


def defect_block(binary, work):
    """blk_ccx.mtx is K_bb: superjoin's K* with the interior nodes clamped too."""
    keys, ccx = ccx_entries(os.path.join(HERE, "blk_ccx.mtx"))
    kbb = sj_export(binary, work, "blk_kbb", ccx_model("blk_ccx"), "TIP",
                    "".join(f"{n}, 1, 3\n" for n in range(5, 13)))
    kstar = sj_export(binary, work, "blk_kstar", ccx_model("blk_ccx"), "TIP")
    gap_bb, gap_star = matrix_gap(keys, ccx, kbb), matrix_gap(keys, ccx, kstar)
    return report(gap_bb <= 1e-12 and gap_star > 0.1,
                  f"blk_ccx.mtx = K_bb with the interior clamped to {gap_bb:.1e} (13 digits); "
                  f"{gap_star:.2f} from superjoin's K* (diagonal {kstar[(13, 1, 13, 1)]:.6g}, "
                  f"CalculiX {ccx[(13, 1, 13, 1)]:.6g})")


def condense(keys, k, kept):
    """Static condensation of the dense k on keys onto the keys in kept."""
    b = [i for i, key in enumerate(keys) if key in kept]
    i_ = [i for i, key in enumerate(keys) if key not in kept]
    cols = [solve([[k[r][c] for c in i_] for r in i_], [k[r][j] for r in i_]) for j in b]
    return {keys[p] + keys[q]: k[p][q] - sum(k[p][r] * x for r, x in zip(i_, cols[jq]))
            for p in b for jq, q in enumerate(b)}


def static_ref():
    ref = {}
    for ln in open(os.path.join(HERE, "blk_static.dat.ref")):
        f = ln.split()
        if len(f) == 4 and f[0].isdigit():
            ref[int(f[0])] = [float(v) for v in f[1:]]
    return ref


def import_block(binary, work, name, mtx):
    """mtx on the block's nodes 5..16, loaded as blk_static.inp: tip displacements."""
    coords = ccx_model("blk_static").split("*NODE")[1].split("*")[0].splitlines()[1:]
    deck = ["*SUBSTRUCTURE, NAME=BLK", "*NODE"] + [c for c in coords if int(c.split(",")[0]) > 4]
    deck += [f"*MATRIX INPUT, INPUT={mtx}, FORMAT=CALCULIX", "*END SUBSTRUCTURE", "*STEP", "*CLOAD"]
    deck += [f"BLK.{n}, {d}, {v}" for n, d, v in LOADS] + ["*END STEP"]
    got = run(binary, work, name, "\n".join(deck) + "\n")
    return {n: got[("BLK", n)] for n in TIP}


def digits_gap(got, ref):
    """Largest |got - ref| in units of half the last printed digit of ref (d.dddddd E+xx)."""
    # a printed 0 has no digits of its own: judged in the unit of the largest printed value
    top = max(abs(r) for n in TIP for r in ref[n])
    unit = lambda r: 5e-7 * 10.0 ** math.floor(math.log10(abs(r) if r != 0.0 else top))
    return max(abs(g - r) / unit(r) for n in TIP for g, r in zip(got[n], ref[n]))


def full_matrix(binary, work):
    """blk_all.mtx (no interior DOF): CalculiX's genuine stiffness, its static result."""
    path = os.path.join(HERE, "blk_all.mtx")
    keys, ccx = ccx_entries(path)
    free = sj_export(binary, work, "blk_free", ccx_model("blk_static") + "*NSET, NSET=FREE\n" +
                     ", ".join(str(n) for n in range(5, 17)) + "\n", "FREE")
    ok1 = report(matrix_gap(keys, ccx, free) <= 1e-12,
                 f"blk_all.mtx ({len(keys)} DOFs) = superjoin's K* (RETAIN=FREE) to "
                 f"{matrix_gap(keys, ccx, free):.1e}")
    _, k = read_ccx_mtx(path)
    tipkeys = [(n, d) for n in TIP for d in (1, 2, 3)]
    cond = condense(keys, k, set(tipkeys))
    kstar = sj_export(binary, work, "blk_tip", ccx_model("blk_static"), "TIP")
    gap = matrix_gap(tipkeys, cond, kstar)
    ok2 = report(gap <= 1e-10, f"... condensed to the tip here: superjoin's K* (RETAIN=TIP) to {gap:.1e}")
    ref = static_ref()
    got = import_block(binary, work, "import_all", path)
    f = [0.0] * len(keys)
    for nd, dof, v in LOADS:
        f[keys.index((nd, dof))] = v
    x = solve(k, f)
    scale = max(abs(v) for vals in ref.values() for v in vals)
    worst = max(abs(got[n][d - 1] - x[keys.index((n, d))]) for n in TIP for d in (1, 2, 3)) / scale
    ok3 = report(worst <= 1e-10 and digits_gap(got, ref) <= 1.0,
                 f"... imported: {worst:.1e} from its independent solve, CalculiX's blk_static.dat.ref to "
                 f"{digits_gap(got, ref):.2f} half-units of its 7th digit")
    text = open(path).read().replace("13,        13,        13,        14,        14,        14,",
                                     "14,        14,        14,        13,        13,        13,", 1)
    swapped = os.path.join(work, "blk_swapped.mtx")
    with open(swapped, "w") as fh:
        fh.write(text)
    bad = import_block(binary, work, "import_swapped", swapped)
    miss = max(abs(g - r) for n in TIP for g, r in zip(bad[n], ref[n])) / scale
    ok4 = report(text != open(path).read() and miss > 1e-2,
                 f"... negative control: nodes 13 and 14 swapped in its node list miss it by {miss:.2f}")
    return ok1 and ok2 and ok3 and ok4


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
    ref = static_ref()
    explicit = run(binary, work, "static_export", static_deck(export="blk_sj"))
    imported = run(binary, work, "static_import", static_deck(matrix="blk_sj.mtx"))
    scale = max(abs(v) for vals in ref.values() for v in vals)
    worst_e = max(abs(a - b) for n in TIP for a, b in zip(explicit[("LOAD", n)], imported[("LOAD", n)])) / scale
    gap = digits_gap({n: imported[("LOAD", n)] for n in TIP}, ref)
    ok1 = report(worst_e <= 1e-10, f"our CALCULIX-layout export imported: largest difference {worst_e:.2e} "
                 "from the explicit block")
    ok2 = report(gap <= 1.0, f"... and CalculiX's blk_static.dat.ref to {gap:.2f} half-units of its 7th digit")
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
    results = [closed_form_truss(binary, work), closed_form_bar(binary, work), defect_block(binary, work),
               import_ccx(binary, work), full_matrix(binary, work), reproduce_ccx(binary, work),
               retained_export(binary, work)]
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
