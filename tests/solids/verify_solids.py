#!/usr/bin/env python3
"""3D solid element verification through the whole program: generates decks,
solves them with superjoin, compares with closed forms (and CalculiX if `ccx`
is on PATH).

usage: verify_solids.py SUPERJOIN WORKDIR
Exit status 1 if any check fails.

Cases
- patch tests, every type (C3D8, C3D20, C3D20R, C3D4, C3D10, C3D8I): a 2 x 2 x 2 block
  (tetrahedra: each cell split into six) on [0, 2] x [0, 1.5] x [0, 1] whose
  interior nodes are moved by a smooth non-affine map (curved interior edges
  for the quadratic types); every boundary node prescribed by a linear field
  u = a + G x (all six strains and a rotation), the interior free. The interior
  displacements must be exact, and every boundary node's reaction must equal
  the consistent nodal force of the traction sigma.n of the constant stress
  on the faces around it (to 1e-10 of the largest), and the strain energy
  (*EL FILE ENER) sigma:eps V / 2;
- self weight (*DLOAD GRAV), quadratic types on an undistorted block: the
  exact elasticity solution of a prism under its own weight is quadratic
  (sigma_zz = rho g (z - H)), prescribed on the boundary; the interior must be
  exact (consistent body force);
- C3D8I in bending, one element through the thickness: pure bending exact,
  end shear near Timoshenko (C3D8 beside it);
- a C3D20R cantilever (10 x 1 x 1, nu = 0, clamped end, end shear as a uniform
  traction) against Timoshenko's tip deflection P L^3 / 3EI + P L / (k G A),
  k = 5/6, on refined meshes;
- two C3D8 blocks in two substructures joined by *CONTACT springs on DOFs 1-3
  (plain and condensed): tip displacement, joint opening and reactions exact;
- pressure on faces (*DLOAD P1..P6, *SURFACE S1..S6 with *DSLOAD): the
  hydrostatic state of the distorted block on symmetry supports, exact;
- VTK cells of every type; refusals of P and a *TEMPERATURE gradient
  (third field) on solids (their thermal loads: tests/decks/thermal_solids.deck);
- CalculiX (if installed): the patch block of every type but C3D8I with a
  load and face pressures instead of the interior prescription, `ccx -i`:
  displacements, S and E at the integration points (.dat), nodal S (.frd).
"""
import csv
import itertools
import math
import os
import re
import shutil
import subprocess
import sys

failures = []
TYPES = ("C3D8", "C3D20", "C3D20R", "C3D4", "C3D10", "C3D8I", "C3D6", "C3D15")
QUAD = {"C3D20", "C3D20R", "C3D10", "C3D15"}
WEDGES = {"C3D6", "C3D15"}
HEX_CORNERS = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
WEDGE_EDGES = [(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


def fmt(v):
    return repr(float(v))


def det3(a, b, c):
    return (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
            + a[2] * (b[0] * c[1] - b[1] * c[0]))


def sub(p, q):
    return tuple(a - b for a, b in zip(p, q))


class Mesh:
    """A structured block of n[0] x n[1] x n[2] cells on a half-index grid
    (even indices: cell corners; odd: mid-side points)."""

    def __init__(self, n, size, etype, distort, curved=False):
        self.n, self.size, self.etype = n, size, etype
        self.distort, self.curved = distort, curved
        self.elems = []
        used = set()
        for k in range(n[2]):
            for j in range(n[1]):
                for i in range(n[0]):
                    base = (2 * i, 2 * j, 2 * k)
                    for el in self.cell(base):
                        used.update(el)
                        self.elems.append(tuple(self.nid(p) for p in el))
        self.nodes = {self.nid(p): self.point(p) for p in used}
        self.index = {self.nid(p): p for p in used}

    def cell(self, base):
        add = lambda p: tuple(b + q for b, q in zip(base, p))
        corners = [add(c) for c in HEX_CORNERS]
        if self.etype in ("C3D8", "C3D8I", "C3D8R", "C3D20", "C3D20R"):
            el = corners
            if self.etype not in ("C3D8", "C3D8I", "C3D8R"):
                el = el + [mid(corners[a], corners[b]) for a, b in HEX_EDGES]
            return [el]
        out = []
        if self.etype in WEDGES:                              # two prisms, split along the x-y diagonal
            for tri in ((0, 1, 2), (0, 2, 3)):
                v = [corners[c] for c in tri] + [corners[c + 4] for c in tri]
                if self.etype == "C3D15":
                    v = v + [mid(v[a], v[b]) for a, b in WEDGE_EDGES]
                out.append(v)
            return out
        for perm in itertools.permutations(range(3)):        # Kuhn's six tetrahedra
            v = [base]
            for ax in perm:
                p = list(v[-1])
                p[ax] += 2
                v.append(tuple(p))
            if det3(sub(v[1], v[0]), sub(v[2], v[0]), sub(v[3], v[0])) < 0:
                v[1], v[2] = v[2], v[1]
            if self.etype == "C3D10":
                v = v + [mid(v[a], v[b]) for a, b in TET_EDGES]
            out.append(v)
        return out

    def nid(self, p):
        return 1 + p[0] + (2 * self.n[0] + 1) * (p[1] + (2 * self.n[1] + 1) * p[2])

    def point(self, p):
        odd = [q % 2 for q in p]
        if any(odd) and not self.curved:      # a mid-side node: the middle of a straight edge
            a = self.map(tuple(q - o for q, o in zip(p, odd)))
            b = self.map(tuple(q + o for q, o in zip(p, odd)))
            return tuple((u + v) / 2 for u, v in zip(a, b))
        return self.map(p)

    def map(self, p):
        s = [p[d] / (2 * self.n[d]) for d in range(3)]
        x = [self.size[d] * s[d] for d in range(3)]
        if self.distort:
            bump = math.sin(math.pi * s[0]) * math.sin(math.pi * s[1]) * math.sin(math.pi * s[2])
            x[0] += 0.18 * self.size[0] * bump * (1.0 + 0.5 * s[1])
            x[1] += -0.12 * self.size[1] * bump * (1.0 + 0.7 * s[2])
            x[2] += 0.15 * self.size[2] * bump * (1.0 - 0.4 * s[0])
        return tuple(x)

    def boundary(self, nid):
        p = self.index[nid]
        return any(p[d] in (0, 2 * self.n[d]) for d in range(3))

    def face_weights(self):
        """{node: [(outward normal, area share)]}: the consistent shares of a
        unit uniform traction on the block's faces (flat, regular)."""
        w = {}
        for ax in range(3):
            a, b = [d for d in range(3) if d != ax]
            area = (self.size[a] / self.n[a]) * (self.size[b] / self.n[b])
            for side in (0, 2 * self.n[ax]):
                normal = [0.0, 0.0, 0.0]
                normal[ax] = 1.0 if side else -1.0
                for i in range(self.n[a]):
                    for j in range(self.n[b]):
                        for p, share in self.face_cell(ax, side, a, b, 2 * i, 2 * j, area):
                            w.setdefault(self.nid(p), []).append((tuple(normal), share))
        return w

    def face_cell(self, ax, side, a, b, i, j, area):
        def pt(di, dj):
            p = [0, 0, 0]
            p[ax], p[a], p[b] = side, i + di, j + dj
            return tuple(p)
        kind = self.etype
        if kind in WEDGES:      # quadrilaterals on x, y = const, triangles (as the tetrahedra's) on z = const
            kind = {("C3D6", True): "C3D4", ("C3D6", False): "C3D8",
                    ("C3D15", True): "C3D10", ("C3D15", False): "C3D20"}[(kind, ax == 2)]
        if kind in ("C3D8", "C3D8I", "C3D8R"):
            return [(pt(di, dj), area / 4) for di in (0, 2) for dj in (0, 2)]
        if kind in ("C3D20", "C3D20R"):
            return ([(pt(di, dj), -area / 12) for di in (0, 2) for dj in (0, 2)]
                    + [(pt(di, dj), area / 3) for di, dj in ((1, 0), (1, 2), (0, 1), (2, 1))])
        out = []
        for tri in (((0, 0), (2, 0), (2, 2)), ((0, 0), (0, 2), (2, 2))):   # Kuhn's diagonal
            if kind == "C3D4":
                out += [(pt(*c), area / 6) for c in tri]
            else:
                for m in range(3):
                    c1, c2 = tri[m], tri[(m + 1) % 3]
                    out.append((pt((c1[0] + c2[0]) // 2, (c1[1] + c2[1]) // 2), area / 6))
        return out


def mid(p, q):
    return tuple((a + b) // 2 for a, b in zip(p, q))


def deck(mesh, e, nu, boundary, cloads, extra="", density=None):
    out = ["*HEADING", f"solid verification {mesh.etype}", "*MATERIAL, NAME=MAT", "*ELASTIC",
           f" {fmt(e)}, {fmt(nu)}"]
    if density is not None:
        out += ["*DENSITY", f" {fmt(density)}"]
    out.append("*NODE")
    out += [f" {n}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}" for n, x in sorted(mesh.nodes.items())]
    out.append(f"*ELEMENT, TYPE={mesh.etype}, ELSET=ALL")
    for k, el in enumerate(mesh.elems, 1):
        fields = [str(k)] + [str(v) for v in el]
        for c in range(0, len(fields), 16):                 # Abaqus: at most 16 fields per line
            tail = "," if c + 16 < len(fields) else ""
            out.append(" " + ", ".join(fields[c:c + 16]) + tail)
    out += ["*SOLID SECTION, ELSET=ALL, MATERIAL=MAT", "*BOUNDARY"]
    out += [f" {n}, {d}, {d}, {fmt(v)}" for n, d, v in boundary]
    out += ["*STEP", "*STATIC"]
    if cloads:
        out.append("*CLOAD")
        out += [f" {n}, {d}, {fmt(v)}" for n, d, v in cloads if v != 0.0]
    out.append(extra)
    out += ["*NODE PRINT, NSET=NALL", "U", "*END STEP"]
    text = "\n".join(out) + "\n"
    # NALL for CalculiX's *NODE PRINT
    nall = "*NSET, NSET=NALL, GENERATE\n 1, " + str(max(mesh.nodes)) + ", 1\n"
    return text.replace("*ELEMENT,", nall + "*ELEMENT,", 1)


def solve(exe, work, name, text):
    """Run superjoin; ({node: (u1, u2, u3)}, {(node, dof): reaction})."""
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, name + "_csv")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, name + ".lst"), path],
                       capture_output=True, text=True)
    if r.returncode != 0:
        check(False, f"{name}: exit {r.returncode}: {r.stderr.strip()[:300]}")
        return None, None
    disp, reac = {}, {}
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            disp[int(row["node"])] = (float(row["u1"]), float(row["u2"]), float(row["u3"]))
    with open(os.path.join(out, "reactions.csv")) as f:
        for row in csv.DictReader(f):
            key = (int(row["node"]), int(row["dof"]))
            reac[key] = reac.get(key, 0.0) + float(row["force"])
    return disp, reac


def elasticity(e, nu, eps):
    """sigma (3 x 3) of the strain tensor eps (3 x 3), isotropic."""
    lam = e * nu / ((1 + nu) * (1 - 2 * nu))
    g = e / (2 * (1 + nu))
    tr = eps[0][0] + eps[1][1] + eps[2][2]
    return [[lam * tr * (i == j) + 2 * g * eps[i][j] for j in range(3)] for i in range(3)]


def patch_tests(exe, work):
    print("\n## Patch tests (boundary displacements prescribed, interior free, distorted interior)\n")
    print("Interior corner nodes moved, mid-side nodes at the middle of straight edges; the quadratic")
    print("types also with curved interior edges (measured only: their rules are not exact there).\n")
    print("| element | elements | nodes | interior error / max u | reaction error / max reaction "
          "| stress error / max stress (points and nodes) |")
    print("|---|---|---|---|---|---|")
    e, nu = 2.0e5, 0.3
    a0 = (1e-3, -2e-3, 5e-4)
    g = ((1.0e-3, 4.0e-4, -3.0e-4), (-2.0e-4, -5.0e-4, 6.0e-4), (7.0e-4, 1.0e-4, 8.0e-4))
    eps = [[(g[i][j] + g[j][i]) / 2 for j in range(3)] for i in range(3)]
    sig = elasticity(e, nu, eps)
    field = lambda x: tuple(a0[i] + sum(g[i][j] * x[j] for j in range(3)) for i in range(3))
    for et, curved in [(t, False) for t in TYPES] + [(t, True) for t in sorted(QUAD)]:
        mesh = Mesh((2, 2, 2), (2.0, 1.5, 1.0), et, True, curved)
        bnd = [(n, d + 1, field(x)[d]) for n, x in sorted(mesh.nodes.items()) if mesh.boundary(n) for d in range(3)]
        name = "patch_" + et + ("_curved" if curved else "")
        disp, reac = solve(exe, work, name, deck(mesh, e, nu, bnd, [], extra="*EL FILE\nENER, S"))
        if disp is None:
            continue
        serr = stress_error(os.path.join(work, name + "_csv"), sig)
        with open(os.path.join(work, name + "_csv", "energies.csv")) as f:
            energy = sum(float(row["energy"]) for row in csv.DictReader(f) if row["kind"] == "element")
        exact_energy = 0.5 * sum(sig[i][j] * eps[i][j] for i in range(3) for j in range(3)) * 3.0
        umax = max(abs(v) for x in mesh.nodes.values() for v in field(x))
        err = max((abs(disp[n][d] - field(x)[d]) for n, x in mesh.nodes.items() if not mesh.boundary(n)
                   for d in range(3)), default=0.0)
        expect = {}
        for n, shares in mesh.face_weights().items():
            for normal, s in shares:
                for d in range(3):
                    expect[(n, d + 1)] = expect.get((n, d + 1), 0.0) + s * sum(sig[d][k] * normal[k] for k in range(3))
        rmax = max(abs(v) for v in expect.values())
        rerr = max(abs(reac.get(k, 0.0) - v) for k, v in expect.items())
        label = et + (", curved interior edges" if curved else "")
        print(f"| {label} | {len(mesh.elems)} | {len(mesh.nodes)} | {err / umax:.1e} | {rerr / rmax:.1e} "
              f"| {serr:.1e} |")
        if curved:    # quadrature is not exact on curved elements: measured, not required
            continue
        check(err <= 1e-10 * umax, f"{et} patch: interior displacements exact ({err / umax:.1e})")
        check(abs(energy - exact_energy) <= 1e-10 * exact_energy,
              f"{et} patch: strain energy = sigma:eps V / 2 ({abs(energy / exact_energy - 1):.1e})")
        check(rerr <= 1e-10 * rmax, f"{et} patch: reactions = consistent tractions of the constant stress "
                                    f"({rerr / rmax:.1e})")
        check(serr <= 1e-10, f"{et} patch: stresses at every integration point and node = the constant stress "
                             f"({serr:.1e})")


def stress_error(csvdir, sig):
    """Largest difference / largest stress between the rows of point_stresses.csv
    and nodal_stresses.csv and the constant stress tensor sig (1 if a table is
    missing or empty)."""
    want = [sig[0][0], sig[1][1], sig[2][2], sig[0][1], sig[0][2], sig[1][2]]
    smax = max(abs(v) for v in want)
    worst, rows = 0.0, 0
    for table in ("point_stresses.csv", "nodal_stresses.csv"):
        path = os.path.join(csvdir, table)
        if not os.path.exists(path):
            return 1.0
        with open(path) as f:
            for row in csv.DictReader(f):
                rows += 1
                got = [float(row[k]) for k in ("sxx", "syy", "szz", "sxy", "sxz", "syz")]
                worst = max(worst, max(abs(a - b) for a, b in zip(got, want)) / smax)
    return worst if rows else 1.0


HEX_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]
TET_FACES = [(0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0)]
WEDGE_FACES = [(0, 1, 2), (3, 5, 4), (0, 3, 4, 1), (1, 4, 5, 2), (2, 5, 3, 0)]


def outer_faces(mesh):
    """[(element number, face number, axis, side)] of the faces of the elements on the block's
    faces x, y, z = size (side 1) or 0 (side 0), Abaqus's face numbering."""
    faces = HEX_FACES if mesh.etype.startswith("C3D8") or mesh.etype.startswith("C3D20") else TET_FACES
    if mesh.etype in WEDGES:
        faces = WEDGE_FACES
    out = []
    for k, el in enumerate(mesh.elems, 1):
        for f, corners in enumerate(faces, 1):
            pts = [mesh.index[el[c]] for c in corners]
            for ax in range(3):
                for side, value in ((0, 0), (1, 2 * mesh.n[ax])):
                    if all(p[ax] == value for p in pts):
                        out.append((k, f, ax, side))
    return out


def pressure_tests(exe, work):
    print("\n## Pressure on faces (*DLOAD Pk; C3D20R also *SURFACE S1..S6 + *DSLOAD)\n")
    print("The distorted block (flat outer faces) on symmetry supports (u1 = 0 on x = 0, u2 on y = 0,")
    print("u3 on z = 0) with a pressure p on its three other faces, named per element face: the")
    print("hydrostatic state sigma = -p I, u = -p (1 - 2 nu) x / E, exact at every node; the reactions")
    print("on each support face sum to p times its area.\n")
    print("| element | faces loaded | displacement error / max u | stress error / p | resultant error |")
    print("|---|---|---|---|---|")
    e, nu, p = 2.0e5, 0.3, 7.0
    size = (2.0, 1.5, 1.0)
    for et in TYPES:
        mesh = Mesh((2, 2, 2), size, et, True)
        bnd = [(n, d + 1, 0.0) for n, x in sorted(mesh.nodes.items()) for d in range(3)
               if mesh.index[n][d] == 0]
        loaded = [(k, f) for k, f, ax, side in outer_faces(mesh) if side == 1]
        if et == "C3D20R":      # the same faces through a surface
            card = ("*DSLOAD\n LOADED, P, " + fmt(p))
            surface = "*SURFACE, NAME=LOADED, TYPE=ELEMENT\n" + "".join(f" {k}, S{f}\n" for k, f in loaded)
        else:
            card = "*DLOAD\n" + "\n".join(f" {k}, P{f}, {fmt(p)}" for k, f in loaded)
            surface = ""
        text = deck(mesh, e, nu, bnd, [], extra=card + "\n*EL FILE\nS")
        if surface:
            text = text.replace("*STEP", surface + "*STEP", 1)
        name = "pressure_" + et
        disp, reac = solve(exe, work, name, text)
        if disp is None:
            continue
        c = -p * (1 - 2 * nu) / e
        umax = abs(c) * max(size)
        err = max(abs(disp[n][d] - c * x[d]) for n, x in mesh.nodes.items() for d in range(3)) / umax
        serr = stress_error(os.path.join(work, name + "_csv"), [[-p if i == j else 0.0 for j in range(3)]
                                                                 for i in range(3)])
        area = [size[1] * size[2], size[0] * size[2], size[0] * size[1]]
        rerr = max(abs(sum(v for (n, dof), v in reac.items() if dof == d + 1) - p * area[d]) / (p * area[d])
                   for d in range(3))
        print(f"| {et} | {len(loaded)} | {err:.1e} | {serr:.1e} | {rerr:.1e} |")
        check(err <= 1e-10 and serr <= 1e-10 and rerr <= 1e-10,
              f"{et} pressure on faces: hydrostatic state exact ({err:.1e}, {serr:.1e}, {rerr:.1e})")


def gravity_tests(exe, work):
    print("\n## Self weight (exact quadratic field prescribed on the boundary, interior free)\n")
    e, nu, rho, grav = 2.0e5, 0.3, 8.0e-3, 9.81
    size = (2.0, 1.5, 1.0)
    h = size[2]
    c = rho * grav / e

    def field(x):
        return (-nu * c * (x[2] - h) * x[0], -nu * c * (x[2] - h) * x[1],
                c * (x[2] ** 2 / 2 - h * x[2]) + nu * c / 2 * (x[0] ** 2 + x[1] ** 2))
    for et in ("C3D20", "C3D20R", "C3D10", "C3D15"):
        mesh = Mesh((2, 2, 2), size, et, False)
        bnd = [(n, d + 1, field(x)[d]) for n, x in sorted(mesh.nodes.items()) if mesh.boundary(n) for d in range(3)]
        text = deck(mesh, e, nu, bnd, [], extra=f"*DLOAD\n ALL, GRAV, {fmt(grav)}, 0., 0., -1.", density=rho)
        disp, reac = solve(exe, work, "grav_" + et, text)
        if disp is None:
            continue
        umax = max(abs(v) for x in mesh.nodes.values() for v in field(x))
        err = max(abs(disp[n][d] - field(x)[d]) for n, x in mesh.nodes.items() if not mesh.boundary(n)
                  for d in range(3))
        weight = rho * grav * size[0] * size[1] * size[2]
        rz = sum(v for (n, d), v in reac.items() if d == 3)
        check(err <= 1e-10 * umax, f"{et} self weight: interior exact ({err / umax:.1e}); "
                                   f"reactions {rz:.12g} = weight {weight:.12g}")
        check(abs(rz - weight) <= 1e-10 * weight, f"{et} self weight: vertical reactions sum to the weight")


def cantilever(exe, work):
    print("\n## C3D20R cantilever (L = 10, 1 x 1, E = 1e5, nu = 0, end shear P = 1 as uniform traction)\n")
    length, e, p = 10.0, 1.0e5, 1.0
    inertia, area, g = 1.0 / 12, 1.0, e / 2
    exact = p * length ** 3 / (3 * e * inertia) + p * length / (5.0 / 6.0 * g * area)
    print(f"Timoshenko: {exact:.6e} (bending {p * length ** 3 / (3 * e * inertia):.6e})\n")
    print("Bending stress sxx of the top fibre (y = h, nodal stresses averaged over the elements,")
    print("mean over the width) against -P (L - x) (h/2) / I: at mid-span (-30) and at the root (-60, where the")
    print("clamp, which also holds the section's warping, disturbs it).\n")
    print("| mesh (length x height x width) | tip deflection | / Timoshenko | sxx mid-span / beam | "
          "sxx root / beam |")
    print("|---|---|---|---|---|")
    ratios, mids = [], []
    for n in ((5, 2, 2), (10, 2, 2), (20, 2, 2), (20, 4, 4)):
        mesh = Mesh(n, (length, 1.0, 1.0), "C3D20R", False)
        bnd = [(nd, d, 0.0) for nd, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
        loads = {}
        for nd, shares in mesh.face_weights().items():
            for normal, s in shares:
                if normal[0] == 1.0:
                    loads[nd] = loads.get(nd, 0.0) + s * p / area
        cl = [(nd, 2, v) for nd, v in sorted(loads.items())]
        name = "cantilever_%d_%d_%d" % n
        disp, _ = solve(exe, work, name, deck(mesh, e, 0.0, bnd, cl, extra="*EL FILE\nS"))
        if disp is None:
            continue
        tip = [disp[nd][1] for nd, x in mesh.nodes.items() if x[0] == length]
        mean = sum(tip) / len(tip)
        ratios.append(mean / exact)
        with open(os.path.join(work, name + "_csv", "nodal_stresses.csv")) as f:
            sxx = {int(r["node"]): float(r["sxx"]) for r in csv.DictReader(f)}
        fibre = [lambda xx: [sxx[nd] for nd, x in mesh.nodes.items() if x[0] == xx and x[1] == 1.0]][0]
        mid = sum(fibre(length / 2)) / len(fibre(length / 2)) / (-p * length / 2 * 0.5 / inertia)
        root = sum(fibre(0.0)) / len(fibre(0.0)) / (-p * length * 0.5 / inertia)
        mids.append(mid)
        print(f"| {n[0]} x {n[1]} x {n[2]} | {mean:.6e} | {mean / exact:.5f} | {mid:.6f} | {root:.4f} |")
    check(len(ratios) == 4 and abs(ratios[-1] - 1.0) < 0.01,
          f"C3D20R cantilever within 1% of Timoshenko on the finest mesh ({ratios[-1] if ratios else 0:.5f})")
    check(len(ratios) == 4 and abs(ratios[-1] - ratios[-2]) < 0.002,
          "C3D20R cantilever converged (last two meshes within 0.2%)")
    if len(mids) == 4:
        rate = math.log(abs(mids[0] - 1) / abs(mids[1] - 1)) / math.log(2) if mids[1] != 1 else float("inf")
        print(f"\nmid-span bending stress: error {abs(mids[0] - 1):.1e}, {abs(mids[1] - 1):.1e}, "
              f"{abs(mids[2] - 1):.1e} as the elements halve in length (rate {rate:.2f})")
    check(len(mids) == 4 and abs(mids[-1] - 1.0) < 1e-3 and abs(mids[2] - 1) <= abs(mids[0] - 1),
          f"C3D20R cantilever: mid-span bending stress within 0.1% of the beam's ({mids[-1] if mids else 0:.6f})")


def wedge_cantilever(exe, work):
    """The cantilever of cantilever() meshed with wedges (each hexahedral cell split
    into two prisms along its x-y diagonal), C3D6 and C3D15, on meshes halving the
    element size: tip deflection against Timoshenko, and the observed rate
    p = log2((d2 - d1)/(d3 - d2)) of three successive meshes (Richardson)."""
    print("\n## Wedge cantilevers (C3D6, C3D15; the same beam, end shear P = 1 as uniform traction)\n")
    length, e, p = 10.0, 1.0e5, 1.0
    inertia, g = 1.0 / 12, e / 2
    exact = p * length ** 3 / (3 * e * inertia) + p * length / (5.0 / 6.0 * g)
    print("| element | mesh (cells, 2 wedges each) | tip deflection | / Timoshenko |")
    print("|---|---|---|---|")
    for et, meshes in (("C3D6", ((20, 4, 4), (40, 8, 8), (80, 16, 16))),
                       ("C3D15", ((5, 1, 1), (10, 2, 2), (20, 4, 4)))):
        tips = []
        for n in meshes:
            mesh = Mesh(n, (length, 1.0, 1.0), et, False)
            bnd = [(nd, d, 0.0) for nd, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
            loads = {}
            for nd, shares in mesh.face_weights().items():
                for normal, s in shares:
                    if normal[0] == 1.0:
                        loads[nd] = loads.get(nd, 0.0) + s * p
            name = "wedge_cantilever_%s_%d_%d_%d" % ((et,) + n)
            disp, _ = solve(exe, work, name, deck(mesh, e, 0.0, bnd, [(nd, 2, v) for nd, v in sorted(loads.items())]))
            if disp is None:
                return
            tip = [disp[nd][1] for nd, x in mesh.nodes.items() if x[0] == length]
            tips.append(sum(tip) / len(tip))
            print(f"| {et} | {n[0]} x {n[1]} x {n[2]} | {tips[-1]:.6e} | {tips[-1] / exact:.5f} |")
        errs = [abs(t / exact - 1) for t in tips]
        rates = [math.log(errs[k] / errs[k + 1], 2) for k in range(2)]
        print(f"\n{et}: tip error against Timoshenko {errs[0]:.1e}, {errs[1]:.1e}, {errs[2]:.1e} as the elements "
              f"halve (rates {rates[0]:.2f}, {rates[1]:.2f})\n")
        want = 1.5 if et == "C3D6" else 3.0       # asymptotically 2 and 4 (energy h^2p); pre-asymptotic here
        check(rates[1] >= want and rates[1] >= rates[0] - 0.2,
              f"{et} cantilever converges to the beam at rate {rates[1]:.2f} (at least {want})")
        check(errs[2] < (0.1 if et == "C3D6" else 1e-3), f"{et} cantilever: finest mesh within "
                                                          f"{'10%' if et == 'C3D6' else '0.1%'} ({errs[2]:.1e})")


def c3d8i_bending(exe, work):
    """A cantilever 10 x 1 x 1 (E = 1e5, nu = 0) of 10 hexahedra, one through the
    thickness, clamped at x = 0: an end moment M (the consistent nodal forces
    -+M/2 of the linear traction sxx = -12 M (y - h/2)/h^3 at the end face's
    bottom and top corners) and an end shear P (P/4 per end corner): C3D8I
    against the beam, C3D8 beside it (shear locking)."""
    print("\n## C3D8I in bending (10 x 1 x 1, one element through the thickness, nu = 0)\n")
    print("| load | beam | C3D8I | / beam | C3D8 | / beam |")
    print("|---|---|---|---|---|---|")
    length, e, inertia, g = 10.0, 1.0e5, 1.0 / 12, 0.5e5
    cases = (("end moment M = 1", lambda x: -(x[1] - 0.5), 0, 1.0 * length ** 2 / (2 * e * inertia)),
             ("end shear P = 1", lambda x: 0.25, 1, length ** 3 / (3 * e * inertia) + length / (5 / 6 * g)))
    for label, force, dof, exact in cases:
        row = []
        for et in ("C3D8I", "C3D8"):
            mesh = Mesh((10, 1, 1), (length, 1.0, 1.0), et, False)
            bnd = [(n, d, 0.0) for n, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
            cl = [(n, dof + 1, force(x)) for n, x in sorted(mesh.nodes.items()) if x[0] == length]
            disp, _ = solve(exe, work, "bend_%s_%d" % (et, dof), deck(mesh, e, 0.0, bnd, cl))
            if disp is None:
                return
            tip = [disp[n][1] for n, x in mesh.nodes.items() if x[0] == length]
            row.append(sum(tip) / len(tip))
        print(f"| {label} | {exact:.6e} | {row[0]:.6e} | {row[0] / exact:.5f} | {row[1]:.6e} | {row[1] / exact:.5f} |")
        if dof == 0:
            check(abs(row[0] / exact - 1) < 1e-10, f"C3D8I: pure bending exact with one element through the "
                                                   f"thickness ({row[0] / exact:.12f})")
        else:
            check(abs(row[0] / exact - 1) < 0.02, f"C3D8I: end shear within 2% of Timoshenko ({row[0] / exact:.5f})")


def calculix(exe, work):
    if shutil.which("ccx") is None:
        print("\nccx not installed: CalculiX cross-check skipped")
        return
    print("\n## CalculiX cross-check (the distorted block, clamped at x = 0, loads on the far corner nodes,")
    print("pressures 30 + 5 k on the faces of element k that lie on the block's faces y = 1.5 and z = 1)\n")
    print("Stresses and strains at the integration points (*EL PRINT S, E: .dat, 7 digits), nodal")
    print("stresses averaged over the elements (*EL FILE S: .frd, 5 digits).\n")
    print("| element | U / max U | S at points / max | E at points / max | S at nodes / max |")
    print("|---|---|---|---|---|")
    e, nu = 2.0e5, 0.3
    for et in TYPES:
        if et == "C3D8I":       # CalculiX's C3D8I is not the Taylor element: see c3d8i_bending
            continue
        mesh = Mesh((2, 2, 2), (2.0, 1.5, 1.0), et, True)
        bnd = [(n, d, 0.0) for n, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
        far = [n for n, p in mesh.index.items() if p[0] == 4 and p[1] in (0, 4) and p[2] in (0, 4)]
        cl = [(n, 1, 100.0) for n in far] + [(n, 3, -40.0) for n in far] + [(far[0], 2, 25.0)]
        faces = [(k, f) for k, f, ax, side in outer_faces(mesh) if side == 1 and ax != 0]
        dload = "*DLOAD\n" + "\n".join(f" {k}, P{f}, {fmt(30.0 + 5 * k)}" for k, f in faces)
        text = deck(mesh, e, nu, bnd, cl, extra=dload + "\n*EL PRINT, ELSET=ALL\nS\nE\n*EL FILE\nS")
        disp, _ = solve(exe, work, "ccx_" + et, text)
        if disp is None:
            continue
        job = os.path.join(work, "ccx_" + et)
        with open(job + ".inp", "w") as f:
            f.write(text)
        r = subprocess.run(["ccx", "-i", os.path.basename(job)], cwd=work, capture_output=True, text=True)
        ref = dat_blocks(job + ".dat") if r.returncode == 0 and os.path.exists(job + ".dat") else {}
        if not ref.get("displacements"):
            check(False, f"{et}: ccx gave no displacements ({r.stdout.strip()[-200:]})")
            continue
        umax = max(abs(v) for u in disp.values() for v in u)
        diff = max(abs(disp[n][d] - ref["displacements"][n][d]) for n in ref["displacements"] if n in disp
                   for d in range(3)) / umax
        mine = superjoin_points(job)
        sdiff = table_difference(mine["S"], ref.get("stresses", {}))
        ediff = table_difference(mine["E"], ref.get("strains", {}))
        ndiff = table_difference(superjoin_nodes(job), frd_stresses(job + ".frd"))
        print(f"| {et} | {diff:.1e} | {sdiff:.1e} | {ediff:.1e} | {ndiff:.1e} |")
        check(diff <= 1e-5, f"{et}: superjoin and ccx agree on U ({diff:.1e}; ccx prints 7 digits)")
        check(sdiff <= 1e-5 and ediff <= 1e-5, f"{et}: S and E at every integration point agree with ccx, in "
                                               f"CalculiX's point order ({sdiff:.1e}, {ediff:.1e})")
        if et in WEDGES:    # ccx 2.20 extrapolates wedges otherwise (doc/verification.md): measured only
            continue
        check(ndiff <= 5e-5, f"{et}: averaged nodal stresses agree with ccx's .frd ({ndiff:.1e}; 5 digits)")


def dat_blocks(path):
    """CalculiX .dat: {'displacements'/'forces': {node: values}, 'stresses'/'strains': {(elem, ip): values}}
    (also tests/axisym/verify_axisym.py's)."""
    out, block = {}, None
    with open(path) as f:
        for line in f:
            m = re.match(r"\s*(displacements|forces|stresses|strains) ", line)
            if m:
                block = out.setdefault(m.group(1), {})
                continue
            fields = line.split()
            if block is None or not fields:
                continue
            try:
                vals = [float(v) for v in fields]
            except ValueError:
                block = None
                continue
            if len(vals) == 4:
                block[int(vals[0])] = tuple(vals[1:])
            elif len(vals) == 8:
                block[(int(vals[0]), int(vals[1]))] = tuple(vals[2:])
    return out


def superjoin_points(job):
    """superjoin's listing tables of S and E at the integration points of solids: {(elem, ip): values}."""
    out = {"S": {}, "E": {}}
    block = None
    with open(job + ".lst") as f:
        for line in f:
            m = re.match(r"\s+([SE])   at the integration points of the solid elements", line)
            if m:
                block = out[m.group(1)]
                continue
            fields = line.split()
            if block is not None and len(fields) >= 10 and fields[1].isdigit():
                block[(int(fields[1]), int(fields[3]))] = tuple(float(v) for v in fields[4:10])
            elif block is not None and not fields:
                block = None
    return out


def superjoin_nodes(job):
    with open(job + "_csv/nodal_stresses.csv") as f:
        return {int(r["node"]): tuple(float(r[k]) for k in ("sxx", "syy", "szz", "sxy", "sxz", "syz"))
                for r in csv.DictReader(f)}


def frd_stresses(path):
    """The nodal STRESS block of a CalculiX .frd (ASCII): {node: (xx, yy, zz, xy, xz, yz)}."""
    out, inside = {}, False
    with open(path) as f:
        for line in f:
            if line.startswith(" -4  STRESS"):
                inside = True
            elif inside and line.startswith(" -3"):
                break
            elif inside and line.startswith(" -1"):
                v = [float(line[13 + 12 * j:25 + 12 * j]) for j in range(6)]
                out[int(line[3:13])] = (v[0], v[1], v[2], v[3], v[5], v[4])   # .frd: xx yy zz xy yz zx
    return out


def table_difference(mine, ref):
    """Largest difference over the keys of ref / largest magnitude of ref (1 if a key is missing)."""
    if not ref or any(k not in mine for k in ref):
        return 1.0
    scale = max(abs(v) for row in ref.values() for v in row)
    return max(abs(a - b) for k, row in ref.items() for a, b in zip(mine[k], row)) / scale


def vtk_cells(exe, work):
    """The VTK cells of every type: cell type and connectivity (Abaqus's node order is VTK's)."""
    print("\n## VTK cells\n")
    cell = {"C3D8": 12, "C3D20": 25, "C3D20R": 25, "C3D4": 10, "C3D10": 24, "C3D8I": 12, "C3D6": 13, "C3D15": 26}
    for et in TYPES:
        mesh = Mesh((2, 2, 2), (1.0, 1.0, 1.0), et, False)
        path = os.path.join(work, "vtk_" + et + ".deck")
        with open(path, "w") as f:
            f.write(deck(mesh, 1.0e3, 0.3, [(n, d, 0.0) for n in mesh.nodes if mesh.boundary(n)
                                            for d in (1, 2, 3)],
                         [(n, 1, 1.0) for n in mesh.nodes if not mesh.boundary(n)]))
        base = os.path.join(work, "vtk_" + et)
        r = subprocess.run([exe, "-q", path, "-o", base + ".lst", "--vtk", base], capture_output=True, text=True)
        if r.returncode != 0:
            check(False, f"VTK {et}: exit {r.returncode}")
            continue
        with open(base + "_1.vtu") as f:
            text = f.read()
        arrays = dict(re.findall(r'Name="(\w+)" format="ascii">\s*([^<]*)<', text))
        types = [int(v) for v in arrays["types"].split()]
        conn = [int(v) for v in arrays["connectivity"].split()]
        rank = {n: i for i, n in enumerate(sorted(mesh.nodes))}
        want = [rank[n] for el in mesh.elems for n in el]
        ne = len(mesh.elems)
        check(types[:ne] == [cell[et]] * ne and conn[:len(want)] == want,
              f"VTK {et}: {ne} cells of type {cell[et]}, nodes in the element's order")


def refusals(exe, work):
    """Loads and output not implemented on solids are refused with file:line: error, naming the type."""
    print("\n## Refusals\n")
    mesh = Mesh((1, 1, 1), (1.0, 1.0, 1.0), "C3D8", False)
    bnd = [(n, d, 0.0) for n, x in mesh.nodes.items() if x[0] == 0.0 for d in (1, 2, 3)]
    cases = [("P", "*DLOAD\n 1, P, 1.0", "does not apply to element 1 of type C3D8"),
             ("TEMP", "*TEMPERATURE\n NALL, 10., 5.", "of type C3D8")]
    for name, card, want in cases:
        text = deck(mesh, 1.0e3, 0.3, bnd, [], extra=card, density=1.0)
        if name == "TEMP":
            text = text.replace("*DENSITY", "*EXPANSION\n 1.2e-5\n*DENSITY")
        path = os.path.join(work, "refuse_" + name + ".deck")
        with open(path, "w") as f:
            f.write(text)
        r = subprocess.run([exe, "-q", path, "-o", os.path.join(work, "refuse.lst")], capture_output=True, text=True)
        line = next((l for l in r.stderr.splitlines() if want in l), "")
        print(f"{name}: {line or r.stderr.strip()[:200]}")
        check(r.returncode != 0 and re.match(r".*refuse_\w+\.deck:\d+: error: ", line) is not None,
              f"{name} on a C3D8 refused with file:line: error" + (" (the gradient field)" if name == "TEMP" else ""))
    # an *ELEMENT data line that ends with a comma and is not continued
    text = deck(mesh, 1.0e3, 0.3, bnd, [])
    text = re.sub(r"(\*ELEMENT, TYPE=C3D8, ELSET=ALL\n 1, \d+, \d+, \d+),[^\n]*\n", r"\1,\n", text)
    path = os.path.join(work, "refuse_open_line.deck")
    with open(path, "w") as f:
        f.write(text)
    r = subprocess.run([exe, "-q", "--check", path], capture_output=True, text=True)
    print(f"open line: {r.stderr.strip()[:200]}")
    check(r.returncode != 0 and "ends with a comma, but no line continues it" in r.stderr,
          "an *ELEMENT line ending with a comma and not continued is an error")


def contact_blocks(exe, work):
    """Two C3D8 blocks (substructures I and II, each 1 x 1 x 1, two elements
    long, nu = 0) joined face to face by *CONTACT springs of stiffness g on DOFs
    1-3 at the four node pairs; I clamped at x = 0, an axial load P on II's
    far face (P/4 per corner): u_tip = 2 P L/(E A) + P/(4 g), the joint's
    opening P/(4 g), the reactions -P; plain and with both parts condensed."""
    print("\n## Two solid blocks joined by contact springs\n")
    for condense in ("", ", CONDENSE=YES"):
        contact_case(exe, work, condense)


def contact_case(exe, work, condense):
    e, g, p, length = 1.0e4, 250.0, 100.0, 1.0
    mesh = Mesh((2, 1, 1), (length, 1.0, 1.0), "C3D8", False)
    out = ["*HEADING", "two C3D8 blocks joined by contact springs", "*MATERIAL, NAME=MAT", "*ELASTIC", f" {fmt(e)}, 0.0"]
    for name, shift in (("I", 0.0), ("II", length)):
        out += [f"*SUBSTRUCTURE, NAME={name}{condense}", "*NODE"]
        out += [f" {n}, {fmt(x[0] + shift)}, {fmt(x[1])}, {fmt(x[2])}" for n, x in sorted(mesh.nodes.items())]
        out.append("*ELEMENT, TYPE=C3D8, ELSET=ALL")
        out += [" " + ", ".join(str(v) for v in (k,) + tuple(el)) for k, el in enumerate(mesh.elems, 1)]
        out += ["*SOLID SECTION, ELSET=ALL, MATERIAL=MAT", "*END SUBSTRUCTURE"]
    near = sorted(n for n, x in mesh.nodes.items() if x[0] == 0.0)
    far = sorted(n for n, x in mesh.nodes.items() if x[0] == length)
    out.append("*CONTACT, NAME=J, MASTER=I, SLAVE=II")
    out += [f" {m}, {sl}, 1, 3, {fmt(g)}" for m, sl in zip(far, near)]
    out.append("*SUPPORT")
    out += [f" I.{n}, 1, 3" for n in near]
    out += ["*STEP", "*CLOAD"] + [f" II.{n}, 1, {fmt(p / 4)}" for n in far] + ["*END STEP"]
    tag = "contact_blocks" + ("_condensed" if condense else "")
    path = os.path.join(work, tag + ".deck")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    csvdir = os.path.join(work, tag + "_csv")
    r = subprocess.run([exe, "-q", path, "-o", os.path.join(work, tag + ".lst"), "--csv", csvdir],
                       capture_output=True, text=True)
    if r.returncode != 0:
        check(False, f"contact blocks: exit {r.returncode}: {r.stderr.strip()[:300]}")
        return
    u = {}
    with open(os.path.join(csvdir, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            u[(row["substructure"], int(row["node"]))] = float(row["u1"])
    with open(os.path.join(csvdir, "reactions.csv")) as f:
        rx = sum(float(row["force"]) for row in csv.DictReader(f) if row["dof"] == "1")
    exact = 2 * p * length / e + p / (4 * g)
    tip = [u[("II", n)] for n in far]
    opening = [u[("II", sl)] - u[("I", m)] for m, sl in zip(far, near)]
    err = max(abs(t - exact) for t in tip) / exact
    print(f"tip {sum(tip) / 4:.12g}, closed form {exact:.12g}; opening {sum(opening) / 4:.12g} "
          f"(P/4g = {p / (4 * g):.12g}); reactions {rx:.12g}")
    check(err < 1e-10, f"{tag}: tip displacement exact ({err:.1e})")
    check(max(abs(o - p / (4 * g)) for o in opening) < 1e-10 * exact, f"{tag}: joint opening P/(4 g)")
    check(abs(rx + p) < 1e-10 * p, f"{tag}: reactions -P")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    patch_tests(exe, work)
    gravity_tests(exe, work)
    pressure_tests(exe, work)
    cantilever(exe, work)
    wedge_cantilever(exe, work)
    c3d8i_bending(exe, work)
    calculix(exe, work)
    vtk_cells(exe, work)
    contact_blocks(exe, work)
    refusals(exe, work)
    print(f"\n{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
