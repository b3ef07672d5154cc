#!/usr/bin/env python3
"""B32 (three-node beam) thermal loads against closed forms.

usage: verify_thermal_b32.py SUPERJOIN WORKDIR [--table]

The nodal values of alpha dT and of the gradients across the section (CalculiX's
*TEMPERATURE fields 3: local z, and 4: local y) are interpolated along the
element to its two Gauss points, where they are the initial strains
eps0 = alpha dT, kappa0 = alpha grad (module superjoin_elements_beam3).
1. Straight beam, 4 B32 (9 nodes), length L:
   free (cantilever) under uniform dT: tip u1 = alpha dT L, no force;
   clamped at both ends: N = -E A alpha dT in every element, no displacement;
   cantilever with gradient g (each field): tip deflection -alpha g L^2/2,
   rotation alpha g L, no stress; clamped: M = E I alpha g, fibre stress
   -E alpha (dT + g y);
   gradient varying linearly along the cantilever, g0 + g1 x/L: tip
   -alpha L^2 (g0/2 + g1/6), stress-free (a linear curvature is held
   exactly by the quadratic element);
   T varying quadratically along a free bar, T = T0 + c (x/L)^2: tip
   u1 = alpha L (T0 + c/3) (every element takes its quadratic exactly).
   All to round-off (1e-12 relative).
2. Quarter ring of radius R, 8 curved B32, one end held (all six DOFs) and the
   other end free: a uniform dT expands it radially, every node moves to
   (1 + alpha dT) times its position about the centre, with no force
   (u = alpha dT (x - x1) is linear in x, which the isoparametric element
   holds exactly whatever its curvature): 1e-10 (round-off of the ring's
   stiffness ratio).
"""
import csv
import math
import os
import subprocess
import sys

E, NU, ALPHA = 2.0e11, 0.3, 1.2e-5


def run(exe, work, name, text):
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, name + ".deck")
    with open(deck, "w") as f:
        f.write(text)
    out = os.path.join(work, name + ".csv")
    r = subprocess.run([exe, "-q", deck, "-o", os.path.join(work, name + ".lst"), "--csv", out],
                       stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise SystemExit(f"FAIL: {name}: exit {r.returncode}\n{r.stderr}")
    res = {}
    for table in ("displacements", "element_forces", "fibre_stresses"):
        path = os.path.join(out, table + ".csv")
        if os.path.exists(path):
            with open(path, newline="") as f:
                res[table] = list(csv.DictReader(f))
    return res


def deck(nodes, elems, held, temps, title, vector="0., 1., 0."):
    lines = ["*HEADING", title, "*NODE, NSET=ALL"]
    lines += [f"{k + 1}, {x!r}, {y!r}, 0.0" for k, (x, y) in enumerate(nodes)]
    lines.append("*ELEMENT, TYPE=B32, ELSET=B")
    lines += [f"{k + 1}, " + ", ".join(str(c) for c in e) for k, e in enumerate(elems)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}",
              "*BEAM SECTION, ELSET=B, MATERIAL=M, SECTION=RECT", "0.1, 0.2", vector,
              "*BOUNDARY"]
    lines += [f"{n}, 1, 6" for n in held]
    lines += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALL, 20.0", "*STEP", "*STATIC", "*TEMPERATURE"]
    lines += temps
    lines += ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    return "\n".join(lines) + "\n"


def straight(n, length):
    nodes = [(length * i / (2 * n), 0.0) for i in range(2 * n + 1)]
    elems = [(2 * i + 1, 2 * i + 2, 2 * i + 3) for i in range(n)]
    return nodes, elems


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work, table = argv[1], argv[2], "--table" in argv
    ok, rows = True, []
    length, b, h, n = 2.0, 0.1, 0.2, 4
    # RECT b, h: b along the section's 1-direction (local y), h along local z
    area, iy, iz = b * h, b * h ** 3 / 12, h * b ** 3 / 12
    nodes, elems = straight(n, length)
    tip = 2 * n + 1
    dt, g = 5.0, 10.0

    def check(name, err, tol, result):
        nonlocal ok
        rows.append((name, result, f"{err:.1e}"))
        if not err <= tol:
            print(f"FAIL: B32 {name}: error {err:.2e} (tolerance {tol:.0e})")
            ok = False
        else:
            print(f"ok: B32 {name}: {result} (error {err:.1e})")

    def node_row(res, k):
        return [r for r in res["displacements"] if int(r["node"]) == k][0]

    def smax(res):
        """The largest end force or moment as a fibre stress: |N|/A + |M| c/I."""
        return max(abs(float(r["n"])) / area + (abs(float(r["my"])) * h / 2 / iy + abs(float(r["mz"])) * b / 2 / iz)
                   for r in res["element_forces"])

    # uniform dT, free: tip u1 = alpha dT L, no stress
    res = run(exe, work, "b32_free_dt", deck(nodes, elems, [1], [f"ALL, {20.0 + dt}"], "B32 free dT"))
    u = float(node_row(res, tip)["u1"])
    err = max(abs(u / (ALPHA * dt * length) - 1), smax(res) / (E * ALPHA * dt))
    check("free, uniform dT", err, 1e-12, f"tip u1 {u:.6e} (alpha dT L = {ALPHA * dt * length:.6e})")
    # uniform dT, clamped: N = -E A alpha dT
    res = run(exe, work, "b32_clamped_dt", deck(nodes, elems, [1, tip], [f"ALL, {20.0 + dt}"], "B32 clamped dT"))
    nerr = max(abs(abs(float(r["n"])) - E * area * ALPHA * dt) for r in res["element_forces"]) / (E * area * ALPHA * dt)
    serr = max(abs(float(r[k])) for r in res["element_forces"] for k in ("vy", "vz", "t", "my", "mz")) / \
        (E * area * ALPHA * dt)
    sign = all(float(r["n"]) * (1 if r["end"] == "1" else -1) > 0 for r in res["element_forces"])
    umax = max(abs(float(r[k])) for r in res["displacements"] for k in ("u1", "u2", "u3"))
    check("clamped, uniform dT", max(nerr, serr, umax / (ALPHA * dt * length), 0 if sign else 1), 1e-12,
          f"|N| = E A alpha dT = {E * area * ALPHA * dt:.6e}, compression, sigma = -E alpha dT")
    # gradients: field 3 along local z, field 4 along local y
    for field, line in (("3", f"ALL, 20.0, {g}"), ("4", f"ALL, 20.0, 0.0, {g}")):
        res = run(exe, work, f"b32_free_g{field}", deck(nodes, elems, [1], [line], f"B32 free gradient {field}"))
        row = node_row(res, tip)
        # section vector (0, 1, 0): local y = Y, local z = Z, as the B31 test of verify_thermal.py;
        # the fibres at +y (+z) grow: the beam bends towards -y (-z), turning about z (y) by -+alpha g L
        ucol, rcol, sgn = ("u3", "ur2", 1.0) if field == "3" else ("u2", "ur3", -1.0)
        w, th = float(row[ucol]), float(row[rcol])
        w_exact = -ALPHA * g * length ** 2 / 2
        err = max(abs(w / w_exact - 1), abs(th / (sgn * ALPHA * g * length) - 1), smax(res) / (E * ALPHA * g * h))
        check(f"free, gradient field {field}", err, 1e-12,
              f"tip {ucol} {w:.6e} (-alpha g L^2/2 = {w_exact:.6e}), stress-free")
        res = run(exe, work, f"b32_clamped_g{field}",
                  deck(nodes, elems, [1, tip], [line.replace("20.0", f"{20.0 + dt}", 1)], f"B32 clamped g{field}"))
        umax = max(abs(float(r[k])) for r in res["displacements"] for k in ("u1", "u2", "u3", "ur1", "ur2", "ur3"))
        # M = E I alpha g about the axis normal to the gradient; fibre stress -E alpha (dT + g c)
        inertia = iz if field == "4" else iy
        mcol = "mz" if field == "4" else "my"
        merr = max(abs(abs(float(r[mcol])) - E * inertia * ALPHA * g) for r in res["element_forces"]) / \
            (E * inertia * ALPHA * g)
        nerr = max(abs(float(r["n"]) * (1 if r["end"] == "1" else -1) - E * area * ALPHA * dt)
                   for r in res["element_forces"]) / (E * area * ALPHA * dt)
        other = "mz" if mcol == "my" else "my"
        serr = max(abs(float(r[k])) for r in res["element_forces"] for k in ("vy", "vz", "t", other)) / \
            (E * inertia * ALPHA * g)
        check(f"clamped, dT and gradient field {field}", max(merr, nerr, serr, umax), 1e-12,
              f"|{mcol}| = E I alpha g = {E * inertia * ALPHA * g:.6e}, N = -E A alpha dT")
    # a gradient varying linearly along the cantilever (field 4, local y)
    g0, g1 = 10.0, 30.0
    temps = [f"{k + 1}, 20.0, 0.0, {g0 + g1 * x / length!r}" for k, (x, _) in enumerate(nodes)]   # local y
    res = run(exe, work, "b32_free_slope", deck(nodes, elems, [1], temps, "B32 gradient along"))
    row = node_row(res, tip)
    w_exact = ALPHA * length ** 2 * (g0 / 2 + g1 / 6)
    w = float(row["u2"])
    err = max(abs(-w / w_exact - 1), smax(res) / (E * ALPHA * g0 * h))
    check("free, gradient 10 to 40 along it", err, 1e-12,
          f"tip u2 {w:.6e} (-) (alpha L^2 (g0/2 + g1/6) = {w_exact:.6e}), stress-free")
    # T quadratic along a free bar
    c = 40.0
    temps = [f"{k + 1}, {20.0 + 5.0 + c * (x / length) ** 2!r}" for k, (x, _) in enumerate(nodes)]
    res = run(exe, work, "b32_free_quadratic", deck(nodes, elems, [1], temps, "B32 T quadratic"))
    u = float(node_row(res, tip)["u1"])
    u_exact = ALPHA * length * (5.0 + c / 3)
    err = max(abs(u / u_exact - 1), smax(res) / (E * ALPHA * c))
    check("free, T quadratic along it", err, 1e-12, f"tip u1 {u:.6e} (alpha L (T0 + c/3) = {u_exact:.6e})")
    # quarter ring of radius R, uniform dT, one end clamped: u = alpha dT x
    radius, m = 3.0, 8
    ring = [(radius * math.cos(math.pi / 2 * i / (2 * m)), radius * math.sin(math.pi / 2 * i / (2 * m)))
            for i in range(2 * m + 1)]
    relems = [(2 * i + 1, 2 * i + 2, 2 * i + 3) for i in range(m)]
    # held at node 1 (x = R, y = 0): the similarity about the centre is u = alpha dT (x - x1) plus
    # nothing else only if the held node stays; hold it and compare u - u(node 1) = alpha dT (x - x1)
    res = run(exe, work, "b32_ring", deck(ring, relems, [1], [f"ALL, {20.0 + dt}"], "B32 quarter ring", "0., 0., 1."))
    worst = 0.0
    for r in res["displacements"]:
        k = int(r["node"]) - 1
        ex = ALPHA * dt * (ring[k][0] - ring[0][0])
        ey = ALPHA * dt * (ring[k][1] - ring[0][1])
        worst = max(worst, abs(float(r["u1"]) - ex), abs(float(r["u2"]) - ey), abs(float(r["u3"])),
                    abs(float(r["ur1"])), abs(float(r["ur2"])), abs(float(r["ur3"])) * radius)
    forces = max(abs(float(r[k])) for r in res["element_forces"] for k in ("n", "vy", "vz", "t", "my", "mz"))
    err = max(worst / (ALPHA * dt * radius), forces / (E * area * ALPHA * dt))
    print(f"   ring: displacement error {worst / (ALPHA * dt * radius):.1e}, forces {forces / (E * area * ALPHA * dt):.1e}")
    check("free quarter ring, uniform dT", err, 1e-10,
          f"expands by alpha dT about the held end (radius R alpha dT = {radius * ALPHA * dt:.4e}), no force")
    if table:
        print("\n| B32 case | result | relative error |\n|---|---|---|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
