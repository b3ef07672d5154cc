#!/usr/bin/env python3
"""S8R with a thickness per node (*NODAL THICKNESS varying inside the
element), thermal loads and CENTRIF on S8R, against closed forms.

usage: verify_s8r_taper.py SUPERJOIN WORKDIR
Exit status 1 if a check fails. Prints markdown tables (doc/verification.md).

1. Tapered cantilever strip (nu = 0, so the plate is a beam; t from t0 at the
   clamp to t0/2 at the tip, linear, given at the nodes): tip deflection under
   a tip shear P and under its self weight (rho g t(x) per unit area) against
   Timoshenko beam theory with I(x) = b t(x)^3/12, A_s(x) = 5/6 b t(x):
   w = int M m/(E I) dx + int V v/(G A_s) dx, evaluated by Simpson's rule
   (2e4 panels: 1e-12). Observed convergence order with refinement along x
   (about 3.7) down to a floor of order (dt/dx)^2 (here 6e-6: the laminae of
   the degenerated solid follow the inclined faces, beam theory does not; at
   t0 = 0.02 the floor is 16 times higher).
2. Thermal strains on a free, tapered, distorted 2 x 2 S8R patch: uniform dT
   gives u = alpha dT x (round-off) and no resultants; a through-thickness
   gradient gives the spherical w = -kappa (x^2 + y^2)/2, kappa = alpha dT/dn,
   and no moments. Held in the plane / against rotation: n = -E alpha dT t/(1-nu),
   m = -E t^3 kappa / (12 (1 - nu)).
3. Rotating annular disc (CENTRIF about z, quarter with symmetry edges)
   against Timoshenko-Goodier's plane-stress solution: radial displacement
   at the outer and inner radius, convergence with refinement.
"""
import csv
import math
import os
import subprocess
import sys

FAILURES = []


def check(ok, what):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        FAILURES.append(what)


def run(exe, work, name, text):
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, name + ".inp")
    with open(deck, "w") as f:
        f.write(text)
    out = os.path.join(work, name + "_csv")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, name + ".lst"), deck],
                       stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: superjoin exited with {r.returncode} on {name}:\n{r.stderr}")
        sys.exit(1)
    disp, plate = {}, {}
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            disp[int(row["node"])] = [float(row[k]) for k in ("u1", "u2", "u3", "ur1", "ur2", "ur3")]
    path = os.path.join(out, "plate_results.csv")
    if os.path.exists(path):
        with open(path) as f:
            for row in csv.DictReader(f):
                plate[int(row["element"])] = [float(row[k]) for k in ("nx", "ny", "nxy", "mx", "my", "mxy")]
    return disp, plate


def simpson(f, a, b, n=20000):
    h = (b - a) / n
    s = f(a) + f(b)
    for i in range(1, n):
        s += (4 if i % 2 else 2) * f(a + i * h)
    return s * h / 3


def grid8(nx, ny, coord):
    """Nodes and S8R elements of an nx x ny element grid; coord(i, j) gives the
    position of grid point (i, j), 0 <= i <= 2 nx, 0 <= j <= 2 ny. Returns
    (nodes {id: (i, j, xyz)}, elements [(id, [8 node ids])])."""
    nid = {}
    nodes = {}
    for i in range(2 * nx + 1):
        for j in range(2 * ny + 1):
            if i % 2 and j % 2:
                continue
            k = len(nid) + 1
            nid[(i, j)] = k
            nodes[k] = (i, j, coord(i, j))
    elems = []
    for a in range(nx):
        for c in range(ny):
            i, j = 2 * a, 2 * c
            conn = [(i, j), (i + 2, j), (i + 2, j + 2), (i, j + 2), (i + 1, j), (i + 2, j + 1), (i + 1, j + 2),
                    (i, j + 1)]
            elems.append((len(elems) + 1, [nid[p] for p in conn]))
    return nodes, elems


def mesh_text(nodes, elems):
    lines = ["*NODE, NSET=NALL"]
    lines += [f"{k}, {x[0]:.17g}, {x[1]:.17g}, {x[2]:.17g}" for k, (_, _, x) in sorted(nodes.items())]
    lines.append("*ELEMENT, TYPE=S8R, ELSET=EALL")
    lines += [f"{e}, " + ", ".join(str(n) for n in conn) for e, conn in elems]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- tapered strip

E, L, B, T0 = 2.0e5, 1.0, 0.1, 0.005
RHO, GRAV = 7.8e-9 * 1e3, 9.81e3


def thick(x):
    return T0 * (1 - x / (2 * L))


def strip_deck(n, load):
    nodes, elems = grid8(n, 1, lambda i, j: (i * L / (2 * n), j * B / 2, 0.0))
    text = mesh_text(nodes, elems)
    text += f"*MATERIAL, NAME=M\n*ELASTIC\n{E}, 0.0\n*DENSITY\n{RHO}\n"
    text += f"*SHELL SECTION, ELSET=EALL, MATERIAL=M\n{T0}\n*NODAL THICKNESS\n"
    text += "".join(f"{k}, {thick(x[0]):.17g}\n" for k, (_, _, x) in sorted(nodes.items()))
    text += "*BOUNDARY\n" + "".join(f"{k}, 1, 6\n" for k, (i, _, _) in sorted(nodes.items()) if i == 0)
    text += "*STEP\n*STATIC\n"
    tip = {j: k for k, (i, j, _) in nodes.items() if i == 2 * n}
    if load == "tip":
        text += f"*CLOAD\n{tip[0]}, 3, {-P_TIP / 6}\n{tip[1]}, 3, {-2 * P_TIP / 3}\n{tip[2]}, 3, {-P_TIP / 6}\n"
    else:
        text += f"*DLOAD\nEALL, GRAV, {GRAV}, 0, 0, -1\n"
    text += "*END STEP\n"
    return text, tip[1]


P_TIP = 1.0


def strip_exact(load):
    g = E / 2   # nu = 0

    def ei(x):
        return E * B * thick(x) ** 3 / 12

    def gas(x):
        return 5 / 6 * g * B * thick(x)
    if load == "tip":
        return simpson(lambda x: P_TIP * (L - x) ** 2 / ei(x), 0, L) + simpson(lambda x: P_TIP / gas(x), 0, L)

    # self weight q(s) = rho g b t(s): V(x) = int_x^L q, M(x) = int_x^L q (s - x) (t linear: closed form)
    def q(s):
        return RHO * GRAV * B * thick(s)

    def shear(x):
        return (L - x) * (q(x) + q(L)) / 2

    def moment(x):
        # q linear from q(x) to q(L) over length l = L - x: M = l^2 (q(x) + 2 q(L))/6
        return (L - x) ** 2 * (q(x) + 2 * q(L)) / 6
    return simpson(lambda x: moment(x) * (L - x) / ei(x), 0, L) + simpson(lambda x: shear(x) / gas(x), 0, L)


def tapered_strip(exe, work):
    for load, title in (("tip", "tip shear P"), ("grav", "self weight rho g t(x)")):
        exact = strip_exact(load)
        print(f"\n### Tapered S8R cantilever strip (t {T0} -> {T0 / 2}, L/b = {L / B:g}, nu = 0), {title}\n")
        print(f"Timoshenko beam, I(x) = b t(x)^3/12: w_tip = {exact:.10e}\n")
        print("| elements along x | w_tip | / exact | error | order |")
        print("|---|---|---|---|---|")
        errs = []
        for n in (2, 4, 8, 16):
            text, node = strip_deck(n, load)
            disp, _ = run(exe, work, f"strip_{load}_{n}", text)
            w = -disp[node][2]
            err = abs(w / exact - 1)
            order = math.log2(errs[-1] / err) if errs and err > 0 else float("nan")
            errs.append(err)
            print(f"| {n} | {w:.10e} | {w / exact:.8f} | {err:.2e} | {order:.2f} |")
        check(errs[-1] < 5e-6, f"tapered strip, {title}: 16 elements within 5e-6 of the closed form ({errs[-1]:.1e})")
        check(errs[2] < errs[0] / 100, f"tapered strip, {title}: the error falls at least 100-fold from 2 to 8 "
              f"elements (order >= 2.2; {errs[0]:.1e} -> {errs[2]:.1e})")


# ---------------------------------------------------------------- thermal

ALPHA, NU = 1.2e-5, 0.3


def patch_deck(dt, grad, held, taper=True):
    def coord(i, j):
        s, t = i / 4, j / 4
        d = 0.06 * math.sin(2 * math.pi * s) * math.sin(2 * math.pi * t)
        return (2.0 * s + d, 1.5 * t - d, 0.0)
    nodes, elems = grid8(2, 2, coord)
    origin = next(k for k, (i, j, _) in nodes.items() if i == 0 and j == 0)
    text = mesh_text(nodes, elems)
    text += f"*MATERIAL, NAME=M\n*ELASTIC\n{E}, {NU}\n*EXPANSION\n{ALPHA}\n"
    text += "*SHELL SECTION, ELSET=EALL, MATERIAL=M\n0.05\n"
    if taper:
        text += "*NODAL THICKNESS\n" + "".join(f"{k}, {0.05 + 0.02 * x[0] - 0.01 * x[1]:.17g}\n"
                                               for k, (_, _, x) in sorted(nodes.items()))
    text += "*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 20.0\n*BOUNDARY\n"
    if held == "free":
        text += f"{origin}, 1, 6\n"
    elif held == "plane":
        text += "NALL, 1, 2\nNALL, 6, 6\n" + f"{origin}, 3, 5\n"
    else:   # rotations held, translations free but the origin
        text += "NALL, 4, 6\n" + f"{origin}, 1, 3\n"
    text += f"*STEP\n*STATIC\n*TEMPERATURE\nNALL, {20.0 + dt}, {grad}\n*NODE PRINT, NSET=NALL\nNT\n*END STEP\n"
    thick_at = {e: (0.05 + 0.02 * sum(nodes[c][2][0] for c in conn[:4]) / 4 - 0.01 * sum(nodes[c][2][1]
                    for c in conn[:4]) / 4 if taper else 0.05) for e, conn in elems}
    return text, nodes, elems, thick_at


def thermal(exe, work):
    print("\n### S8R thermal strains (free / held 2 x 2 distorted, tapered patch)\n")
    dt, grad = 50.0, 400.0
    text, nodes, elems, _ = patch_deck(dt, 0.0, "free", taper=False)
    disp, plate = run(exe, work, "thermal_free", text)
    e0 = ALPHA * dt
    err = max(abs(disp[k][c] - e0 * x[c]) for k, (_, _, x) in nodes.items() for c in range(2))
    err = max([err] + [abs(disp[k][c]) for k in nodes for c in range(2, 6)])
    check(err < 1e-10 * e0 * 2, f"free, uniform dT: u = alpha dT x, w = rotations = 0 (max error {err:.1e}, "
          f"alpha dT x up to {2 * e0:.1e})")
    nmax = max(abs(v) for r in plate.values() for v in r)
    check(nmax < 1e-8 * E * e0 * 0.05, f"free, uniform dT: no resultants (max {nmax:.1e}, "
          f"E alpha dT t = {E * e0 * 0.05:.1e})")
    with open(os.path.join(work, "thermal_free.lst")) as f:
        lst = f.read()
    rows = [ln.split() for ln in lst[lst.index("    NT  temperatures"):].splitlines()[2:]]
    temps = [float(r[2].replace("E", "e")) for r in rows if len(r) == 3 and r[1].isdigit()]
    check(len(temps) == len(nodes) and all(t == 20.0 + dt for t in temps),
          f"*NODE PRINT NT: the step's temperature {20.0 + dt} at all {len(nodes)} nodes")
    text, nodes, elems, _ = patch_deck(dt, 0.0, "free")
    disp, plate = run(exe, work, "thermal_free_tapered", text)
    err = max(abs(disp[k][c] - e0 * x[c]) for k, (_, _, x) in nodes.items() for c in range(2)) / (2 * e0)
    nmax = max(abs(v) for r in plate.values() for v in r[:3]) / (E * e0 * 0.05)
    print(f"  tapered (dt/dx = 0.02, dt/dy = -0.01): free expansion to {err:.1e} of alpha dT x, resultants "
          f"{nmax:.1e} of E alpha dT t (the director does not stretch with the laminae tilted by dt/dx/2)")
    check(err < 1e-4 and nmax < 1e-4, "free, uniform dT, tapered: u = alpha dT x and no resultants within "
          "1e-4 (order (dt/dx)^2)")
    text, nodes, elems, _ = patch_deck(0.0, grad, "free", taper=False)
    disp, plate = run(exe, work, "thermal_gradient_free", text)
    kap = ALPHA * grad
    err = 0.0
    for k, (_, _, x) in nodes.items():
        want = [0.0, 0.0, -kap * (x[0] ** 2 + x[1] ** 2) / 2, -kap * x[1], kap * x[0], 0.0]
        err = max(err, max(abs(disp[k][c] - want[c]) for c in range(6)))
    check(err < 1e-10 * kap * 6, f"free, gradient: w = -kappa (x^2 + y^2)/2, theta = (-kappa y, kappa x) "
          f"(max error {err:.1e}, kappa = {kap:.1e})")
    mmax = max(abs(v) for r in plate.values() for v in r)
    check(mmax < 1e-8 * E * kap * 0.05 ** 3, f"free, gradient: no resultants (max {mmax:.1e})")
    text, nodes, elems, tc = patch_deck(dt, 0.0, "plane")
    disp, plate = run(exe, work, "thermal_held", text)
    err = max(abs(plate[e][c] - (-E * e0 * tc[e] / (1 - NU) if c < 2 else 0.0)) / (E * e0 * tc[e] / (1 - NU))
              for e in plate for c in range(3))
    print(f"  held in the plane: nx = ny = -E alpha dT t/(1 - nu) at the centre, t interpolated; "
          f"element 1 nx = {plate[1][0]:.10e}, exact {-E * e0 * tc[1] / (1 - NU):.10e}")
    check(err < 1e-10, f"held in the plane, uniform dT: n = -E alpha dT t/(1-nu), nxy = 0 (max rel. error {err:.1e})")
    text, nodes, elems, tc = patch_deck(0.0, grad, "rot", taper=False)
    disp, plate = run(exe, work, "thermal_gradient_held", text)
    m0 = E * 0.05 ** 3 * kap / (12 * (1 - NU))
    err = max(abs(plate[e][3 + c] - (-m0 if c < 2 else 0.0)) / m0 for e in plate for c in range(3))
    print(f"  rotations held, gradient: m = -E t^3 kappa/(12 (1 - nu)); element 1 mx = {plate[1][3]:.10e}, "
          f"exact {-m0:.10e}")
    check(err < 1e-8, f"rotations held, gradient: mx = my = -E t^3 alpha dT/dn/(12 (1-nu)) (max rel. error {err:.1e})")


# ---------------------------------------------------------------- rotating disc

def disc_deck(n, a, b, omega2, rho):
    def coord(i, j):
        r = a + (b - a) * i / (2 * n)
        th = math.pi / 2 * j / (2 * n)
        return (r * math.cos(th), r * math.sin(th), 0.0)
    nodes, elems = grid8(n, n, coord)
    text = mesh_text(nodes, elems)
    text += f"*MATERIAL, NAME=M\n*ELASTIC\n{E}, {NU}\n*DENSITY\n{rho}\n"
    text += "*SHELL SECTION, ELSET=EALL, MATERIAL=M\n0.01\n*BOUNDARY\nNALL, 3, 5\n"
    text += "".join(f"{k}, 2, 2\n{k}, 6, 6\n" for k, (i, j, _) in sorted(nodes.items()) if j == 0)
    text += "".join(f"{k}, 1, 1\n{k}, 6, 6\n" for k, (i, j, _) in sorted(nodes.items()) if j == 2 * n)
    text += f"*STEP\n*STATIC\n*DLOAD\nEALL, CENTRIF, {omega2}, 0, 0, 0, 0, 0, 1\n*END STEP\n"
    return text, nodes


def disc_exact(r, a, b, omega2, rho):
    c = (3 + NU) / 8 * rho * omega2
    sr = c * (a * a + b * b - a * a * b * b / r ** 2 - r * r)
    st = c * (a * a + b * b + a * a * b * b / r ** 2 - (1 + 3 * NU) / (3 + NU) * r * r)
    return r / E * (st - NU * sr)


def disc(exe, work):
    a, b, omega2, rho = 0.2, 1.0, 1.0e6, 7.8e-9
    ua, ub = disc_exact(a, a, b, omega2, rho), disc_exact(b, a, b, omega2, rho)
    print("\n### Rotating annular disc, S8R, CENTRIF (a/b = 0.2, nu = 0.3): radial displacement\n")
    print(f"Timoshenko-Goodier (plane stress): u(a) = {ua:.10e}, u(b) = {ub:.10e}\n")
    print("| mesh (elements) | u(b) / exact | u(a) / exact | max error | order |")
    print("|---|---|---|---|---|")
    errs = []
    for n in (1, 2, 4, 8):
        text, nodes = disc_deck(n, a, b, omega2, rho)
        disp, _ = run(exe, work, f"disc_{n}", text)
        err, rat = 0.0, {}
        for k, (i, j, x) in nodes.items():
            r = math.hypot(x[0], x[1])
            ur = (disp[k][0] * x[0] + disp[k][1] * x[1]) / r
            ut = (-disp[k][0] * x[1] + disp[k][1] * x[0]) / r
            want = disc_exact(r, a, b, omega2, rho)
            err = max(err, abs(ur - want) / ub, abs(ut) / ub)
            if j == 0 and i in (0, 2 * n):
                rat[i] = ur / want
        order = math.log2(errs[-1] / err) if errs else float("nan")
        errs.append(err)
        print(f"| {n} x {n} | {rat[2 * n]:.8f} | {rat[0]:.8f} | {err:.2e} | {order:.2f} |")
    check(errs[-1] < 1e-4, f"rotating disc: 8 x 8 within 1e-4 of u(b) everywhere ({errs[-1]:.1e})")
    check(errs[-1] < errs[1] / 50, f"rotating disc: the error falls at least 50-fold from 2 x 2 to 8 x 8 "
          f"({errs[1]:.1e} -> {errs[-1]:.1e})")


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    exe, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    tapered_strip(exe, work)
    thermal(exe, work)
    disc(exe, work)
    if FAILURES:
        print(f"\nFAIL: {len(FAILURES)} checks")
        sys.exit(1)
    print("\nall checks passed")


if __name__ == "__main__":
    main()
