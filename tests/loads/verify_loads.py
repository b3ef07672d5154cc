#!/usr/bin/env python3
"""Convergence checks of the centrifugal and thermal loads against closed forms.

usage: verify_loads.py SUPERJOIN WORKDIR [--table]

1. Spinning annular disc (plane stress; Timoshenko & Goodier, Theory of
   Elasticity, sec. 32): inner radius a, outer b, density rho, angular velocity
   omega, *DLOAD CENTRIF about Z; a quarter of the disc with symmetry
   supports, polar meshes of CPS8 (mid-side nodes on the circles), CPS4 and
   S4 (its membrane). Closed form
     s_r = (3+nu)/8 rho w^2 (b^2 + a^2 - a^2 b^2/r^2 - r^2)
     s_t = (3+nu)/8 rho w^2 (b^2 + a^2 + a^2 b^2/r^2 - (1+3nu)/(3+nu) r^2)
     u   = r (s_t - nu s_r)/E
   compared at the inner and outer radius (radial displacement); the error must
   fall at the rate of the element on the last halving of the mesh (CPS8:
   >= 3 on its way to 4, the four-node quadrilaterals with their chordal
   boundary: >= 1.7 on their way to 2), the finest error below 1 %.
2. Bimetal strip (Timoshenko 1925): two layers of equal thickness h/2, moduli
   E1, E2, expansion alpha1, alpha2, heated by dT, free: curvature
     k = 6 (a2 - a1) dT (1+m)^2 / (h (3 (1+m)^2 + (1 + m n)(m^2 + 1/(m n))))
   with m = 1 (thickness ratio), n = E1/E2; a CPS8 strip of length 20 h,
   the curvature taken from the mid-line deflection between x = -L/4 and L/4
   (beam theory is the interior solution of the plane-stress strip: the
   finest mesh must agree to 1e-6).
3. CalculiX: thermal_cps8.inp (a CPS8 plate 2 x 1 clamped at x = 0, heated
   by 100) run unchanged; its displacements against thermal_cps8.dat.ref,
   written by ccx 2.20 on the same file. CalculiX expands the plane-stress
   CPS8 into a layer of C3D20 bricks, superjoin solves the 2D element: they
   agree to 2e-3 of the largest displacement, not to round-off.
With --table the tables of doc/verification.md are printed.
"""
import csv
import math
import os
import subprocess
import sys

E, NU, RHO, W2 = 2.0e11, 0.3, 7800.0, 1.0e4
A, B, T = 0.1, 0.5, 0.01


def disc_closed(r):
    c = (3 + NU) / 8 * RHO * W2
    sr = c * (B**2 + A**2 - A**2 * B**2 / r**2 - r**2)
    st = c * (B**2 + A**2 + A**2 * B**2 / r**2 - (1 + 3 * NU) / (3 + NU) * r**2)
    return r * (st - NU * sr) / E


def disc_deck(etype, nr, nt):
    """Quarter annulus: nodes on the polar grid (radial i, angular j)."""
    quad = etype == "CPS8"
    mr, mt = (2 * nr, 2 * nt) if quad else (nr, nt)
    ids = {}
    lines = ["*HEADING", f"spinning disc {etype} {nr}x{nt}", "*MATERIAL, NAME=STEEL", "*ELASTIC",
             f"{E}, {NU}", "*DENSITY", f"{RHO}", "*NODE"]
    for i in range(mr + 1):
        for j in range(mt + 1):
            if quad and i % 2 == 1 and j % 2 == 1:
                continue
            r = A + (B - A) * i / mr
            th = 0.5 * math.pi * j / mt
            ids[(i, j)] = len(ids) + 1
            z = ", 0.0" if etype == "S4" else ""
            lines.append(f"{ids[(i, j)]}, {r * math.cos(th)!r}, {r * math.sin(th)!r}{z}")
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=DISC")
    k = 0
    for i in range(nr):
        for j in range(nt):
            k += 1
            if quad:
                i0, j0 = 2 * i, 2 * j
                c = [ids[(i0, j0)], ids[(i0 + 2, j0)], ids[(i0 + 2, j0 + 2)], ids[(i0, j0 + 2)],
                     ids[(i0 + 1, j0)], ids[(i0 + 2, j0 + 1)], ids[(i0 + 1, j0 + 2)], ids[(i0, j0 + 1)]]
            else:
                c = [ids[(i, j)], ids[(i + 1, j)], ids[(i + 1, j + 1)], ids[(i, j + 1)]]
            lines.append(f"{k}, " + ", ".join(map(str, c)))
    sec = "*SHELL SECTION" if etype == "S4" else "*SOLID SECTION"
    lines += [f"{sec}, ELSET=DISC, MATERIAL=STEEL", f"{T}", "*BOUNDARY"]
    for (i, j), n in sorted(ids.items(), key=lambda kv: kv[1]):
        if j == 0:
            lines.append(f"{n}, 2, 2")
        if j == mt:
            lines.append(f"{n}, 1, 1")
        if etype == "S4":
            lines.append(f"{n}, 3, 5")
    lines += ["*STEP, NAME=SPIN", "*STATIC", "*DLOAD",
              f"DISC, CENTRIF, {W2}, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0", "*END STEP"]
    return "\n".join(lines) + "\n", ids[(0, 0)], ids[(mr, 0)]


def solve(exe, work, name, text):
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, name + ".deck")
    with open(deck, "w") as f:
        f.write(text)
    out = os.path.join(work, name + ".csv")
    r = subprocess.run([exe, "-q", deck, "-o", os.path.join(work, name + ".lst"), "--csv", out],
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise SystemExit(f"FAIL: {name}: exit {r.returncode}\n{r.stderr}")
    with open(os.path.join(out, "displacements.csv"), newline="") as f:
        return {int(row["node"]): row for row in csv.DictReader(f)}


def disc_study(exe, work, table):
    ok = True
    for etype, meshes, rate in [("CPS8", [(1, 2), (2, 4), (4, 8), (8, 16)], 3.0),
                                ("CPS4", [(2, 4), (4, 8), (8, 16), (16, 32)], 1.7),
                                ("S4", [(2, 4), (4, 8), (8, 16), (16, 32)], 1.7)]:
        errs = []
        if table:
            print(f"\n| {etype} mesh | u(a) | error | u(b) | error |\n|---|---|---|---|---|")
        for nr, nt in meshes:
            text, na, nb = disc_deck(etype, nr, nt)
            d = solve(exe, work, f"disc_{etype}_{nr}", text)
            ua, ub = float(d[na]["u1"]), float(d[nb]["u1"])
            ea = abs(ua / disc_closed(A) - 1)
            eb = abs(ub / disc_closed(B) - 1)
            errs.append(max(ea, eb))
            if table:
                print(f"| {nr} x {nt} | {ua:.6e} | {ea:.2e} | {ub:.6e} | {eb:.2e} |")
        rates = [math.log2(errs[k] / errs[k + 1]) for k in range(len(errs) - 1)]
        if table:
            print(f"closed form u(a) = {disc_closed(A):.6e}, u(b) = {disc_closed(B):.6e}; "
                  f"rates {', '.join(f'{x:.2f}' for x in rates)}")
        if rates[-1] < rate or errs[-1] > 1e-2:
            print(f"FAIL: spinning disc {etype}: errors {errs}, rates {rates} (want >= {rate})")
            ok = False
        else:
            print(f"ok: spinning disc {etype}: finest error {errs[-1]:.2e}, rates {', '.join(f'{x:.2f}' for x in rates)}")
    return ok


def bimetal_deck(nx, ny):
    h, L = 0.01, 0.2
    e1, e2, a1, a2, dt = 2.0e11, 7.0e10, 1.2e-5, 2.3e-5, 100.0
    ids = {}
    lines = ["*HEADING", "bimetal strip", "*MATERIAL, NAME=M1", "*ELASTIC", f"{e1}, 0.3", "*EXPANSION", f"{a1}",
             "*MATERIAL, NAME=M2", "*ELASTIC", f"{e2}, 0.3", "*EXPANSION", f"{a2}", "*NODE, NSET=ALL"]
    mx, my = 2 * nx, 4 * ny
    for i in range(mx + 1):
        for j in range(my + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            ids[(i, j)] = len(ids) + 1
            lines.append(f"{ids[(i, j)]}, {-L / 2 + L * i / mx!r}, {-h / 2 + h * j / my!r}")
    els = {1: [], 2: []}
    k = 0
    for i in range(nx):
        for j in range(2 * ny):
            k += 1
            i0, j0 = 2 * i, 2 * j
            c = [ids[(i0, j0)], ids[(i0 + 2, j0)], ids[(i0 + 2, j0 + 2)], ids[(i0, j0 + 2)],
                 ids[(i0 + 1, j0)], ids[(i0 + 2, j0 + 1)], ids[(i0 + 1, j0 + 2)], ids[(i0, j0 + 1)]]
            els[1 if j < ny else 2].append(f"{k}, " + ", ".join(map(str, c)))
    for m in (1, 2):
        lines.append(f"*ELEMENT, TYPE=CPS8, ELSET=L{m}")
        lines += els[m]
        lines += [f"*SOLID SECTION, ELSET=L{m}, MATERIAL=M{m}", "0.01"]
    mid = ids[(mx // 2, my // 2)]
    lines += ["*BOUNDARY", f"{mid}, 1, 2", f"{ids[(mx // 2, 0)]}, 1, 1", "*STEP, NAME=HEAT", "*STATIC",
              "*TEMPERATURE", f"ALL, {dt}", "*END STEP"]
    n = e1 / e2
    kappa = 6 * (a2 - a1) * dt * 4 / (h * (3 * 4 + (1 + n) * (1 + 1 / n)))
    return "\n".join(lines) + "\n", mid, ids[(mx // 4, my // 2)], ids[(3 * mx // 4, my // 2)], L / 4, kappa


def bimetal_study(exe, work, table):
    errs = []
    if table:
        print("\n| CPS8 mesh (length x thickness) | curvature | error |\n|---|---|---|")
    for nx, ny in [(8, 1), (16, 2), (32, 4)]:
        text, mid, left, right, xq, kappa = bimetal_deck(nx, ny)
        d = solve(exe, work, f"bimetal_{nx}", text)
        vm, vl, vr = (float(d[n]["u2"]) for n in (mid, left, right))
        # v = v0 - k x^2/2 (the layer with the larger alpha, on top, is the longer one)
        k = -((vl + vr) / 2 - vm) * 2 / xq**2
        errs.append(abs(k / kappa - 1))
        if table:
            print(f"| {2 * nx} x {2 * ny} | {k:.6e} | {errs[-1]:.2e} |")
    if table:
        print(f"Timoshenko: k = {kappa:.6e}")
    if errs[-1] > 1e-6:
        print(f"FAIL: bimetal strip: curvature errors {errs}")
        return False
    print(f"ok: bimetal strip: curvature error {errs[-1]:.2e} (CPS8, {errs})")
    return True


def ccx_study(exe, work, table):
    here = os.path.dirname(os.path.abspath(__file__))
    ref = {}
    with open(os.path.join(here, "thermal_cps8.dat.ref")) as f:
        for line in f:
            p = line.split()
            if len(p) == 4 and p[0].isdigit():
                ref[int(p[0])] = [float(x) for x in p[1:3]]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "thermal_cps8.csv")
    r = subprocess.run([exe, "-q", os.path.join(here, "thermal_cps8.inp"), "-o",
                        os.path.join(work, "thermal_cps8.lst"), "--csv", out], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: thermal_cps8.inp: exit {r.returncode}\n{r.stderr}")
        return False
    with open(os.path.join(out, "displacements.csv"), newline="") as f:
        ours = {int(row["node"]): [float(row["u1"]), float(row["u2"])] for row in csv.DictReader(f)}
    scale = max(abs(v) for u in ref.values() for v in u)
    worst = max(abs(ours[n][k] - ref[n][k]) for n in ref for k in range(2)) / scale
    if table:
        print("\n| node | ccx u1 | superjoin u1 | ccx u2 | superjoin u2 |\n|---|---|---|---|---|")
        for n in (2, 3, 5, 6, 11):
            print(f"| {n} | {ref[n][0]:.6e} | {ours[n][0]:.6e} | {ref[n][1]:.6e} | {ours[n][1]:.6e} |")
        print(f"largest difference {worst:.2e} of the largest displacement")
    if worst > 2e-3 or len(ref) != 13:
        print(f"FAIL: thermal_cps8 against ccx: difference {worst:.2e} (nodes {len(ref)})")
        return False
    print(f"ok: thermal_cps8 against ccx 2.20: largest difference {worst:.2e} of the largest displacement")
    return True


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work = argv[1], argv[2]
    table = "--table" in argv
    ok = disc_study(exe, work, table)
    ok = bimetal_study(exe, work, table) and ok
    ok = ccx_study(exe, work, table) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
