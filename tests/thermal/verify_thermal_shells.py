#!/usr/bin/env python3
"""Temperatures interpolated inside shells (S3, S4, S3R, S4R, S8R) against closed forms.

usage: verify_thermal_shells.py SUPERJOIN WORKDIR [--table]

What is compatible. A thermal strain alpha T (1, 1, 0) in the plane is
compatible when T is linear in x and y (exx,yy + eyy,xx = gxy,xy holds), so a
free flat plate with T = T0 + a x + b y is stress-free, its displacement the
integral u = alpha (T0 x + a (x^2 - y^2)/2 + b x y), v = alpha (T0 y + b (y^2 -
x^2)/2 + a x y). A thermal curvature alpha g (1, 1, 0) (kx = ky = alpha g,
kxy = 0) is compatible only when g is constant: w,xx = w,yy = -alpha g with
w,xy = 0 forces g,x = g,y = 0. So a linear gradient is tested where its answer
is closed-form, on a plate held at every node (no displacement): the moments
are m = -D (1 + nu) alpha g(x, y) at every integration point.
1. Free plate on meshes of 4 x 4, 8 x 8 and 16 x 16 parallelograms of [0,1]^2
   sheared and lifted (verify_thermal.quad_mesh; triangles: each cut along a
   diagonal), T = 20 + 60 x - 40 y, node 1 at the origin held in translation
   and in the rotations about x and y, the node farthest along x in y and z
   (so the exact field is compared plus the rigid rotation that support adds),
   the farthest along y in z:
   S8R: the quadratic field is in its space: stresses < 1e-10 E alpha a and
   displacements the exact ones to 1e-10 of the largest;
   S4, S4R: the drilling quadrilateral holds the field only where every edge
   keeps its bubble (superjoin_elements_drill_mask drops those at supported
   nodes), so the error is local and falls with h: rate >= 0.8 on the last
   halving of the largest stress;
   S3, S3R (CST): a constant strain per element, the stress error falls like h
   (rate >= 0.8).
   With --old BINARY (a superjoin built before this change, element mean) the
   table gets the mean's errors for comparison.
2. Clamped plate (every DOF held), 4 x 4, T = 20 + 60 x - 40 y and gradient
   g = 10 + 30 x + 20 y: the element results are those of the initial strain
   alone, sigma = -E/(1 - nu) alpha (T + g z) at z = -+t/2, checked to 1e-10
   where the element has no internal modes: the bending stresses (top minus
   bottom) of all five at their points and (averaged) nodes, the membrane
   stresses of S3/S3R (CST, one point) and S8R at their points, and for all
   five the resultants at the centroid (n = -E t alpha T/(1 - nu), m = -E t^3
   alpha g/(12 (1 - nu)); the incompatible modes' strains vanish there); a
   load combination 2 x the step has twice every point stress.
3. A free strip 10 x 1 (c = 0.5) with T = 100 (y/c)^2 (not compatible: it
   carries sigma_x = E alpha T0 (1/3 - y^2/c^2) away from the ends, Timoshenko
   & Goodier sec. 150), nodal stresses at the middle section, S8R and S4
   meshes halved three times: S8R's error below 2e-2 and falling at a rate
   >= 1.8 (its nodal stresses extrapolate the reduced 2 x 2 points), S4's at
   >= 0.8.
4. CalculiX: thermal_linear_s8r.inp (the free S8R plate of 1, 4 x 4,
   translations held at three nodes) run unchanged against
   thermal_linear_s8r.dat.ref written by ccx 2.20 from the same file (ccx
   expands the S8R into C3D20R bricks; the exact field is stress-free in 3D
   too): in-plane displacements to 1e-4 of the largest (measured 2e-5; ours
   match the exact field to 1e-12, ccx's differ from it by that much).
With --table the tables of doc/verification.md are printed.
"""
import csv
import math
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify_thermal import quad_mesh, quad4_mesh  # noqa: E402

E, NU, ALPHA, THICK = 2.0e11, 0.3, 1.2e-5, 0.02


def temp(x, y):
    return 20.0 + 60.0 * x - 40.0 * y


def grad(x, y):
    return 10.0 + 30.0 * x + 20.0 * y


def exact(x, y):
    t0, a, b = 20.0, 60.0, -40.0
    return (ALPHA * (t0 * x + a * x * x / 2 - a * y * y / 2 + b * x * y),
            ALPHA * (t0 * y + b * y * y / 2 - b * x * x / 2 + a * x * y))


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
    for table in ("displacements", "point_stresses", "nodal_stresses", "plate_results"):
        path = os.path.join(out, table + ".csv")
        if os.path.exists(path):
            with open(path, newline="") as f:
                res[table] = list(csv.DictReader(f))
    return res


def tri3_mesh(nx, ny):
    """3-node triangles: every parallelogram of quad4_mesh cut along a diagonal."""
    nodes, quads = quad4_mesh(nx, ny)
    elems = []
    for q in quads:
        elems += [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
    return nodes, elems


def mesh(etype, n):
    if etype == "S8R":
        return quad_mesh(n, n)
    if etype in ("S4", "S4R"):
        return quad4_mesh(n, n)
    return tri3_mesh(n, n)


def deck(etype, nodes, elems, supports, tfun, gfun=None, combination=False):
    lines = ["*HEADING", f"shell temperature {etype}", "*NODE, NSET=ALL"]
    lines += [f"{k + 1}, {x!r}, {y!r}, 0.0" for k, (x, y) in enumerate(nodes)]
    lines.append(f"*ELEMENT, TYPE={etype}, ELSET=P")
    lines += [f"{k + 1}, " + ", ".join(map(str, c)) for k, c in enumerate(elems)]
    lines += ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}",
              "*SHELL SECTION, ELSET=P, MATERIAL=M", f"{THICK}", "*BOUNDARY"] + supports
    lines += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE", "ALL, 0.0", "*STEP", "*STATIC", "*TEMPERATURE"]
    for k, (x, y) in enumerate(nodes):
        lines.append(f"{k + 1}, {tfun(k, x, y)!r}" + (f", {gfun(x, y)!r}" if gfun else ""))
    lines += ["*NODE FILE", "U, S", "*EL FILE", "S", "*END STEP"]
    if combination:   # 2 x the step, superposed (its temperatures too)
        lines += ["*LOAD COMBINATION, NAME=TWICE", "1, 2.0"]
    return "\n".join(lines) + "\n"


def free_supports(nodes):
    """Node 1 at the origin: translations and the rotations about x and y; the node farthest along
    x: y and z (it takes the in-plane rigid rotation); the farthest along y: z. Free drilling rotations:
    the elements' own (a drilling rotation held would fight the field's rotation alpha (a y - b x))."""
    far_x = max(range(len(nodes)), key=lambda k: nodes[k][0] - 0.01 * nodes[k][1])
    far_y = max(range(len(nodes)), key=lambda k: nodes[k][1] - 0.01 * nodes[k][0])
    return ["1, 1, 5", f"{far_x + 1}, 2, 3", f"{far_y + 1}, 3, 3"], far_x


def free_errors(nodes, res, far_x):
    """Largest stress / (E alpha a), displacement error / largest displacement; the exact field plus
    the rigid rotation w about node 1 that holds v at node far_x (w = -v(x1, y1)/x1)."""
    smax = max(abs(float(r[k])) for r in res["point_stresses"] for k in ("sxx", "syy", "sxy"))
    x1, y1 = nodes[far_x]
    # a rotation w moves (x, y) by (-w y, w x): v(x1, y1) + w x1 = 0
    w = -exact(x1, y1)[1] / x1
    worst, scale = 0.0, 0.0
    for r in res["displacements"]:
        x, y = nodes[int(r["node"]) - 1]
        ue, ve = exact(x, y)
        ue, ve = ue - w * y, ve + w * x
        worst = max(worst, abs(float(r["u1"]) - ue), abs(float(r["u2"]) - ve))
        scale = max(scale, abs(ue), abs(ve))
    return smax / (E * ALPHA * 60.0), worst / scale


G = 1 / math.sqrt(3.0)
CORNER = [(-1, -1), (1, -1), (1, 1), (-1, 1)]


def point_value(etype, corners, values, k):
    """values (at the corners) interpolated to stress point k of an element (linear fields)."""
    if etype in ("S3", "S3R"):
        return sum(values) / 3
    xi, eta = G * CORNER[k][0], G * CORNER[k][1]
    return sum(v * (1 + xi * c[0]) * (1 + eta * c[1]) / 4 for v, c in zip(values, CORNER))


def clamped_study(exe, work, rows):
    """Every DOF held: stresses = -E/(1 - nu) alpha (T + g z), z = -+t/2, where the element has no
    internal modes (bending parts of all five, membrane of S3/S3R and S8R)."""
    ok = True
    fac = -E / (1 - NU) * ALPHA
    for etype in ("S8R", "S4", "S4R", "S3", "S3R"):
        nodes, elems = mesh(etype, 4)
        res = run(exe, work, f"clamped_{etype}", deck(etype, nodes, elems, ["ALL, 1, 6"],
                                                         lambda k, x, y: temp(x, y), grad, combination=True))
        membrane_exact = etype in ("S8R", "S3", "S3R")
        sig, twice = {}, {}
        for r in res["point_stresses"]:
            (sig if r["step"] == "1" else twice)[(int(r["element"]), int(r["point"]), r["surface"])] = \
                [float(r[c]) for c in ("sxx", "syy", "sxy")]
        # the combination 2 x the step: twice every stress (its temperatures superposed too)
        comb = max(abs(twice[k][i] - 2 * v[i]) for k, v in sig.items() for i in range(3)) / \
            max(abs(v[i]) for v in sig.values() for i in range(3))
        bend = memb = 0.0
        for (e, k, surf), v in sig.items():
            if surf != "top":
                continue
            bot = sig[(e, k, "bottom")]
            corners = [nodes[i - 1] for i in elems[e - 1][:4 if etype not in ("S3", "S3R") else 3]]
            tp = point_value(etype, corners, [temp(*c) for c in corners], k - 1)
            gp = point_value(etype, corners, [grad(*c) for c in corners], k - 1)
            # bending: (top - bottom)/2 = fac g t/2 (1, 1, 0); membrane: (top + bottom)/2 = fac T (1, 1, 0)
            b = [(v[i] - bot[i]) / 2 for i in range(3)]
            m = [(v[i] + bot[i]) / 2 for i in range(3)]
            bend = max(bend, abs(b[0] - fac * gp * THICK / 2), abs(b[1] - fac * gp * THICK / 2), abs(b[2]))
            if membrane_exact:
                memb = max(memb, abs(m[0] - fac * tp), abs(m[1] - fac * tp), abs(m[2]))
        # nodal stresses (extrapolated, averaged): the bending part at the nodes
        nsig = {}
        for r in res["nodal_stresses"]:
            if r["step"] != "1":
                continue
            nsig[(int(r["node"]), r["surface"])] = [float(r[c]) for c in ("sxx", "syy", "sxy")]
        bend_n = 0.0
        for (nd, surf), v in nsig.items():
            if surf != "top":
                continue
            bot = nsig[(nd, "bottom")]
            gn = grad(*nodes[nd - 1])
            bend_n = max(bend_n, abs((v[0] - bot[0]) / 2 - fac * gn * THICK / 2), abs((v[2] - bot[2]) / 2))
        # centroid resultants: n = fac t T, m = fac t^3/12 g at the centre (the incompatible modes'
        # strains vanish at xi = eta = 0, so every membrane is exact there)
        res_err = 0.0
        for r in res["plate_results"]:
            if r["step"] != "1":
                continue
            e = int(r["element"])
            corners = [nodes[i - 1] for i in elems[e - 1][:4 if etype not in ("S3", "S3R") else 3]]
            tc = sum(temp(*c) for c in corners) / len(corners)
            gc = sum(grad(*c) for c in corners) / len(corners)
            res_err = max(res_err, abs(float(r["nx"]) - fac * THICK * tc) / (abs(fac) * THICK * 80),
                          abs(float(r["ny"]) - fac * THICK * tc) / (abs(fac) * THICK * 80),
                          abs(float(r["mx"]) - fac * THICK ** 3 / 12 * gc) / (abs(fac) * THICK ** 3 / 12 * 40),
                          abs(float(r["my"]) - fac * THICK ** 3 / 12 * gc) / (abs(fac) * THICK ** 3 / 12 * 40),
                          abs(float(r["nxy"])) / (abs(fac) * THICK * 80),
                          abs(float(r["mxy"])) / (abs(fac) * THICK ** 3 / 12 * 40))
        scale_b = abs(fac) * 40.0 * THICK / 2
        scale_m = abs(fac) * 80.0
        err = max(bend / scale_b, bend_n / scale_b, memb / scale_m, res_err, comb)
        what = "resultants at the centroid, bending stresses at points and nodes" + \
            (", membrane at points" if membrane_exact else "") + ", the combination 2 x the step"
        rows.append((etype, "clamped, T and gradient linear", what, f"{err:.1e}"))
        if err > 1e-10:
            print(f"FAIL: clamped {etype}: bending {bend / scale_b:.2e} (nodes {bend_n / scale_b:.2e}), "
                  f"membrane {memb / scale_m:.2e}, resultants {res_err:.2e}, combination {comb:.2e}")
            ok = False
        else:
            print(f"ok: clamped {etype}: sigma = -E/(1 - nu) alpha (T + g z) at its points ({what}): {err:.1e}")
    return ok


def ccx_study(exe, work, rows):
    """thermal_linear_s8r.inp (the free S8R plate of 1 on a 4 x 4 mesh, translations held at three
    nodes) run unchanged against thermal_linear_s8r.dat.ref of ccx 2.20 (which expands the S8R into
    C3D20R bricks): in-plane displacements to 1e-4 of the largest."""
    here = os.path.dirname(os.path.abspath(__file__))
    ref = {}
    with open(os.path.join(here, "thermal_linear_s8r.dat.ref")) as f:
        for line in f:
            p = line.split()
            if len(p) == 4 and p[0].isdigit():
                ref[int(p[0])] = [float(x) for x in p[1:3]]
    out = os.path.join(work, "thermal_linear_s8r.csv")
    os.makedirs(work, exist_ok=True)
    r = subprocess.run([exe, "-q", os.path.join(here, "thermal_linear_s8r.inp"), "-o",
                        os.path.join(work, "thermal_linear_s8r.lst"), "--csv", out], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: thermal_linear_s8r.inp: exit {r.returncode}\n{r.stderr}")
        return False
    with open(os.path.join(out, "displacements.csv"), newline="") as f:
        ours = {int(row["node"]): [float(row["u1"]), float(row["u2"])] for row in csv.DictReader(f)}
    scale = max(abs(v) for u in ref.values() for v in u)
    worst = max(abs(ours[n][k] - ref[n][k]) for n in ref for k in range(2)) / scale
    rows.append(("S8R", "free, T linear, 4 x 4, against ccx 2.20", "in-plane displacements", f"{worst:.1e}"))
    if worst > 1e-4:
        print(f"FAIL: thermal_linear_s8r against ccx: difference {worst:.2e}")
        return False
    print(f"ok: thermal_linear_s8r against ccx 2.20: in-plane displacements to {worst:.1e} of the largest")
    return True


def strip_study(exe, work, rows, old=None):
    """A free strip 10 x 1 (c = 0.5) with T = 100 (y/c)^2: away from the ends sigma_x = E alpha T0
    (1/3 - y^2/c^2) (Timoshenko & Goodier, sec. 150), nodal stresses at the middle section at y = 0
    and y = c; S8R and S4 meshes halved three times: the error falls (S8R: rate >= 1.8 on the last
    halving and below 2e-2 on the finest, its nodal values being the bilinear extrapolation of its
    reduced 2 x 2 points; S4: rate >= 0.8). With old (a superjoin that took the element mean) its
    errors are printed beside."""
    c, half, t0 = 0.5, 5.0, 100.0
    ok = True
    for etype in ("S8R", "S4"):
        errs = []
        for ny in (1, 2, 4, 8):
            nx = 10 * ny
            nodes, ids, elems = [], {}, []
            mx, my = 2 * nx, 2 * ny
            for i in range(mx + 1):
                for j in range(my + 1):
                    if etype == "S8R" and i % 2 == 1 and j % 2 == 1:
                        continue
                    nodes.append((-half + 2 * half * i / mx, -c + 2 * c * j / my))
                    ids[(i, j)] = len(nodes)
            if etype == "S8R":
                for i in range(nx):
                    for j in range(ny):
                        i0, j0 = 2 * i, 2 * j
                        elems.append([ids[(i0, j0)], ids[(i0 + 2, j0)], ids[(i0 + 2, j0 + 2)], ids[(i0, j0 + 2)],
                                      ids[(i0 + 1, j0)], ids[(i0 + 2, j0 + 1)], ids[(i0 + 1, j0 + 2)],
                                      ids[(i0, j0 + 1)]])
            else:
                for i in range(mx):
                    for j in range(my):
                        elems.append([ids[(i, j)], ids[(i + 1, j)], ids[(i + 1, j + 1)], ids[(i, j + 1)]])
            mid, top = ids[(mx // 2, my // 2)], ids[(mx // 2, my)]
            sup = [f"{mid}, 1, 5", f"{ids[(mx // 2, 0)]}, 1, 1", f"{ids[(mx // 2, 0)]}, 3, 3", f"{ids[(0, 0)]}, 3, 3"]
            res = run(exe, work, f"strip_{etype}_{ny}",
                      deck(etype, nodes, elems, sup, lambda k, x, y: t0 * (y / c) ** 2))
            sx = {int(r["node"]): float(r["sxx"]) for r in res["nodal_stresses"] if r["surface"] == "top"}
            exact_mid, exact_top = E * ALPHA * t0 / 3, -2 * E * ALPHA * t0 / 3
            err = max(abs(sx[mid] - exact_mid), abs(sx[top] - exact_top)) / abs(exact_top)
            errs.append(err)
            what = "σx(0, 0), σx(0, c)"
            if old:
                res = run(old, work + "/old", f"strip_{etype}_{ny}",
                          deck(etype, nodes, elems, sup, lambda k, x, y: t0 * (y / c) ** 2))
                so = {int(r["node"]): float(r["sxx"]) for r in res["nodal_stresses"] if r["surface"] == "top"}
                what += f" (element mean: {max(abs(so[mid] - exact_mid), abs(so[top] - exact_top)) / abs(exact_top):.1e})"
            rows.append((etype, f"strip, T quadratic, {nx} x {ny}", what, f"{err:.1e}"))
        rate = math.log2(errs[-2] / errs[-1])
        good = rate >= (1.8 if etype == "S8R" else 0.8) and (etype != "S8R" or errs[-1] < 2e-2)
        if good:
            print(f"ok: strip with quadratic T ({etype}): errors {', '.join(f'{e:.1e}' for e in errs)}, "
                  f"last rate {rate:.2f}")
        else:
            print(f"FAIL: strip with quadratic T ({etype}): errors {errs}, last rate {rate:.2f}")
            ok = False
    return ok


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, work, table = argv[1], argv[2], "--table" in argv
    old = argv[argv.index("--old") + 1] if "--old" in argv else None
    ok, rows = True, []
    for etype in ("S8R", "S4", "S4R", "S3", "S3R"):
        errs = []
        for n in (4, 8, 16):
            nodes, elems = mesh(etype, n)
            sup, far_x = free_supports(nodes)
            text = deck(etype, nodes, elems, sup, lambda k, x, y: temp(x, y))
            s_, d_ = free_errors(nodes, run(exe, work, f"free_{etype}_{n}", text), far_x)
            mean = ""
            if old:   # the element mean (superjoin before this change)
                so, do = free_errors(nodes, run(old, work + "/old", f"free_{etype}_{n}", text), far_x)
                mean = f"{so:.1e} / {do:.1e}"
            errs.append((n, s_, d_, mean))
        (_, s1, d1, _), (_, s2, d2, _) = errs[-2], errs[-1]
        rate = math.log2(s1 / s2) if s2 > 0 else float("inf")
        if etype == "S8R":
            good = all(e[1] < 1e-10 and e[2] < 1e-10 for e in errs)
            claim = "stress-free, displacement exact (1e-10)"
        else:
            good = rate >= 0.8 and d2 < d1
            claim = f"stress error falls at rate {rate:.2f} (>= 0.8)"
        for n, s_, d_, mean in errs:
            rows.append((etype, f"free, T linear, {n} x {n}", f"{s_:.1e}", f"{d_:.1e}", mean or "-"))
        if good:
            print(f"ok: free {etype} plate, T linear: {claim}; finest: stress {s2:.1e}, displacement {d2:.1e}")
        else:
            print(f"FAIL: free {etype} plate, T linear: {[(e[0], e[1], e[2]) for e in errs]}")
            ok = False
    crows = []
    ok = clamped_study(exe, work, crows) and ok
    ok = ccx_study(exe, work, crows) and ok
    ok = strip_study(exe, work, crows, old) and ok
    if table:
        print("\n| element | case | max stress / (E α a) | displacement error / max | element mean (before): stress / displacement |")
        print("|---|---|---|---|---|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
        print("\n| element | case | checked | max relative error |\n|---|---|---|---|")
        for r in crows:
            print("| " + " | ".join(r) + " |")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
