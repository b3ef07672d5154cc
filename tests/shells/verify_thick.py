#!/usr/bin/env python3
"""Thick-shell (S4R, S3R) verification: patch test through the whole program,
square plates at a/t = 5, 10, 20, 100 against the Reissner-Mindlin series,
the thin limit against S4/S3, and the MacNeal-Harder shells (Scordelis-Lo roof,
pinched hemisphere, twisted beam). Prints markdown tables.

usage: verify_thick.py SUPERJOIN WORKDIR [--full] [--markdown FILE]
Exit status 1 if any check fails; --full adds the finer meshes of doc/verification.md.

Reissner-Mindlin plate, simply supported (hard support: w = 0 and the rotation
about the edge normal fixed), uniform load q, square of side a, D = E t^3 /
(12 (1 - nu^2)), shear stiffness k G t with k = 5/6. For a polygonal plate with
these supports the Mindlin deflection is the Kirchhoff one plus the Marcus
moment over the shear stiffness, w = w_K + M_K / (k G t), M = -D lap w
(Wang, Reddy & Lee, Shear Deformable Beams and Plates, Elsevier 2000, ch. 7;
Reddy, Theory and Analysis of Elastic Plates and Shells, 2nd ed. 2007, sec. 10.2,
Navier solution of the first-order shear deformation theory). In Navier form,
with alpha = (m^2 + n^2) pi^2 / a^2 and q_mn = 16 q / (pi^2 m n), m, n odd:
    w(a/2, a/2) = sum q_mn (1/(D alpha^2) + 1/(k G t alpha)) sin(m pi/2) sin(n pi/2).
"""
import argparse
import functools
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shellgen as g  # noqa: E402
import verify_shells as vs  # noqa: E402

KAPPA = 5.0 / 6.0
NU = 0.3


@functools.lru_cache(maxsize=None)
def mindlin_ss_uniform(a_over_t, nu=NU, nterms=801):
    """Centre deflection w D / (q a^4) of the hard simply supported square
    Mindlin plate under uniform load (series above; the tail of the shear part,
    which decays like 1/(m n (m^2 + n^2)), is below 1e-7 relative at 801 terms)."""
    t = 1.0 / a_over_t
    # a = 1, D = 1: k G t / D = k * 6 (1 - nu) / t^2
    kgt = KAPPA * 6.0 * (1.0 - nu) / t ** 2
    s = 0.0
    for m in range(1, nterms + 1, 2):
        for n in range(1, nterms + 1, 2):
            sign = (-1) ** ((m - 1) // 2 + (n - 1) // 2)
            alpha = (m * m + n * n) * math.pi ** 2
            s += sign * 16.0 / (math.pi ** 2 * m * n) * (1.0 / alpha ** 2 + 1.0 / (kgt * alpha))
    return s


def distorted(s, u):
    """A smooth map of the unit square onto itself (edges kept, centre kept):
    interior elements become general quadrilaterals, angles down to about 60 degrees."""
    d = DISTORTION * math.sin(2 * math.pi * s) * math.sin(2 * math.pi * u)
    return (s + d, u + d, 0.0)


DISTORTION = 0.06
ZIGZAG = 0.25


def zigzag(s, u, n):
    """Interior nodes moved by +-ZIGZAG h along x and y in a checkerboard
    pattern: every element stays a general (non-parallelogram) quadrilateral
    on every mesh, the distortion does not fade under refinement."""
    i, j = round(s * n), round(u * n)
    if 0 < i < n and 0 < j < n:
        d = ZIGZAG / n * (1 if (i + j) % 2 == 0 else -1)
        return (s + d, u + d, 0.0)
    return (s, u, 0.0)


def thick_plate(n, etype, support, a_over_t, mesh="regular"):
    """Square plate a = 1, D = 1, uniform pressure 1, n x n mesh of S4R/S3R (or S4/S3),
    regular or distorted (see distorted()).
    SS: w and the rotation about the edge normal fixed (hard support); CL: all."""
    t = 1.0 / a_over_t
    e = 12.0 * (1.0 - NU ** 2) / t ** 3
    p = g.Part("PLATE")
    if mesh == "regular":
        mapping = lambda s, u: (s, u, 0.0)  # noqa: E731
    elif mesh == "distorted":
        mapping = distorted
    else:
        mapping = lambda s, u: zigzag(s, u, n)  # noqa: E731
    nid = g.grid(p, n, n, mapping, etype)
    p.nsets["X0"] = [nid(0, j) for j in range(n + 1)] + [nid(n, j) for j in range(n + 1)]
    p.nsets["Y0"] = [nid(i, 0) for i in range(n + 1)] + [nid(i, n) for i in range(n + 1)]
    p.nsets["ALLN"] = list(p.nodes)
    if support == "SS":
        # edges x = 0, 1: w, rotation about x; edges y = 0, 1: w, rotation about y
        bnd = [("PLATE.X0", 3, 4), ("PLATE.Y0", 3, 3), ("PLATE.Y0", 5, 5)]
    else:
        bnd = [("PLATE.X0", 3, 5), ("PLATE.Y0", 3, 5)]
    bnd += [("PLATE.ALLN", 1, 2), ("PLATE.ALLN", 6, 6)]   # the flat plate has no membrane load
    name = f"thick_{support}_{etype}_{a_over_t}_{n}" + ("" if mesh == "regular" else "_" + mesh)
    deck = g.deck_text(name, [p], e, NU, t, bnd, (), [("PLATE.ALL", "P", 1.0)])
    if support == "SS":
        ref, src = -mindlin_ss_uniform(a_over_t), "Reissner-Mindlin Navier series, k = 5/6"
    else:
        ref, src = -g.CLAMPED_UNIFORM, "Kirchhoff (Timoshenko sec. 44); no Mindlin series"
    return g.Case(name, deck, "PLATE", nid(n // 2, n // 2), 3, ref, src, g.count_dofs([p]))


def clamped_table(exe, work, etype, ratios, meshes):
    """Clamped plates: no series here, the values and their Richardson
    extrapolation (order 2) from the two finest meshes, relative to Kirchhoff."""
    vs.say(f"\n### {etype} clamped, uniform pressure: w D / (q a^4)\n")
    vs.say("| a/t | " + " | ".join(f"{n}x{n}" for n in meshes) + " | Richardson | / Kirchhoff 0.00126532 |")
    vs.say("|---|" + "---|" * (len(meshes) + 2))
    for r in ratios:
        vals = []
        for n in meshes:
            case = thick_plate(n, etype, "CL", r)
            disp, _ = vs.solve(exe, work, case)
            if disp is None:
                return
            vals.append(-vs.value(disp, case))
        rich = vals[-1] + (vals[-1] - vals[-2]) / 3.0
        vs.say(f"| {r} | " + " | ".join(f"{v:.6f}" for v in vals) + f" | {rich:.6f} | {rich / g.CLAMPED_UNIFORM:.4f} |")
        if r == 100:
            vs.check(abs(rich / g.CLAMPED_UNIFORM - 1.0) < 0.01,
                     f"{etype} clamped a/t = 100: {rich / g.CLAMPED_UNIFORM:.4f} of the Kirchhoff value")


def thin_limit(exe, work, n):
    """S4R against S4 and S3R against S3 on the same meshes at a/t = 1000."""
    vs.say(f"\n### Thin limit, a/t = 1000, {n}x{n} mesh: thick / thin element\n")
    vs.say("| support | S4R / S4 | S3R / S3 |")
    vs.say("|---|---|---|")
    for sup in ("SS", "CL"):
        ratios = []
        for thick, thin in (("S4R", "S4"), ("S3R", "S3")):
            a = thick_plate(n, thick, sup, 1000)
            b = thick_plate(n, thin, sup, 1000)
            da, _ = vs.solve(exe, work, a)
            db, _ = vs.solve(exe, work, b)
            if da is None or db is None:
                return
            ratios.append(vs.value(da, a) / vs.value(db, b))
        vs.say(f"| {sup} | {ratios[0]:.5f} | {ratios[1]:.5f} |")
        for et, r in zip(("S4R", "S3R"), ratios):
            vs.check(abs(r - 1.0) < 0.01, f"thin limit {et} {sup}: {r:.5f} of the thin element")


def goodman_face_s4r(exe, work):
    """decks/goodman_face.deck (a plate on a face *INTERFACE of normal stiffness
    KN per unit area, pressure p: uniform sinking p/KN) with S4R plates: its
    `** expect:` lines checked by tests/examples/check_example.py."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    text = open(os.path.join(root, "decks", "goodman_face.deck")).read()
    vs.check("TYPE=S4," in text, "goodman_face.deck has no S4 elements")
    deck = os.path.join(work, "goodman_face_s4r.deck")
    with open(deck, "w") as f:
        f.write(text.replace("TYPE=S4,", "TYPE=S4R,"))
    r = subprocess.run([sys.executable, os.path.join(root, "tests", "examples", "check_example.py"), exe, deck,
                        os.path.join(work, "goodman_face_s4r")], capture_output=True, text=True)
    vs.say("\n## Face *INTERFACE on S4R (decks/goodman_face.deck with S4R)\n")
    for line in r.stdout.strip().splitlines():
        vs.say("    " + line)
    vs.check(r.returncode == 0, f"goodman_face with S4R: check_example.py exit {r.returncode}: {r.stdout[-300:]}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    exe = a.exe

    vs.patch_tests(exe, a.work, ("S4R", "S3R"))
    goodman_face_s4r(exe, a.work)

    meshes = [4, 8, 16, 32] + ([64] if a.full else [])
    vs.say("\n## Thick square plates, simply supported (hard), uniform pressure, centre deflection")
    for et in ("S4R", "S3R"):
        for r in (5, 10, 20, 100):
            vs.convergence(exe, a.work, f"{et} a/t = {r}",
                           lambda n, et=et, r=r: thick_plate(n, et, "SS", r), meshes,
                           2e-3 if et == "S4R" else 5e-3, 1.7, True)
    vs.say("\n## Thick square plates, simply supported, distorted mesh (x = s + d, y = t + d, "
           f"d = {DISTORTION} sin 2 pi s sin 2 pi t)")
    for et in ("S4R", "S3R"):
        for r in (10, 100, 1000):
            vs.convergence(exe, a.work, f"{et} a/t = {r}, distorted",
                           lambda n, et=et, r=r: thick_plate(n, et, "SS", r, "distorted"), meshes,
                           5e-3, 1.5, True)
    # (triangles are affine images of each other whatever the distortion: S4R only)
    vs.say(f"\n## Thick square plates, simply supported, zigzag mesh (interior nodes +-{ZIGZAG} h)")
    for et in ("S4R",):
        for r in (10, 100, 1000):
            vs.convergence(exe, a.work, f"{et} a/t = {r}, zigzag",
                           lambda n, et=et, r=r: thick_plate(n, et, "SS", r, "zigzag"), meshes,
                           2e-2, 1.5, True)
    vs.say("\n## Thick square plates, clamped, uniform pressure")
    for et in ("S4R", "S3R"):
        clamped_table(exe, a.work, et, (5, 10, 20, 100), meshes)
    thin_limit(exe, a.work, 32)

    vs.say("\n## MacNeal-Harder shells with S4R, S3R\n")
    cases = [
        (g.twisted_beam(12, 2, "S4R", "IN"), 0.05),
        (g.twisted_beam(12, 2, "S4R", "OUT"), 0.05),
        (g.twisted_beam(24, 4, "S4R", "IN"), 0.02),
        (g.twisted_beam(24, 4, "S4R", "OUT"), 0.02),
    ]
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.scordelis_lo(n, "S4R"), 0.03 if n >= 16 else None))
        cases.append((g.scordelis_lo(n, "S3R"), 0.05 if n >= 16 else None))
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.pinched_hemisphere(n, "S4R"), 0.03 if n >= 16 else None))
        cases.append((g.pinched_hemisphere(n, "S3R"), 0.05 if n >= 16 else None))
    vs.single(exe, a.work, cases, None)

    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(vs.lines) + "\n")
    print(f"\n{len(vs.failures)} failures")
    return 1 if vs.failures else 0


if __name__ == "__main__":
    sys.exit(main())
