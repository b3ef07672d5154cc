#!/usr/bin/env python3
"""Superelements that travel (issue 26): export a condensed part and import it.

A plate part (S4, 4 x 4) is placed twice by *INSTANCE: A as defined, B turned
by 90 degrees about X and moved. Their corners are joined by finite contact
elements (all six DOFs) to a clamped B33 frame BASE. Loads: on A's interior
(so f* differs from A's boundary loads), on B's corner and on BASE.

1. explicit: the deck as written (the plates' elements in the model), solved
   monolithically (--condense no); export: the same deck exporting A with
   *SUBSTRUCTURE MATRIX OUTPUT in every format (A is condensed for it).
2. import: the plate part replaced by a part of its four corners whose
   stiffness is A's exported K* (*MATRIX INPUT, FORMAT=ABAQUS, and again with
   FORMAT=CALCULIX); B turned by its *INSTANCE; A's exported f* applied as
   *CLOAD lines (the .load files); once more with B the one instance of a
   second part with the same matrix (its matrix turned at placement, not
   A's condensation turned by the cache). BASE and the corners of A and B must agree
   with the explicit run to 1e-10 (relative to the largest displacement).
3. the DMIG file read back by the small reader below (large-field DMIG*
   entries): its K and P must equal the ABAQUS export to its 10 digits, and
   the Matrix Market files with their CSV DOF map likewise to round-off.

usage: round_trip.py SUPERJOIN WORKDIR
"""
import csv
import os
import subprocess
import sys

RTOL = 1e-10
DIGITS_TOL = {"DMIG": 1e-8}   # the DMIG file's 16-column fields hold 10 significant digits
N = 4                      # elements per side
H = 1.0 / N
G = 1.0e7                  # contact stiffness


def node(i, j):
    return 1 + i + (N + 1) * j


CORNERS = [node(0, 0), node(N, 0), node(0, N), node(N, N)]
CENTRE = node(N // 2, N // 2)
OFF = node(1, 3)


def plate_part(matrix=None, name="PLATE"):
    lines = [f"*PART, NAME={name}", "*NODE"]
    for j in range(N + 1):
        for i in range(N + 1):
            n = node(i, j)
            if matrix is None or n in CORNERS:
                lines.append(f"{n}, {i * H!r}, {j * H!r}, 0.0")
    if matrix is None:
        lines.append("*ELEMENT, TYPE=S4, ELSET=SKIN")
        e = 0
        for j in range(N):
            for i in range(N):
                e += 1
                lines.append(f"{e}, {node(i, j)}, {node(i + 1, j)}, {node(i + 1, j + 1)}, {node(i, j + 1)}")
        lines += ["*SHELL SECTION, ELSET=SKIN, MATERIAL=STEEL", "0.01"]
    else:
        lines.append(f"*MATRIX INPUT, INPUT={matrix[0]}, FORMAT={matrix[1]}")
    lines.append("*END PART")
    return lines


def model_lines(matrix=None, export=False, split=False, heading="plate part joined to a frame"):
    """The deck up to its steps (shared with loads_round_trip.py)."""
    d = ["*HEADING", f"{heading} (tests/travel)", "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e11, 0.3"]
    d += plate_part(matrix)
    if split:
        d += plate_part(matrix, "PLATE2")
    d += ["*ASSEMBLY", "*INSTANCE, NAME=A, PART=PLATE", "*END INSTANCE",
          f"*INSTANCE, NAME=B, PART={'PLATE2' if split else 'PLATE'}", "2.0, 0.0, 0.0",
          "2.0, 0.0, 0.0, 3.0, 0.0, 0.0, 90.0",
          "*END INSTANCE", "*END ASSEMBLY"]
    # BASE: the eight corner positions, a ring of beams under each plate
    pos = {1: (0, 0, 0), 2: (1, 0, 0), 3: (0, 1, 0), 4: (1, 1, 0),
           5: (2, 0, 0), 6: (3, 0, 0), 7: (2, 0, 1), 8: (3, 0, 1)}
    d += ["*SUBSTRUCTURE, NAME=BASE", "*NODE"]
    d += [f"{k}, {x}, {y}, {z}" for k, (x, y, z) in pos.items()]
    d += ["*ELEMENT, TYPE=B33, ELSET=RING",
          "1, 1, 2", "2, 2, 4", "3, 4, 3", "4, 3, 1", "5, 5, 6", "6, 6, 8", "7, 8, 7", "8, 7, 5", "9, 2, 5",
          "*BEAM SECTION, ELSET=RING, MATERIAL=STEEL, SECTION=RECT", "0.05, 0.05", "0.0, 1.0, 1.0",
          "*END SUBSTRUCTURE"]
    for inst, base in (("A", (1, 2, 3, 4)), ("B", (5, 6, 7, 8))):
        d.append(f"*CONTACT, NAME=J{inst}, MASTER=BASE, SLAVE={inst}")
        d += [f"{b}, {c}, 1, 6, {G}" for b, c in zip(base, CORNERS)]
    d += ["*BOUNDARY", "BASE.1, ENCASTRE", "BASE.6, ENCASTRE"]
    if export:
        for fmt, name in (("ABAQUS", "pa"), ("CALCULIX", "pc"), ("DMIG", "pd"), ("MATRIX MARKET", "pm")):
            d.append(f"*SUBSTRUCTURE MATRIX OUTPUT, SUBSTRUCTURE=A, FILE NAME={name}, FORMAT={fmt}")
    return d


def deck(matrix=None, loads_a=None, export=False, split=False):
    """split: B is the one instance of a second part with the same matrix, so
    that its matrix is turned by its own placement (not reused from A's)."""
    d = model_lines(matrix, export, split)
    steps = {"PUSH": [f"B.{CORNERS[3]}, 2, 500.0", "BASE.4, 3, -200.0"],
             "TWIST": [f"B.{CORNERS[1]}, 4, 30.0", "BASE.8, 1, 100.0"]}
    interior = {"PUSH": [f"A.{CENTRE}, 3, -1000.0", f"A.{OFF}, 1, 300.0"],
                "TWIST": [f"A.{OFF}, 5, 40.0", f"A.{CENTRE}, 2, -250.0"]}
    for name, lines in steps.items():
        d += [f"*STEP, NAME={name}", "*CLOAD"] + lines
        d += interior[name] if loads_a is None else loads_a[name]
        d += ["*NODE PRINT, NSET=BASE.RINGN", "U", "*END STEP"] if False else ["*END STEP"]
    return "\n".join(d) + "\n"


def run(binary, work, name, text, extra=()):
    path = os.path.join(work, name + ".inp")
    with open(path, "w") as fh:
        fh.write(text)
    out = os.path.join(work, name)
    p = subprocess.run([binary, "-q", path, "-o", out + ".lst", "--csv", out] + list(extra), capture_output=True,
                       text=True, cwd=work)
    if p.returncode != 0:
        raise SystemExit(f"FAIL: {name} exited with {p.returncode}: {(p.stderr or p.stdout).strip()[:600]}")
    return out


def displacements(csvdir):
    """{(step, substructure, node): [u1..u6]} from the displacement CSV."""
    res = {}
    with open(os.path.join(csvdir, "displacements.csv")) as fh:
        for row in csv.DictReader(fh):
            key = (row["step"], row["substructure"], row["node"])
            res[key] = [float(row[c]) for c in ("u1", "u2", "u3", "ur1", "ur2", "ur3")]
    return res


def compare(ref, got, what, rtol=RTOL):
    scale = max(abs(v) for vals in ref.values() for v in vals)
    worst = 0.0
    n = 0
    for key, vals in got.items():
        if key not in ref:
            continue
        n += 1
        worst = max(worst, max(abs(a - b) for a, b in zip(ref[key], vals)) / scale)
    ok = worst <= rtol and n >= 2 * (8 + 8)
    print(f"{'ok' if ok else 'FAIL'}: {what}: {n} nodes, largest difference {worst:.2e} of the largest displacement")
    return ok


def load_lines(work, base):
    out = {}
    for step in ("PUSH", "TWIST"):
        with open(os.path.join(work, f"{base}_{step}.load")) as fh:
            out[step] = ["A." + ln.strip() for ln in fh if ln.strip() and not ln.startswith("**")]
    return out


def read_abaqus(path):
    k = {}
    with open(path) as fh:
        for ln in fh:
            if ln.startswith("**"):
                continue
            a, b, c, d, v = [s.strip() for s in ln.split(",")]
            k[((int(a), int(b)), (int(c), int(d)))] = float(v)
    return k


def read_dmig(path):
    """A small DMIG reader: large-field (DMIG*) entries, 16-column fields."""
    mats = {}
    cur = None
    col = None
    with open(path) as fh:
        for ln in fh:
            ln = ln.rstrip("\n")
            if ln.startswith("$") or not ln.strip():
                continue
            f = [ln[8 + 16 * i: 8 + 16 * (i + 1)].strip() for i in range(4)]
            if ln.startswith("DMIG*"):
                name = f[0]
                if f[1] == "0":          # header: NAME, 0, IFO, TIN
                    mats[name] = {"ifo": int(f[2]), "tin": int(f[3]), "terms": {}}
                    cur, col = name, None
                else:
                    cur, col = name, (int(f[1]), int(f[2]))
            elif ln.startswith("*"):
                if col is None:
                    continue             # header continuation: TOUT, POLAR, NCOL
                mats[cur]["terms"][((int(f[0]), int(f[1])), col)] = float(f[2].replace("D", "E"))
    return mats


def dmig_load_lines(work):
    """The *CLOAD lines of A from the P2G matrix of the DMIG file (column k: step k)."""
    pm = read_dmig(os.path.join(work, "pd.dmig"))["PA"]["terms"]
    return {step: [f"A.{nd}, {dof}, {v!r}" for ((nd, dof), (col, _)), v in sorted(pm.items()) if col == s]
            for s, step in enumerate(("PUSH", "TWIST"), start=1)}


def mm_load_lines(work):
    """The *CLOAD lines of A from the Matrix Market load array and its DOF map."""
    with open(os.path.join(work, "pm_dofs.csv")) as fh:
        dofs = [(int(r["node"]), int(r["dof"])) for r in csv.DictReader(fh)]
    with open(os.path.join(work, "pm_loads.mtx")) as fh:
        lines = [ln for ln in fh if not ln.startswith("%")]
    n, ncol = map(int, lines[0].split())
    vals = [float(v) for v in lines[1:]]
    return {step: [f"A.{nd}, {dof}, {vals[s * n + i]!r}" for i, (nd, dof) in enumerate(dofs) if vals[s * n + i] != 0.0]
            for s, step in enumerate(("PUSH", "TWIST")[:ncol])}


def nastran8(v):
    """v in one 8-column small field (Nastran's exponent without its letter)."""
    if v == 0.0:
        return "0."
    for dec in (3, 2, 1, 0):
        m, e = f"{v:.{dec}e}".split("e")
        t = f"{m}{int(e):+d}"
        if len(t) <= 8:
            return t
    raise ValueError(v)


def nastran_float(t):
    """The value of a Nastran real field (the exponent letter may be left out)."""
    t = t.strip().upper().replace("D", "E")
    if "E" not in t:
        k = max(t.rfind("+"), t.rfind("-"))
        if k > 0:
            t = t[:k] + "E" + t[k:]
    return float(t)


def write_dmig_forms(work):
    """From A's K (pa.mtx, 17 digits): pf.dmig in free field, square (IFO=1:
    both triangles) with every digit, next to a load matrix and a second square
    matrix (NAME= chooses); ps.dmig in small field (IFO=6, '+' continuations)
    with 8-column values, and ps.mtx: the same rounded values for FORMAT=ABAQUS."""
    k = read_abaqus(os.path.join(work, "pa.mtx"))
    cols = {}
    for (r, c), v in k.items():
        cols.setdefault(c, []).append((r, v))
    with open(os.path.join(work, "pf.dmig"), "w") as fh:
        fh.write("$ free field, written by tests/travel/round_trip.py\nBEGIN BULK\n")
        fh.write("DMIG,KOTHER,0,1,2,0\nDMIG,KOTHER,1,1,,1,1,1.0\n")
        fh.write("DMIG,KAAX,0,1,2,0\n")
        full = {}
        for (r, c), v in k.items():
            full[(r, c)] = v
            full[(c, r)] = v
        byc = {}
        for (r, c), v in full.items():
            byc.setdefault(c, []).append((r, v))
        for c in sorted(byc):
            terms = sorted(byc[c])
            fh.write(f"DMIG,KAAX,{c[0]},{c[1]},,{terms[0][0][0]},{terms[0][0][1]},{terms[0][1]!r}\n")
            for (g, comp), v in terms[1:]:
                fh.write(f",{g},{comp},{v!r}\n")
        fh.write("DMIG,PAAX,0,9,2,0,,,1\nDMIG,PAAX,1,0,,1,3,-5.0\nENDDATA\n")
    rounded = {}
    with open(os.path.join(work, "ps.dmig"), "w") as fh:
        fh.write("DMIG    KAAX           0       6       2\n")
        for c in sorted(cols):
            terms = sorted(cols[c])
            fields = []
            for (g, comp), v in terms:
                t = nastran8(v)
                rounded[((g, comp), c)] = nastran_float(t)
                fields.append((str(g), str(comp), t))
            line = f"{'DMIG':<8}{'KAAX':>8}{c[0]:>8}{c[1]:>8}{'':8}" + "".join(f"{x:>8}" for x in fields[0])
            fh.write(line + "\n")
            rest = fields[1:]
            for i in range(0, len(rest), 2):
                pair = rest[i:i + 2]
                ln = f"{'+':<8}" + "".join(f"{x:>8}" for x in pair[0])
                if len(pair) > 1:
                    ln += f"{'':8}" + "".join(f"{x:>8}" for x in pair[1])
                fh.write(ln + "\n")
    with open(os.path.join(work, "ps.mtx"), "w") as fh:
        for ((g, comp), (h, d)), v in rounded.items():
            fh.write(f"{g}, {comp}, {h}, {d}, {v!r}\n")


def check_dmig(work):
    k = read_abaqus(os.path.join(work, "pa.mtx"))
    mats = read_dmig(os.path.join(work, "pd.dmig"))
    km, pm = mats.get("KA"), mats.get("PA")
    ok = km is not None and pm is not None and km["ifo"] == 6 and km["tin"] == 2 and pm["ifo"] == 9
    worst = 0.0
    scale = max(abs(v) for v in k.values())
    if ok:
        ok = set(km["terms"]) == set(k)
        for key, v in k.items():
            worst = max(worst, abs(km["terms"].get(key, 0.0) - v) / scale)
        loads = load_lines(work, "pa")
        for s, step in enumerate(("PUSH", "TWIST"), start=1):
            for ln in loads[step]:
                nd, dof, v = [x.strip() for x in ln[2:].split(",")]
                got = pm["terms"].get(((int(nd), int(dof)), (s, 0)), 0.0)
                if abs(got - float(v)) > 1e-9 * max(1.0, abs(float(v))):
                    ok = False
    ok = ok and worst <= 1e-9
    print(f"{'ok' if ok else 'FAIL'}: DMIG read back: K {len(k)} entries, largest difference {worst:.2e}; P2G columns")
    return ok


def check_mm(work):
    k = read_abaqus(os.path.join(work, "pa.mtx"))
    with open(os.path.join(work, "pm_dofs.csv")) as fh:
        dofs = {int(r["index"]): (int(r["node"]), int(r["dof"])) for r in csv.DictReader(fh)}
    with open(os.path.join(work, "pm.mtx")) as fh:
        lines = [ln for ln in fh if not ln.startswith("%")]
    n, _, nnz = map(int, lines[0].split())
    got = {}
    for ln in lines[1:]:
        i, j, v = ln.split()
        got[(dofs[int(i)], dofs[int(j)])] = float(v)
    ok = n == len(dofs) and nnz == len(got) == len(k) and all(got[key] == v for key, v in k.items())
    print(f"{'ok' if ok else 'FAIL'}: Matrix Market with its DOF map equals the ABAQUS export ({n} DOFs)")
    return ok


def main():
    binary, work = sys.argv[1], os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    ref = displacements(run(binary, work, "explicit", deck(), ["--condense", "no"]))
    exported = displacements(run(binary, work, "export", deck(export=True)))
    results = [compare(ref, exported, "the exporting run (A condensed) against the monolithic one"),
               check_dmig(work), check_mm(work)]
    loads = {"pa": load_lines(work, "pa"), "pd": dmig_load_lines(work), "pm": mm_load_lines(work)}
    for fmt, base, split in (("ABAQUS", "pa", False), ("CALCULIX", "pc", False), ("ABAQUS", "pa", True),
                             ("DMIG", "pd", False), ("DMIG", "pd", True),
                             ("MATRIX MARKET", "pm", False), ("MATRIX MARKET", "pm", True)):
        ext = ".dmig" if fmt == "DMIG" else ".mtx"
        got = displacements(run(binary, work, "import_" + fmt.lower().replace(" ", "_") + ("_split" if split else ""),
                                deck(matrix=(base + ext, fmt), loads_a=loads.get(base, loads["pa"]), split=split)))
        how = "its own part's matrix turned by its instance" if split else "A's condensation turned"
        results.append(compare(ref, got, f"import of the {fmt} export, B: {how}", DIGITS_TOL.get(fmt, RTOL)))
    write_dmig_forms(work)
    for split in (False, True):
        tag = "_split" if split else ""
        got = displacements(run(binary, work, "import_dmig_free" + tag,
                                deck(matrix=("pf.dmig, NAME=kaax", "DMIG"), loads_a=loads["pa"], split=split)))
        results.append(compare(ref, got, "import of a free-field square DMIG with every digit" + tag))
        small = displacements(run(binary, work, "import_dmig_small" + tag,
                                  deck(matrix=("ps.dmig", "DMIG"), loads_a=loads["pa"], split=split)))
        same = displacements(run(binary, work, "import_rounded_abaqus" + tag,
                                 deck(matrix=("ps.mtx", "ABAQUS"), loads_a=loads["pa"], split=split)))
        results.append(compare(same, small, "small-field DMIG (8-column values) = the same values as ABAQUS" + tag,
                               1e-13))
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
