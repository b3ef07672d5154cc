#!/usr/bin/env python3
"""Second-order thick shells: S8R (eight-node) and, with --element S6, the
six-node triangle S6 (assumed transverse shear). Square plates at a/t = 5, 10,
20, 100 against the Reissner-Mindlin series (simply supported) with the
observed convergence order, distorted meshes, clamped plates, the thin limit
against the Kirchhoff series, and the MacNeal-Harder shells (Scordelis-Lo roof
under its self weight, pinched hemisphere, twisted beam). Prints markdown tables.

usage: verify_s8r.py SUPERJOIN WORKDIR [--element S8R|S6] [--full] [--markdown FILE]
Exit status 1 if any check fails; --full adds the finer meshes of doc/verification.md.

Meshes: "n x n" is the node grid: S8R (shellgen.grid8) n/2 x n/2 elements,
each on a 2 x 2 block of the grid, the same nodes as an n x n grid of S4R
less the block centres; S6 (shellgen.grid6) each such block split along a
diagonal (alternating by quadrant) into two triangles, the block centre the
diagonal's mid-side node. Loads are consistent (pressure *DLOAD P, self
weight *DLOAD GRAV).
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shellgen as g  # noqa: E402
import verify_shells as vs  # noqa: E402
import verify_thick as vt  # noqa: E402

THIN = 1000          # a/t of the thin limit
THIN_TOL = 0.01      # the thin limit against Kirchhoff (the 1 %)

# Per element: the finest SS plate's error and the least order; the distorted
# plates' (a/t, error, order: None where the sequence is not monotone); the
# MacNeal-Harder tolerances (twisted beam 24 x 4, Scordelis-Lo from 16, the
# hemisphere from 32). S6 measured 2026-12-03: distorted a/t = 100 +8.7e-2,
# -1.6e-3, +3.3e-3, +2.4e-3 and a/t = 1000 +8.1e-2, -2.0e-2, -1.0e-1, -5.9e-3;
# the hemisphere 0.911 at 32 (membrane locking of the curved triangle).
TOLERANCES = {
    "S8R": dict(plate=(1e-4, 3.0), distorted=((10, 2e-3, 2.5), (100, 2e-3, 2.5), (1000, 2e-2, 2.5)),
                twisted=0.01, twisted_coarse=0.02, scordelis=0.02, hemisphere=0.02),
    "S6": dict(plate=(5e-3, 1.5), distorted=((10, 1e-2, 1.5), (100, 1e-2, None), (1000, 1e-2, None)),
               twisted=0.01, twisted_coarse=None, scordelis=0.02, hemisphere=0.1),
}


def thin_limit(exe, work, meshes, etype):
    """The element at a/t = 1000 against the Kirchhoff series (SS: Navier;
    clamped: Timoshenko sec. 44): within THIN_TOL on the finest mesh."""
    vs.say(f"\n### Thin limit, a/t = {THIN}: {etype} against Kirchhoff (w D / q a^4)\n")
    vs.say("| mesh (nodes) | elements | SS | SS / Kirchhoff | clamped | clamped / Kirchhoff |")
    vs.say("|---|---|---|---|---|---|")
    kirch = {"SS": g.navier_ss_uniform(), "CL": g.CLAMPED_UNIFORM}
    last = {}
    for n in meshes:
        row = []
        for sup in ("SS", "CL"):
            case = vt.thick_plate(n, etype, sup, THIN)
            disp, _ = vs.solve(exe, work, case)
            if disp is None:
                return
            w = -vs.value(disp, case)
            row += [w, w / kirch[sup]]
            last[sup] = w / kirch[sup]
        nel = (n // 2) ** 2 * (2 if etype == "S6" else 1)
        vs.say(f"| {n}x{n} | {nel} | {row[0]:.6e} | {row[1]:.5f} | {row[2]:.6e} | {row[3]:.5f} |")
    for sup, r in last.items():
        vs.check(abs(r - 1.0) < THIN_TOL, f"{etype} thin limit {sup}: ratio {r:.5f} outside 1 +- {THIN_TOL}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--element", choices=sorted(TOLERANCES), default="S8R")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    exe, et, tol = a.exe, a.element, TOLERANCES[a.element]

    meshes = [4, 8, 16, 32] + ([64] if a.full else [])
    vs.say(f"\n## {et}: thick square plates, simply supported (hard), uniform pressure, centre deflection")
    vs.say("\n(mesh: the node grid; n x n nodes = n/2 x n/2 elements" + (" pairs)" if et == "S6" else ")"))
    for r in (5, 10, 20, 100):
        vs.convergence(exe, a.work, f"{et} a/t = {r}",
                       lambda n, r=r: vt.thick_plate(n, et, "SS", r), meshes, *tol["plate"], True)
    vs.say(f"\n## {et}: simply supported, distorted mesh (x = s + d, y = t + d, "
           f"d = {vt.DISTORTION} sin 2 pi s sin 2 pi t)")
    for r, err, order in tol["distorted"]:
        vs.convergence(exe, a.work, f"{et} a/t = {r}, distorted",
                       lambda n, r=r: vt.thick_plate(n, et, "SS", r, "distorted"), meshes, err, order, True)
    vs.say(f"\n## {et}: clamped, uniform pressure")
    vt.clamped_table(exe, a.work, et, (5, 10, 20, 100), meshes)
    thin_limit(exe, a.work, meshes, et)

    vs.say(f"\n## MacNeal-Harder shells with {et}\n")
    vs.say("(Scordelis-Lo under *DLOAD GRAV, density 360 x t 0.25 = 90 per unit area: consistent loads)")
    cases = [
        (g.twisted_beam(12, 2, et, "IN"), tol["twisted_coarse"]),
        (g.twisted_beam(12, 2, et, "OUT"), tol["twisted_coarse"]),
        (g.twisted_beam(24, 4, et, "IN"), tol["twisted"]),
        (g.twisted_beam(24, 4, et, "OUT"), tol["twisted"]),
    ]
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.scordelis_lo(n, et, gravity=True), tol["scordelis"] if n >= 16 else None))
    for n in (8, 16, 32) + ((64,) if a.full else ()):
        cases.append((g.pinched_hemisphere(n, et), tol["hemisphere"] if n >= 32 else None))
    vs.single(exe, a.work, cases, None)

    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(vs.lines) + "\n")
    print(f"\n{len(vs.failures)} failures")
    return 1 if vs.failures else 0


if __name__ == "__main__":
    sys.exit(main())
