#!/usr/bin/env python3
"""Temperatures inside elements (interpolated to the integration points) and
beam temperature gradients, against closed forms.

usage: verify_thermal.py SUPERJOIN WORKDIR [--table]

1. Free plate, temperature linear in x and y, T = T0 + a x + b y: the thermal
   strain alpha T (1, 1, 0) is compatible, the exact solution is stress-free
   and its displacement is the integral of the strain,
     u = alpha (T0 x + a x^2/2 - a y^2/2 + b x y),
     v = alpha (T0 y + b y^2/2 - b x^2/2 + a x y)
   (plane strain: (1 + nu) times, sigma_zz = -E alpha T), plus the rigid
   rotation the supports leave (node 1 at the origin held, the node farthest
   along x held in y).
   The quadratic elements hold this field exactly on straight-sided meshes of
   any shape (CPS6/CPE6: randomly distorted triangles; CPS8/CPE8/CPS8R/CPE8R:
   a skewed mesh of parallelograms), and so does CPS4/CPE4 (QM6) on
   parallelograms with its incompatible modes (which take their share of the
   thermal load before they are condensed), so with the temperature interpolated to
   the integration points every stress is 0 to 1e-10 of E alpha dT and every
   displacement the exact one to 1e-10; the element values of *EL PRINT S
   (at the centroid; plane strain sigma_zz = -E alpha T there) to the 7
   digits of the listing. CPS8 and CPE4 also solve a load combination
   2 x the step: its stresses are 0 too (the superposed temperatures are
   taken off). (The element mean of the nodal
   temperatures, what superjoin did before, leaves stresses of order
   E alpha a h: the table in doc/verification.md.)
2. Quadratic temperature across a long free strip (plane stress), T = T0 y^2/c^2,
   |y| <= c, length 20 c: away from the ends (Timoshenko & Goodier, sec. 150)
     sigma_x = E alpha T0 (1/3 - y^2/c^2),
   checked at the middle section at y = 0 and y = c (nodal stresses); CPS8
   meshes halved three times: error below 1e-2 on the finest and falling at
   a rate >= 1.8 on the last halving (the mean of the nodal temperatures per
   element, a staircase, converges at rate 1).
3. Beams (B21, B23, B31, B33) with gradients across the section, CalculiX's
   *TEMPERATURE fields 3 (along the section's 2-direction: local z of B31/B33,
   the in-plane local y of B21/B23) and 4 (1-direction, local y): a cantilever
   bends freely, tip deflection -alpha g L^2/2 and rotation alpha g L, with
   no stress (fibre stresses < 1e-12 E alpha g h); clamped at both ends it does
   not move and its fibres carry -E alpha (dT + g y) (1e-12).
   A gradient varying linearly along the beam (nodal values 10 to 40, 4
   elements, the element interpolating between its nodes): the cantilever's
   tip deflects -alpha L^2 (g0/2 + g1/6) and turns alpha L (g0 + g1/2),
   stress-free (all four types); clamped, the Euler-Bernoulli B23/B33 do not
   move and carry -E alpha g(x) y at every element end (1e-12; the free
   bending is a cubic, which the elements hold). A clamped Timoshenko beam
   does move (the slope of the thermal moment is a shear force): one B21
   element clamped at both ends has the fixed-end shear E I b/(1 + phi) of
   kappa0 = a + b x, phi = 12 E I/(k G A L^2), and end moments that balance it.
   A temperature rising linearly along a clamped beam (4 elements): every
   element carries N = -E A alpha (the beam's mean dT), 1e-12.
4. CalculiX: thermal_linear_cps8.inp (a CPS8 plate clamped at x = 0, T linear
   in x and y) run unchanged, against thermal_linear_cps8.dat.ref written by
   ccx 2.20 from the same file (ccx expands the plane-stress CPS8 into a layer
   of C3D20 bricks: agreement to 2e-3 of the largest displacement).
With --table the tables of doc/verification.md are printed.
"""
import csv
import math
import os
import random
import subprocess
import sys

E, NU, ALPHA, THICK = 2.0e11, 0.3, 1.2e-5, 0.1


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
    for table in ("displacements", "point_stresses", "nodal_stresses", "fibre_stresses"):
        path = os.path.join(out, table + ".csv")
        if os.path.exists(path):
            with open(path, newline="") as f:
                res[table] = list(csv.DictReader(f))
    return res


# ------------------------------------------------------------ 1. linear field

def lin_temp(x, y):
    return 20.0 + 60.0 * x - 40.0 * y


def lin_exact(x, y, strain):
    k = ALPHA * (1 + NU if strain else 1.0)
    t0, a, b = 20.0, 60.0, -40.0
    return (k * (t0 * x + a * x * x / 2 - a * y * y / 2 + b * x * y),
            k * (t0 * y + b * y * y / 2 - b * x * x / 2 + a * x * y))


def tri_mesh(n, seed):
    """Straight-sided 6-node triangles on a randomly perturbed n x n grid of [0,1]^2."""
    rnd = random.Random(seed)
    h = 1.0 / n
    corner = {}
    for i in range(n + 1):
        for j in range(n + 1):
            dx = dy = 0.0
            if 0 < i < n and 0 < j < n:
                dx, dy = rnd.uniform(-0.3, 0.3) * h, rnd.uniform(-0.3, 0.3) * h
            elif 0 < i < n:
                dx = rnd.uniform(-0.3, 0.3) * h
            elif 0 < j < n:
                dy = rnd.uniform(-0.3, 0.3) * h
            corner[(i, j)] = (i * h + dx, j * h + dy)
    nodes, ids, elems = [], {}, []

    def node(p):
        key = (round(p[0], 12), round(p[1], 12))
        if key not in ids:
            nodes.append(p)
            ids[key] = len(nodes)
        return ids[key]

    def mid(p, q):
        return ((p[0] + q[0]) / 2, (p[1] + q[1]) / 2)
    for i in range(n):
        for j in range(n):
            a, b, c, d = corner[(i, j)], corner[(i + 1, j)], corner[(i + 1, j + 1)], corner[(i, j + 1)]
            for t in ((a, b, c), (a, c, d)):
                elems.append([node(t[0]), node(t[1]), node(t[2]), node(mid(t[0], t[1])),
                              node(mid(t[1], t[2])), node(mid(t[2], t[0]))])
    return nodes, elems


def quad_mesh(nx, ny, skew=0.35, lift=0.2):
    """8-node parallelograms: the rectangle grid of [0,1]^2 under x' = x + skew y, y' = y + lift x."""
    nodes, ids, elems = [], {}, []
    mx, my = 2 * nx, 2 * ny
    for i in range(mx + 1):
        for j in range(my + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            x, y = i / mx, j / my
            nodes.append((x + skew * y, y + lift * x))
            ids[(i, j)] = len(nodes)
    for i in range(nx):
        for j in range(ny):
            i0, j0 = 2 * i, 2 * j
            elems.append([ids[(i0, j0)], ids[(i0 + 2, j0)], ids[(i0 + 2, j0 + 2)], ids[(i0, j0 + 2)],
                          ids[(i0 + 1, j0)], ids[(i0 + 2, j0 + 1)], ids[(i0 + 1, j0 + 2)], ids[(i0, j0 + 1)]])
    return nodes, elems


def quad4_mesh(nx, ny):
    """4-node parallelograms: the corners of quad_mesh."""
    nodes, elems = quad_mesh(nx, ny)
    used = sorted({n for e in elems for n in e[:4]})
    new = {old: k + 1 for k, old in enumerate(used)}
    return [nodes[n - 1] for n in used], [[new[n] for n in e[:4]] for e in elems]


def plate_deck(etype, nodes, elems, temp, supports, combination=False):
    lines = ["*HEADING", f"free plate {etype}", "*NODE, NSET=ALL"]
    lines += [f"{k + 1}, {x!r}, {y!r}" for k, (x, y) in enumerate(nodes)]
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=P")
    lines += [f"{k + 1}, " + ", ".join(map(str, c)) for k, c in enumerate(elems)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}",
              "*SOLID SECTION, ELSET=P, MATERIAL=M", f"{THICK}", "*BOUNDARY"] + supports
    lines += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALL, 0.0", "*STEP", "*STATIC", "*TEMPERATURE"]
    lines += [f"{k + 1}, {temp(x, y)!r}" for k, (x, y) in enumerate(nodes)]
    lines += ["*NODE FILE", "U, S", "*EL FILE", "S", "*EL PRINT, ELSET=P", "S", "*END STEP"]
    if combination:   # results of 2 x the step: superposed, temperatures included
        lines += ["*LOAD COMBINATION, NAME=TWICE", "1, 2.0"]
    return "\n".join(lines) + "\n"


def element_values(work, name):
    """The element (centroid) stresses of *EL PRINT S in the listing: {element: [xx, yy, zz, xy]}."""
    out, on = {}, False
    with open(os.path.join(work, name + ".lst")) as f:
        for line in f:
            if "S   stresses (global axes" in line:
                on = True
                continue
            if on:
                p = line.split()
                if len(p) == 9 and p[1].isdigit():
                    out[int(p[1])] = [float(v) for v in p[3:7]]
                elif out:
                    break
    return out


def factor(row):
    """1 for the step, 2 for the combination TWICE (2 x the step)."""
    return 1 if row["step"] == "1" else 2


def linear_study(exe, work, table):
    ok = True
    rows = []
    cases = [("CPS6", tri_mesh(3, 7)), ("CPE6", tri_mesh(3, 11)),
             ("CPS8", quad_mesh(3, 2)), ("CPE8", quad_mesh(3, 2)),
             ("CPS8R", quad_mesh(3, 2)), ("CPE8R", quad_mesh(3, 2)),
             ("CPS4", quad4_mesh(3, 2)), ("CPE4", quad4_mesh(3, 2))]
    for etype, (nodes, elems) in cases:
        strain = etype.startswith("CPE")
        # node 1 at the origin held, the node farthest along x held in y
        n2 = max(range(len(nodes)), key=lambda k: nodes[k][0])
        combo = etype in ("CPS8", "CPE4")
        res = run(exe, work, f"linear_{etype}", plate_deck(etype, nodes, elems, lin_temp,
                                                            ["1, 1, 2", f"{n2 + 1}, 2, 2"], combo))
        dtmax = max(abs(lin_temp(x, y)) for x, y in nodes)
        scale = E * ALPHA * dtmax
        sig = 0.0
        for tab in ("point_stresses", "nodal_stresses"):
            for r in res[tab]:
                sig = max(sig, abs(float(r["sxx"])), abs(float(r["syy"])), abs(float(r["sxy"])))
        szz = 0.0
        if strain:    # sigma_zz = -E alpha T at the nodes (the combination: twice)
            for r in res["nodal_stresses"]:
                x, y = nodes[int(r["node"]) - 1]
                szz = max(szz, abs(float(r["szz"]) + factor(r) * E * ALPHA * lin_temp(x, y)))
        if combo and {factor(r) for r in res["point_stresses"]} != {1, 2}:
            print(f"FAIL: free plate, linear T, {etype}: the combination's stresses are missing")
            ok = False
        # the element values of *EL PRINT S (listing, 7 digits) at the area centroid
        # (straight sides, affine: the mean of the corners): 0, plane strain sigma_zz = -E alpha T
        ev = element_values(work, f"linear_{etype}")
        ncorner = 3 if len(elems[0]) in (3, 6) else 4
        eerr = 0.0
        for k, c in enumerate(elems):
            xc = sum(nodes[n - 1][0] for n in c[:ncorner]) / ncorner
            yc = sum(nodes[n - 1][1] for n in c[:ncorner]) / ncorner
            want = [0.0, 0.0, -E * ALPHA * lin_temp(xc, yc) if strain else 0.0, 0.0]
            eerr = max(eerr, max(abs(a - b) for a, b in zip(ev[k + 1], want)))
        if len(ev) != len(elems) or eerr > 1e-6 * scale:
            print(f"FAIL: free plate, linear T, {etype}: *EL PRINT S element values off by {eerr / scale:.2e}")
            ok = False
        # exact displacement with the rigid rotation of the supports: v(node 2) = 0
        x2, y2 = nodes[n2]
        w = -lin_exact(x2, y2, strain)[1] / x2
        umax = max(max(abs(c) for c in lin_exact(x, y, strain)) for x, y in nodes)
        du = 0.0
        for r in res["displacements"]:
            x, y = nodes[int(r["node"]) - 1]
            ue, ve = lin_exact(x, y, strain)
            ue, ve = ue - w * y, ve + w * x
            f = factor(r)    # the combination TWICE: 2 x step 1
            du = max(du, abs(float(r["u1"]) - f * ue), abs(float(r["u2"]) - f * ve))
        rows.append((etype, len(elems), sig / scale, szz / scale, du / umax))
        if sig > 1e-10 * scale or szz > 1e-10 * scale or du > 1e-10 * umax:
            print(f"FAIL: free plate, linear T, {etype}: stress {sig / scale:.2e}, szz {szz / scale:.2e}, "
                  f"displacement {du / umax:.2e} (relative; want 1e-10)")
            ok = False
        else:
            print(f"ok: free plate, linear T, {etype} ({len(elems)} elements): stress {sig / scale:.1e}, "
                  f"displacement {du / umax:.1e} of the exact")
    if table:
        print("\n| element | elements | max in-plane stress / (E α ΔT_max) | plane strain: max σzz + E α T | "
              "max displacement error / max u |\n|---|---|---|---|---|")
        for r in rows:
            print(f"| {r[0]} | {r[1]} | {r[2]:.1e} | {r[3]:.1e} | {r[4]:.1e} |")
    return ok


# ------------------------------------------------------------ 2. quadratic field

def strip_study(exe, work, table):
    c, half, t0 = 0.5, 5.0, 100.0

    def temp(x, y):
        return t0 * (y / c) ** 2
    errs, rows = [], []
    for ny in (1, 2, 4, 8):
        nx = 10 * ny
        nodes, ids, elems = [], {}, []
        mx, my = 2 * nx, 2 * ny
        for i in range(mx + 1):
            for j in range(my + 1):
                if i % 2 == 1 and j % 2 == 1:
                    continue
                nodes.append((-half + 2 * half * i / mx, -c + 2 * c * j / my))
                ids[(i, j)] = len(nodes)
        for i in range(nx):
            for j in range(ny):
                i0, j0 = 2 * i, 2 * j
                elems.append([ids[(i0, j0)], ids[(i0 + 2, j0)], ids[(i0 + 2, j0 + 2)], ids[(i0, j0 + 2)],
                              ids[(i0 + 1, j0)], ids[(i0 + 2, j0 + 1)], ids[(i0 + 1, j0 + 2)], ids[(i0, j0 + 1)]])
        mid, top = ids[(mx // 2, my // 2)], ids[(mx // 2, my)]
        res = run(exe, work, f"strip_{ny}", plate_deck("CPS8", nodes, elems, temp,
                                                       [f"{mid}, 1, 2", f"{ids[(mx // 2, 0)]}, 1, 1"]))
        s = {int(r["node"]): float(r["sxx"]) for r in res["nodal_stresses"]}
        exact_mid, exact_top = E * ALPHA * t0 / 3, -2 * E * ALPHA * t0 / 3
        err = max(abs(s[mid] - exact_mid), abs(s[top] - exact_top)) / abs(exact_top)
        errs.append(err)
        rows.append((f"{nx} x {ny}", s[mid], s[top], err))
    rate = math.log2(errs[-2] / errs[-1])
    if table:
        print("\n| CPS8 mesh (length x depth) | σx(0, 0) | σx(0, c) | error / (2/3 E α T0) |\n|---|---|---|---|")
        for r in rows:
            print(f"| {r[0]} | {r[1]:.6e} | {r[2]:.6e} | {r[3]:.2e} |")
        print(f"closed form σx(0, 0) = {E * ALPHA * t0 / 3:.6e}, σx(0, c) = {-2 * E * ALPHA * t0 / 3:.6e}; "
              f"rate of the last halving {rate:.2f}")
    if errs[-1] > 1e-2 or rate < 1.8:
        print(f"FAIL: strip with quadratic T: errors {errs}, last rate {rate:.2f}")
        return False
    print(f"ok: strip with quadratic T (CPS8): errors {', '.join(f'{e:.1e}' for e in errs)}, last rate {rate:.2f}")
    return True


# ------------------------------------------------------------ 3. beams

def beam_deck(etype, bc, n, fields, length=2.0, b=0.1, h=0.2):
    planar = etype in ("B21", "B23")
    lines = ["*HEADING", f"beam gradient {etype} {bc}", "*NODE, NSET=ALL"]
    lines += [f"{i + 1}, {length * i / n!r}, 0.0, 0.0" for i in range(n + 1)]
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=B")
    lines += [f"{i + 1}, {i + 1}, {i + 2}" for i in range(n)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}",
              "*BEAM SECTION, ELSET=B, MATERIAL=M, SECTION=RECT", f"{b}, {h}",
              "0., 0., -1." if planar else "0., 1., 0.", "*BOUNDARY"]
    held = ["1, 1, 2", "1, 6, 6"] if planar else ["1, 1, 6"]
    lines += held
    if bc == "clamped":
        lines += [s.replace("1,", f"{n + 1},", 1) for s in held]
    lines += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALL, 20.0", "*STEP", "*STATIC", "*TEMPERATURE"]
    lines += fields
    lines += ["*NODE FILE", "U", "*EL FILE", "S", "*END STEP"]
    return "\n".join(lines) + "\n"


def beam_study(exe, work, table):
    ok = True
    rows = []
    length, b, h, n = 2.0, 0.1, 0.2, 4
    g, dt = 10.0, 5.0
    for etype in ("B23", "B21", "B33", "B31"):
        planar = etype in ("B21", "B23")
        # (field 3, field 4) -> the displacement and rotation columns, the section coordinate
        cases = [("3", f"ALL, 20.0, {g}", "u2" if planar else "u3", "ur3" if planar else "ur2",
                  "y" if planar else "z")]
        if not planar:
            cases.append(("4", f"ALL, 20.0, 0.0, {g}", "u2", "ur3", "y"))
        for field, line, ucol, rcol, coord in cases:
            res = run(exe, work, f"beam_{etype}_{field}_free", beam_deck(etype, "cantilever", n, [line]))
            tip = [r for r in res["displacements"] if int(r["node"]) == n + 1][0]
            w, th = float(tip[ucol]), float(tip[rcol])
            w_exact = -ALPHA * g * length ** 2 / 2
            # rotation: about z it is dv/dx = -alpha g L; about y it is -dw/dx = +alpha g L
            th_exact = ALPHA * g * length * (-1 if rcol == "ur3" else 1)
            smax = max(abs(float(r["sxx"])) for r in res["fibre_stresses"])
            e1 = max(abs(w / w_exact - 1), abs(th / th_exact - 1))
            rows.append((etype, f"cantilever, field {field}", f"tip {ucol} {w:.6e} (exact {w_exact:.6e})",
                         f"{e1:.1e}", f"{smax / (E * ALPHA * g * h):.1e}"))
            if e1 > 1e-12 or smax > 1e-12 * E * ALPHA * g * h:
                print(f"FAIL: {etype} cantilever, gradient field {field}: tip error {e1:.2e}, stress {smax:.2e}")
                ok = False
            res = run(exe, work, f"beam_{etype}_{field}_clamped",
                      beam_deck(etype, "clamped", n, [line.replace("20.0", f"{20.0 + dt}", 1)]))
            umax = max(abs(float(r[k])) for r in res["displacements"] for k in ("u1", "u2", "u3", "ur1", "ur2", "ur3"))
            serr = 0.0
            for r in res["fibre_stresses"]:
                s_exact = -E * ALPHA * (dt + g * float(r[coord]))
                serr = max(serr, abs(float(r["sxx"]) - s_exact))
            scale = E * ALPHA * (dt + g * h / 2)
            rows.append((etype, f"clamped, field {field}, ΔT = {dt}", f"max displacement {umax:.1e}",
                         f"{serr / scale:.1e}", "-"))
            if umax > 1e-15 or serr > 1e-12 * scale:
                print(f"FAIL: {etype} clamped, gradient field {field}: displacement {umax:.2e}, "
                      f"fibre stress error {serr / scale:.2e}")
                ok = False
        if ok:
            print(f"ok: {etype}: free cantilever bends to alpha g, clamped beam carries -E alpha (dT + g y)")
    # a gradient varying linearly along the beam, g(x) = g0 + g1 x/L, given at
    # the nodes: the cantilever's tip deflects -alpha L^2 (g0/2 + g1/6) and
    # turns alpha L (g0 + g1/2), stress-free; clamped, it does not move and the
    # fibres at x carry -E alpha g(x) z (at both ends of every element)
    g0, g1 = 10.0, 30.0
    for etype in ("B33", "B31", "B23", "B21"):
        planar = etype in ("B21", "B23")
        ucol, rcol, coord = ("u2", "ur3", "y") if planar else ("u3", "ur2", "z")
        lines = [f"{i + 1}, 20.0, {g0 + g1 * i / n!r}" for i in range(n + 1)]
        res = run(exe, work, f"beam_{etype}_slope_free", beam_deck(etype, "cantilever", n, lines))
        tip = [r for r in res["displacements"] if int(r["node"]) == n + 1][0]
        w, th = float(tip[ucol]), float(tip[rcol])
        w_exact = -ALPHA * length ** 2 * (g0 / 2 + g1 / 6)
        th_exact = ALPHA * length * (g0 + g1 / 2) * (-1 if planar else 1)
        smax = max(abs(float(r["sxx"])) for r in res["fibre_stresses"])
        e1 = max(abs(w / w_exact - 1), abs(th / th_exact - 1))
        umax = serr = 0.0
        scale = E * ALPHA * (g0 + g1) * h / 2
        if etype in ("B33", "B23"):
            # Euler-Bernoulli only: the Timoshenko beam's shear V = -E I kappa0' deforms it
            res = run(exe, work, f"beam_{etype}_slope_clamped", beam_deck(etype, "clamped", n, lines))
            umax = max(abs(float(r[k])) for r in res["displacements"]
                       for k in ("u1", "u2", "u3", "ur1", "ur2", "ur3"))
            for r in res["fibre_stresses"]:
                xe = length * (int(r["element"]) - 2 + int(r["end"])) / n
                serr = max(serr, abs(float(r["sxx"]) + E * ALPHA * (g0 + g1 * xe / length) * float(r[coord])))
        clamped = (f"clamped: max displacement {umax:.1e}, fibre stress error {serr / scale:.1e}"
                   if etype in ("B33", "B23") else "clamped: see the one-element row")
        rows.append((etype, "gradient 10 to 40 along it", f"cantilever tip {ucol} {w:.6e} (exact {w_exact:.6e}); "
                     + clamped,
                     f"{e1:.1e}", f"{smax / (E * ALPHA * g0 * h):.1e}"))
        if e1 > 1e-12 or smax > 1e-12 * E * ALPHA * g0 * h or umax > 1e-15 or serr > 1e-12 * scale:
            print(f"FAIL: {etype} with a gradient varying along it: tip error {e1:.2e}, free stress {smax:.2e}, "
                  f"clamped displacement {umax:.2e}, fibre stress error {serr / scale:.2e}")
            ok = False
        else:
            print(f"ok: {etype}: a gradient varying along the beam (exact: tip error {e1:.1e})")
    # one Timoshenko B21 clamped at both ends, gradient 10 to 40: the fixed-end
    # shear of kappa0 = a + b x is E I b/(1 + phi), phi = 12 E I/(k G A L^2)
    # (k = 0.85, Abaqus's factor of a RECT section), the end moments balance it
    res = run(exe, work, "beam_B21_slope_one", beam_deck("B21", "clamped", 1, ["1, 20.0, 10.0", "2, 20.0, 40.0"]))
    with open(os.path.join(work, "beam_B21_slope_one.csv", "element_forces.csv"), newline="") as f:
        ef = list(csv.DictReader(f))
    inertia, area = b * h ** 3 / 12, b * h
    phi = 12 * E * inertia / (0.85 * E / (2 * (1 + NU)) * area * length ** 2)
    v_exact = E * inertia * ALPHA * 30.0 / length / (1 + phi)
    verr = max(abs(abs(float(r["vy"])) - v_exact) for r in ef) / v_exact
    mbal = abs(float(ef[0]["mz"]) + float(ef[1]["mz"]) - float(ef[0]["vy"]) * length) / (v_exact * length)
    rows.append(("B21", "one element clamped, gradient 10 to 40", f"end shear {abs(float(ef[0]['vy'])):.6e} "
                 f"(E I b/(1 + phi) = {v_exact:.6e})", f"{max(verr, mbal):.1e}", "-"))
    if verr > 1e-12 or mbal > 1e-12:
        print(f"FAIL: clamped B21 with a varying gradient: shear error {verr:.2e}, moment balance {mbal:.2e}")
        ok = False
    else:
        print(f"ok: clamped B21 with a varying gradient: fixed-end shear E I b/(1 + phi) to {verr:.1e}")
    # a temperature rising linearly from 0 to 40 along a clamped beam: every
    # element carries N = -E A alpha 20 (the mean over the beam; the element
    # means differ, the inner nodes move)
    lines = [f"{i + 1}, {20.0 + 40.0 * i / n!r}" for i in range(n + 1)]
    res = run(exe, work, "bar_linear", beam_deck("B33", "clamped", n, lines))
    worst = max(abs(float(r["sxx"]) + E * ALPHA * 20.0) for r in res["fibre_stresses"])
    rows.append(("B33", "clamped, T linear along it (0 to 40)", "σ = -E α 20 in every element",
                 f"{worst / (E * ALPHA * 20):.1e}", "-"))
    if worst > 1e-12 * E * ALPHA * 20:
        print(f"FAIL: clamped beam with T linear along it: stress error {worst:.2e}")
        ok = False
    else:
        print("ok: T linear along a clamped beam: every element carries -E alpha (the mean dT)")
    if table:
        print("\n| element | case | result | relative error | stress of the free beam / (E α g h) |\n|---|---|---|---|---|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
    return ok


# ------------------------------------------------------------ 4. CalculiX

def ccx_study(exe, work, table):
    here = os.path.dirname(os.path.abspath(__file__))
    ref = {}
    with open(os.path.join(here, "thermal_linear_cps8.dat.ref")) as f:
        for line in f:
            p = line.split()
            if len(p) == 4 and p[0].isdigit():
                ref[int(p[0])] = [float(x) for x in p[1:3]]
    os.makedirs(work, exist_ok=True)
    out = os.path.join(work, "thermal_linear_cps8.csv")
    r = subprocess.run([exe, "-q", os.path.join(here, "thermal_linear_cps8.inp"), "-o",
                        os.path.join(work, "thermal_linear_cps8.lst"), "--csv", out], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: thermal_linear_cps8.inp: exit {r.returncode}\n{r.stderr}")
        return False
    with open(os.path.join(out, "displacements.csv"), newline="") as f:
        ours = {int(row["node"]): [float(row["u1"]), float(row["u2"])] for row in csv.DictReader(f)}
    scale = max(abs(v) for u in ref.values() for v in u)
    worst = max(abs(ours[n][k] - ref[n][k]) for n in ref for k in range(2)) / scale
    if table:
        print("\n| node | ccx u1 | superjoin u1 | ccx u2 | superjoin u2 |\n|---|---|---|---|---|")
        for n in sorted(ref)[::3]:
            print(f"| {n} | {ref[n][0]:.6e} | {ours[n][0]:.6e} | {ref[n][1]:.6e} | {ours[n][1]:.6e} |")
        print(f"largest difference {worst:.2e} of the largest displacement")
    if worst > 2e-3:
        print(f"FAIL: thermal_linear_cps8 against ccx: difference {worst:.2e}")
        return False
    print(f"ok: thermal_linear_cps8 against ccx 2.20: largest difference {worst:.2e} of the largest displacement")
    return True


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    exe, work = argv[1], argv[2]
    table = "--table" in argv
    ok = linear_study(exe, work, table)
    ok = strip_study(exe, work, table) and ok
    ok = beam_study(exe, work, table) and ok
    if os.path.exists(os.path.join(os.path.dirname(os.path.abspath(__file__)), "thermal_linear_cps8.dat.ref")):
        ok = ccx_study(exe, work, table) and ok
    else:
        print("FAIL: thermal_linear_cps8.dat.ref missing")
        ok = False
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
