#!/usr/bin/env python3
"""S8R (eight-node thick shell) verification: square plates at a/t = 5, 10, 20,
100 against the Reissner-Mindlin series (simply supported) with the observed
convergence order, distorted meshes, clamped plates, the thin limit against
the Kirchhoff series, and the MacNeal-Harder shells (Scordelis-Lo roof under
its self weight, pinched hemisphere, twisted beam). Prints markdown tables.

usage: verify_s8r.py SUPERJOIN WORKDIR [--full] [--markdown FILE]
Exit status 1 if any check fails; --full adds the finer meshes of doc/verification.md.

Meshes: "n x n" is the node grid (shellgen.grid8): n/2 x n/2 elements, each on a
2 x 2 block of the grid, the same nodes as an n x n grid of S4R less the block
centres; loads are consistent (pressure *DLOAD P, self weight *DLOAD GRAV).
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


def thin_limit(exe, work, meshes):
    """S8R at a/t = 1000 against the Kirchhoff series (SS: Navier; clamped:
    Timoshenko sec. 44): within THIN_TOL on the finest mesh."""
    vs.say(f"\n### Thin limit, a/t = {THIN}: S8R against Kirchhoff (w D / q a^4)\n")
    vs.say("| mesh (nodes) | elements | SS | SS / Kirchhoff | clamped | clamped / Kirchhoff |")
    vs.say("|---|---|---|---|---|---|")
    kirch = {"SS": g.navier_ss_uniform(), "CL": g.CLAMPED_UNIFORM}
    last = {}
    for n in meshes:
        row = []
        for sup in ("SS", "CL"):
            case = vt.thick_plate(n, "S8R", sup, THIN)
            disp, _ = vs.solve(exe, work, case)
            if disp is None:
                return
            w = -vs.value(disp, case)
            row += [w, w / kirch[sup]]
            last[sup] = w / kirch[sup]
        vs.say(f"| {n}x{n} | {n // 2}x{n // 2} | {row[0]:.6e} | {row[1]:.5f} | {row[2]:.6e} | {row[3]:.5f} |")
    for sup, r in last.items():
        vs.check(abs(r - 1.0) < THIN_TOL, f"S8R thin limit {sup}: ratio {r:.5f} outside 1 +- {THIN_TOL}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    exe = a.exe

    meshes = [4, 8, 16, 32] + ([64] if a.full else [])
    vs.say("\n## S8R: thick square plates, simply supported (hard), uniform pressure, centre deflection")
    vs.say("\n(mesh: the node grid; n x n nodes = n/2 x n/2 elements)")
    for r in (5, 10, 20, 100):
        vs.convergence(exe, a.work, f"S8R a/t = {r}",
                       lambda n, r=r: vt.thick_plate(n, "S8R", "SS", r), meshes, 1e-4, 3.0, True)
    vs.say("\n## S8R: simply supported, distorted mesh (x = s + d, y = t + d, "
           f"d = {vt.DISTORTION} sin 2 pi s sin 2 pi t)")
    for r, tol, order in ((10, 2e-3, 2.5), (100, 2e-3, 2.5), (1000, 2e-2, 2.5)):
        vs.convergence(exe, a.work, f"S8R a/t = {r}, distorted",
                       lambda n, r=r: vt.thick_plate(n, "S8R", "SS", r, "distorted"), meshes, tol, order, True)
    vs.say("\n## S8R: clamped, uniform pressure")
    vt.clamped_table(exe, a.work, "S8R", (5, 10, 20, 100), meshes)
    thin_limit(exe, a.work, meshes)

    vs.say("\n## MacNeal-Harder shells with S8R\n")
    vs.say("(Scordelis-Lo under *DLOAD GRAV, density 360 x t 0.25 = 90 per unit area: consistent loads)")
    cases = [
        (g.twisted_beam(12, 2, "S8R", "IN"), 0.02),
        (g.twisted_beam(12, 2, "S8R", "OUT"), 0.02),
        (g.twisted_beam(24, 4, "S8R", "IN"), 0.01),
        (g.twisted_beam(24, 4, "S8R", "OUT"), 0.01),
    ]
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.scordelis_lo(n, "S8R", gravity=True), 0.02 if n >= 16 else None))
    for n in (8, 16, 32) + ((64,) if a.full else ()):
        cases.append((g.pinched_hemisphere(n, "S8R"), 0.02 if n >= 32 else None))
    vs.single(exe, a.work, cases, None)

    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(vs.lines) + "\n")
    print(f"\n{len(vs.failures)} failures")
    return 1 if vs.failures else 0


if __name__ == "__main__":
    sys.exit(main())
