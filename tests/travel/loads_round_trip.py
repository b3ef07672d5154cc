#!/usr/bin/env python3
"""Condensed loads that travel (issue 26): *MATRIX LOAD reads the loads of an
exported part back, in every format, onto a plain and a turned instance.

The model is the one of round_trip.py (a plate part placed twice, A as
defined and B turned by 90 degrees about X, joined to a clamped frame BASE).
Both plates carry interior loads in two steps: A the loads L of the step, B
the same loads turned with it and scaled (R L times 2.5 in PUSH, times -1.5 in
TWIST), so that B's condensed loads are R̂ f*(A) times the scale.

1. explicit: solved monolithically; export: A condensed and exported in every
   format (K*, f* of both steps).
2. import: the plates replaced by A's exported matrix (*MATRIX INPUT), their
   interior loads by `*MATRIX LOAD` lines naming the exported loads (A, name,
   1.0 and B, name, 2.5 or -1.5): ABAQUS and CALCULIX (the .load files, by
   step name), DMIG (the P2G matrix, `PA(k)` and `k`), MATRIX MARKET (column
   k of _loads.mtx); B the instance of A's part, and again of a second part
   with the same matrix. BASE and the corners of A and B must agree with the
   explicit run to 1e-10 of the largest displacement; the DMIG export holds
   10 significant digits (large field): 1e-8 there (measured about 5e-9).
3. DMIG written by another program: free field with every digit (K and a
   two-column P2G matrix: 1e-10), and small field (8-column values) against
   the same rounded values given in the ABAQUS layout (1e-13).

usage: loads_round_trip.py SUPERJOIN WORKDIR
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import round_trip as rt  # noqa: E402

STEPS = ("PUSH", "TWIST")
SCALE_B = {"PUSH": 2.5, "TWIST": -1.5}
INTERIOR = {"PUSH": [(rt.CENTRE, 3, -1000.0), (rt.OFF, 1, 300.0), (rt.OFF, 6, 25.0)],
            "TWIST": [(rt.OFF, 5, 40.0), (rt.CENTRE, 2, -250.0), (rt.CENTRE, 4, 15.0)]}
OTHER = {"PUSH": [f"B.{rt.CORNERS[3]}, 2, 500.0", "BASE.4, 3, -200.0"],
         "TWIST": [f"B.{rt.CORNERS[1]}, 4, 30.0", "BASE.8, 1, 100.0"]}
# B's placement: 90 degrees about X (part y -> global z), as round_trip.py's *INSTANCE
R = [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]]
DMIG_TOL = 1e-8


def turned(loads, scale):
    """The loads (node, DOF, value) turned by R (translations and rotations) and scaled."""
    out = []
    for nd, dof, v in loads:
        blk, c = (dof - 1) // 3, (dof - 1) % 3
        for i in range(3):
            if R[i][c] != 0.0:
                out.append((nd, 3 * blk + i + 1, scale * R[i][c] * v))
    return out


def deck(matrix=None, names=None, export=False, split=False, history=False):
    """names: {step: (load name for A, load name for B)} of *MATRIX LOAD lines
    (with matrix); else the interior loads as *CLOAD lines."""
    d = rt.model_lines(matrix, export, split, "plate part with condensed loads")
    d += history_steps(names) if history else plain_steps(names)
    return "\n".join(d) + "\n"


def interior(step, inst, scale):
    """*CLOAD lines of the interior loads of a plate (B's turned with it)."""
    loads = INTERIOR[step] if inst == "A" else turned(INTERIOR[step], 1.0)
    return [f"{inst}.{nd}, {dof}, {scale * v!r}" for nd, dof, v in loads]


def plain_steps(names):
    """Two steps without a procedure card: each a load case of its own."""
    d = []
    for step in STEPS:
        d += [f"*STEP, NAME={step}", "*CLOAD"] + OTHER[step]
        if names is None:
            d += interior(step, "A", 1.0) + interior(step, "B", SCALE_B[step])
        else:
            d += ["*MATRIX LOAD", f"A, {names[step][0]}, 1.0", f"B, {names[step][1]}, {SCALE_B[step]!r}"]
        d.append("*END STEP")
    return d


def history_steps(names):
    """*STATIC steps, whose loads continue: PUSH; TWIST (PUSH kept, TWIST
    added); NEW (OP=NEW: only TWIST's other loads and A's TWIST load); MOD (A's
    TWIST load again, three times: it replaces the kept one)."""
    d = []
    for step in STEPS:
        d += [f"*STEP, NAME={step}", "*STATIC", "*CLOAD"] + OTHER[step]
        if names is None:
            d += interior(step, "A", 1.0) + interior(step, "B", SCALE_B[step])
        else:
            d += ["*MATRIX LOAD", f"A, {names[step][0]}, 1.0", f"B, {names[step][1]}, {SCALE_B[step]!r}"]
        d.append("*END STEP")
    d += ["*STEP, NAME=NEW", "*STATIC", "*CLOAD, OP=NEW"] + OTHER["TWIST"]
    if names is None:
        d += interior("TWIST", "A", 1.0)
    else:
        d += ["*MATRIX LOAD, OP=NEW", f"A, {names['TWIST'][0]}, 1.0"]
    d += ["*END STEP", "*STEP, NAME=MOD", "*STATIC"]
    if names is None:
        d += ["*CLOAD"] + interior("TWIST", "A", 3.0)
    else:
        d += ["*MATRIX LOAD", f"A, {names['TWIST'][0]}, 3.0"]
    d.append("*END STEP")
    return d


def write_other_dmig(work):
    """pq.dmig: free field, K (IFO=6) and the two-column P2G matrix PQ with
    every digit of pa's K and loads; pr.dmig: small field with 8-column values
    (K as round_trip.py's ps.dmig, P rounded likewise) and pr.mtx, pr_PUSH.load,
    pr_TWIST.load: the same rounded values in the ABAQUS layout."""
    k = rt.read_abaqus(os.path.join(work, "pa.mtx"))
    loads = {}
    for step in STEPS:
        with open(os.path.join(work, f"pa_{step}.load")) as fh:
            loads[step] = [(int(a), int(b), float(c)) for a, b, c in
                           (ln.split(",") for ln in fh if ln.strip() and not ln.startswith("**"))]
    byc = {}
    for (r, c), v in k.items():
        byc.setdefault(c, []).append((r, v))
    with open(os.path.join(work, "pq.dmig"), "w") as fh:
        fh.write("$ free field, written by tests/travel/loads_round_trip.py\nBEGIN BULK\n")
        fh.write("DMIG,KQ,0,6,2,0\n")
        for c in sorted(byc):
            terms = sorted(byc[c])
            fh.write(f"DMIG,KQ,{c[0]},{c[1]},,{terms[0][0][0]},{terms[0][0][1]},{terms[0][1]!r}\n")
            for (g, comp), v in terms[1:]:
                fh.write(f",{g},{comp},{v!r}\n")
        fh.write("DMIG,PQ,0,9,2,0,,,2\n")
        for s, step in enumerate(STEPS, start=1):
            terms = [t for t in loads[step] if t[2] != 0.0]
            fh.write(f"DMIG,PQ,{s},,,{terms[0][0]},{terms[0][1]},{terms[0][2]!r}\n")
            for nd, dof, v in terms[1:]:
                fh.write(f"+,{nd},{dof},{v!r}\n")
        fh.write("ENDDATA\n")
    rounded_k = {}
    with open(os.path.join(work, "pr.dmig"), "w") as fh:
        fh.write("$ small field, written by tests/travel/loads_round_trip.py\n")
        fh.write("DMIG    KR             0       6       2\n")
        for c in sorted(byc):
            fields = []
            for (g, comp), v in sorted(byc[c]):
                t = rt.nastran8(v)
                rounded_k[((g, comp), c)] = rt.nastran_float(t)
                fields.append((str(g), str(comp), t))
            fh.write(small_column("KR", f"{c[0]:>8}{c[1]:>8}", fields))
        fh.write(f"{'DMIG':<8}{'PR':>8}{'0':>8}{'9':>8}{'2':>8}{'0':>8}{'':8}{'':8}{'2':>8}\n")
        for s, step in enumerate(STEPS, start=1):
            fields = [(str(nd), str(dof), rt.nastran8(v)) for nd, dof, v in loads[step] if v != 0.0]
            fh.write(small_column("PR", f"{s:>8}{'':8}", fields))
            with open(os.path.join(work, f"pr_{step}.load"), "w") as lf:
                for nd, dof, t in fields:
                    lf.write(f"{nd}, {dof}, {rt.nastran_float(t)!r}\n")
    with open(os.path.join(work, "pr.mtx"), "w") as fh:
        for ((g, comp), (h, dd)), v in rounded_k.items():
            fh.write(f"{g}, {comp}, {h}, {dd}, {v!r}\n")


def small_column(name, column, fields):
    """One small-field DMIG column entry: two G, C, A groups a line ('+' continuations)."""
    out = f"{'DMIG':<8}{name:>8}{column}{'':8}" + "".join(f"{x:>8}" for x in fields[0]) + "\n"
    rest = fields[1:]
    for i in range(0, len(rest), 2):
        ln = f"{'+':<8}" + "".join(f"{x:>8}" for x in rest[i])
        if i + 1 < len(rest):
            ln += f"{'':8}" + "".join(f"{x:>8}" for x in rest[i + 1])
        out += ln + "\n"
    return out


def kept_lines(listing, fmt):
    """The listing says what each step keeps: TWIST keeps PUSH's two matrix
    loads (and its *CLOAD lines), MOD keeps no matrix load (the one it names
    again replaces the kept one; NEW dropped the others)."""
    with open(listing) as fh:
        kept = [line.strip() for line in fh if line.strip().startswith("kept from step")]
    twist = [k for k in kept if k.startswith("kept from step PUSH") and k.endswith(" 2 matrix load(s)")]
    mod = [k for k in kept if k.startswith("kept from step NEW") and "matrix load" in k]
    ok = len(twist) == 1 and not mod
    print(("ok" if ok else "FAIL") + f": the listing counts the kept matrix loads ({fmt}): {kept}")
    return ok


def main():
    binary, work = sys.argv[1], os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    ref = rt.displacements(rt.run(binary, work, "explicit", deck(), ["--condense", "no"]))
    exported = rt.displacements(rt.run(binary, work, "export", deck(export=True)))
    results = [rt.compare(ref, exported, "the exporting run (A condensed) against the monolithic one")]
    names = {"ABAQUS": {"PUSH": ("PUSH", "push"), "TWIST": ("TWIST", "TWIST")},
             "DMIG": {"PUSH": ("PA(1)", "1"), "TWIST": ("pa(2)", "2")},
             "MATRIX MARKET": {"PUSH": ("1", "1"), "TWIST": ("2", "2")}}
    for fmt, base in (("ABAQUS", "pa"), ("CALCULIX", "pc"), ("DMIG", "pd"), ("MATRIX MARKET", "pm")):
        ext = ".dmig" if fmt == "DMIG" else ".mtx"
        for split in (False, True):
            tag = fmt.lower().replace(" ", "_") + ("_split" if split else "")
            got = rt.displacements(rt.run(binary, work, "loads_" + tag,
                                          deck((base + ext, fmt), names.get(fmt, names["ABAQUS"]), split=split)))
            how = "its own part's matrix and loads turned by B" if split else "A's part turned by B"
            results.append(rt.compare(ref, got, f"*MATRIX LOAD from the {fmt} export, {how}",
                                      DMIG_TOL if fmt == "DMIG" else rt.RTOL))
    href = rt.displacements(rt.run(binary, work, "history_explicit", deck(history=True), ["--condense", "no"]))
    for fmt, base in (("ABAQUS", "pa"), ("DMIG", "pd")):
        ext = ".dmig" if fmt == "DMIG" else ".mtx"
        out = rt.run(binary, work, "history_" + fmt.lower(),
                     deck((base + ext, fmt), names[fmt], split=True, history=True))
        got = rt.displacements(out)
        results.append(rt.compare(href, got, f"*STATIC steps, OP=MOD kept, OP=NEW dropped, a load named again "
                                  f"replaced ({fmt})", DMIG_TOL if fmt == "DMIG" else rt.RTOL))
        results.append(kept_lines(out + ".lst", fmt))
    write_other_dmig(work)
    for split in (False, True):
        tag = "_split" if split else ""
        got = rt.displacements(rt.run(binary, work, "loads_dmig_free" + tag, deck(
            ("pq.dmig, NAME=KQ", "DMIG"), {"PUSH": ("PQ(1)", "PQ(1)"), "TWIST": ("PQ(2)", "2")}, split=split)))
        results.append(rt.compare(ref, got, "free-field DMIG with a two-column P2G matrix, every digit" + tag))
        small = rt.displacements(rt.run(binary, work, "loads_dmig_small" + tag, deck(
            ("pr.dmig", "DMIG"), {"PUSH": ("PR(1)", "1"), "TWIST": ("PR(2)", "2")}, split=split)))
        same = rt.displacements(rt.run(binary, work, "loads_rounded_abaqus" + tag, deck(
            ("pr.mtx", "ABAQUS"), {"PUSH": ("PUSH", "PUSH"), "TWIST": ("TWIST", "TWIST")}, split=split)))
        results.append(rt.compare(same, small, "small-field DMIG loads (8-column values) = the same values as "
                                  "ABAQUS .load files" + tag, 1e-13))
    failed = results.count(False)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
