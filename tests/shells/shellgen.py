"""Deck generators for superjoin's plate and shell verification and benchmarks.

Each case function returns a Case: the deck text, where to read the answer
(substructure, node, DOF, sign) and the reference value with its source. The
meshes are structured grids mapped onto the surface of each problem.
"""
import math
from dataclasses import dataclass, field


@dataclass
class Part:
    """One substructure: nodes {id: (x, y, z)}, elements [(id, type, nodes)], node sets."""
    name: str
    nodes: dict = field(default_factory=dict)
    elems: list = field(default_factory=list)
    nsets: dict = field(default_factory=dict)


@dataclass
class Case:
    name: str
    deck: str
    sub: str            # substructure of the result node
    node: int
    dof: int            # 1..6
    reference: float    # expected value of the displacement (sign included)
    source: str
    ndof: int = 0       # model size (for tables)


def grid(part, nx, ny, mapping, etype, first_node=1, first_elem=1, diag="alt", ioff=0, nxtot=None):
    """Mesh a logical nx-by-ny grid on mapping(s, t) -> (x, y, z), s, t in [0, 1].

    Node (i, j) gets id first_node + j*(nx+1) + i. S3/CPS3 split each quad;
    diag="alt" alternates the diagonal by quadrant so that the mesh is symmetric
    about the grid centre (a grid that is part ioff.. of a wider one of nxtot
    columns uses the wider grid's quadrants). Returns the id function nid(i, j).
    """
    def nid(i, j):
        return first_node + j * (nx + 1) + i
    if etype == "S8R":
        return grid8(part, nx, ny, mapping, nid, first_elem)
    if etype == "S6":
        return grid6(part, nx, ny, mapping, nid, first_elem)
    for j in range(ny + 1):
        for i in range(nx + 1):
            part.nodes[nid(i, j)] = mapping(i / nx, j / ny)
    e = first_elem
    tri = etype in ("S3", "CPS3", "S3R")
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
            if not tri:
                part.elems.append((e, etype, (a, b, c, d)))
                e += 1
                continue
            flip = (diag == "alt") and ((i + ioff < (nxtot or nx) / 2) != (j < ny / 2))
            if flip:
                part.elems.append((e, etype, (a, b, d)))
                part.elems.append((e + 1, etype, (b, c, d)))
            else:
                part.elems.append((e, etype, (a, b, c)))
                part.elems.append((e + 1, etype, (a, c, d)))
            e += 2
    return nid


def grid8(part, nx, ny, mapping, nid, first_elem):
    """S8R on the logical grid: nx, ny are the node intervals (even), each
    element takes a 2 x 2 block of them (corners at even (i, j), mid-side
    nodes at mixed parity; the block centres, both odd, are not nodes), so that
    the mid-side nodes lie on the mapped surface and a case written for an
    nx-by-ny grid of S4R has the same nodes (less the centres) with S8R."""
    if nx % 2 or ny % 2:
        raise ValueError("S8R grid: the node intervals must be even")
    for j in range(ny + 1):
        for i in range(nx + 1):
            if i % 2 and j % 2:
                continue
            part.nodes[nid(i, j)] = mapping(i / nx, j / ny)
    e = first_elem
    for j in range(0, ny, 2):
        for i in range(0, nx, 2):
            part.elems.append((e, "S8R", (nid(i, j), nid(i + 2, j), nid(i + 2, j + 2), nid(i, j + 2),
                                          nid(i + 1, j), nid(i + 2, j + 1), nid(i + 1, j + 2), nid(i, j + 1))))
            e += 1
    return nid


def grid6(part, nx, ny, mapping, nid, first_elem):
    """S6 on the logical grid: as grid8, each 2 x 2 block of node intervals
    split along a diagonal into two six-node triangles (the block centre the
    diagonal's mid-side node), the diagonal alternating by quadrant as grid's
    diag="alt" so that the mesh is symmetric about the grid centre."""
    if nx % 2 or ny % 2:
        raise ValueError("S6 grid: the node intervals must be even")
    for j in range(ny + 1):
        for i in range(nx + 1):
            part.nodes[nid(i, j)] = mapping(i / nx, j / ny)
    e = first_elem
    for j in range(0, ny, 2):
        for i in range(0, nx, 2):
            a, b, c, d = nid(i, j), nid(i + 2, j), nid(i + 2, j + 2), nid(i, j + 2)
            ab, bc, cd, da, m = nid(i + 1, j), nid(i + 2, j + 1), nid(i + 1, j + 2), nid(i, j + 1), nid(i + 1, j + 1)
            if (i < nx / 2) != (j < ny / 2):
                part.elems.append((e, "S6", (a, b, d, ab, m, da)))
                part.elems.append((e + 1, "S6", (b, c, d, bc, cd, m)))
            else:
                part.elems.append((e, "S6", (a, b, c, ab, bc, m)))
                part.elems.append((e + 1, "S6", (a, c, d, m, cd, da)))
            e += 2
    return nid


def fmt(v):
    return repr(float(v))


def negated(v):
    """-v for a number or a number's text (written as fmt would)."""
    if isinstance(v, str):
        return v[1:] if v.startswith("-") else "-" + v
    return -v


def deck_text(title, parts, e, nu, thickness, boundary=(), cloads=(), dloads=(), contacts=(),
              section="SHELL", extra=""):
    """Deck text: one material, one section per part on all its elements."""
    out = ["*HEADING", title, "*MATERIAL, NAME=MAT", "*ELASTIC", f" {fmt(e)}, {fmt(nu)}"]
    for p in parts:
        out.append(f"*SUBSTRUCTURE, NAME={p.name}")
        out.append("*NODE")
        out += [f" {i}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}" for i, x in sorted(p.nodes.items())]
        bytype = {}
        for (i, t, ns) in p.elems:
            bytype.setdefault(t, []).append((i, ns))
        for t, lst in bytype.items():
            out.append(f"*ELEMENT, TYPE={t}, ELSET=ALL")
            out += [" " + ", ".join(str(v) for v in (i,) + tuple(ns)) for i, ns in lst]
        for name, ids in p.nsets.items():
            out.append(f"*NSET, NSET={name}")
            ids = sorted(set(ids))
            for k in range(0, len(ids), 16):
                out.append(" " + ", ".join(str(v) for v in ids[k:k + 16]))
        out.append(f"*{section} SECTION, ELSET=ALL, MATERIAL=MAT")
        out.append(f" {fmt(thickness)}")
        out.append("*END SUBSTRUCTURE")
    for c in contacts:
        out.append(c)
    if boundary:
        out.append("*BOUNDARY")
        for b in boundary:
            out.append(" " + ", ".join(str(v) for v in b))
    out.append(extra)
    out.append("*STEP, NAME=LOAD")
    if cloads:
        out.append("*CLOAD")
        out += [" " + ", ".join(str(v) for v in c) for c in cloads]
    if dloads:
        # the generators' pressure pushes against the normal; *DLOAD P pushes
        # along it (Abaqus, CalculiX, the deck contract), so P is written negated
        out.append("*DLOAD")
        out += [" " + ", ".join(str(v) for v in (d[:2] + (negated(d[2]),) if d[1] == "P" else d)) for d in dloads]
    out.append("*END STEP")
    return "\n".join(out) + "\n"


def count_dofs(parts, per_node=6):
    return per_node * sum(len(p.nodes) for p in parts)


# ------------------------------------------------------------------ references

def navier_ss_uniform(nterms=401):
    """Centre deflection of a simply supported square plate under uniform load,
    w D / (q a^4), Navier double series (odd terms; the tail is below 1e-13)."""
    s = 0.0
    for m in range(1, nterms + 1, 2):
        for n in range(1, nterms + 1, 2):
            sign = (-1) ** ((m - 1) // 2 + (n - 1) // 2)
            s += sign / (m * n * (m * m + n * n) ** 2)
    return 16.0 / math.pi ** 6 * s


def levy_ss_point(nterms=20000):
    """Centre deflection of a simply supported square plate under a central point
    load, w D / (P a^2), Levy single series (Timoshenko & Woinowsky-Krieger §34)."""
    s = 0.0
    for m in range(1, 2 * nterms, 2):
        al = m * math.pi / 2.0
        sech2 = 0.0 if al > 300.0 else 1.0 / math.cosh(al) ** 2
        s += (math.tanh(al) - al * sech2) / m ** 3
    return s / (2.0 * math.pi ** 3)


def levy_ss_joint(k, nu=0.3, nterms=2001):
    """Centre deflection w D / (q a^4) of a simply supported square plate (a = 1,
    D = 1) under uniform load, cut along x = a/2 and joined by a rotational line
    spring k (moment per unit length per radian of relative rotation), the
    translations continuous. Levy series on the half plate 0 <= x <= a/2: SS at
    x = 0, at the joint zero Kirchhoff shear (symmetry) and M_x = 2 k w_x.
    k -> infinity gives navier_ss_uniform, k = 0 a hinge line."""
    c = 0.5
    total = 0.0
    for n in range(1, nterms + 1, 2):
        b = n * math.pi
        yp = 4.0 / (n * math.pi) / b ** 4          # particular solution q_n / (D b^4)
        # basis (a0 + a1 x) exp(s (x - x0)), each decaying away from one end
        basis = [(1.0, 0.0, -b, 0.0), (0.0, 1.0, -b, 0.0), (1.0, 0.0, b, c), (c, -1.0, b, c)]

        def der(f, x, kk):
            a0, a1, s_, x0 = f
            return math.exp(s_ * (x - x0)) * (s_ ** kk * (a0 + a1 * x) + kk * s_ ** (kk - 1) * a1 if kk else
                                               (a0 + a1 * x))
        rows = [[der(f, 0.0, 0) for f in basis] + [-yp],
                [der(f, 0.0, 2) for f in basis] + [0.0],
                [der(f, c, 3) - (2.0 - nu) * b * b * der(f, c, 1) for f in basis] + [0.0],
                [der(f, c, 2) - nu * b * b * der(f, c, 0) + 2.0 * k * der(f, c, 1) for f in basis]
                + [nu * b * b * yp]]
        coef = _solve4(rows)
        y = sum(cf * der(f, c, 0) for cf, f in zip(coef, basis)) + yp
        total += y * math.sin(n * math.pi / 2)
    return total


def _solve4(rows):
    """Gaussian elimination with partial pivoting on an augmented n x (n+1) system."""
    m = [list(r) for r in rows]
    n = len(m)
    for i in range(n):
        p = max(range(i, n), key=lambda r: abs(m[r][i]))
        m[i], m[p] = m[p], m[i]
        for r in range(i + 1, n):
            f = m[r][i] / m[i][i]
            for j in range(i, n + 1):
                m[r][j] -= f * m[i][j]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (m[i][n] - sum(m[i][j] * x[j] for j in range(i + 1, n))) / m[i][i]
    return x


# Clamped square plate: simply supported plate plus edge moments
# (Timoshenko & Woinowsky-Krieger §44), a 400-term system solved in
# tests/unit/test_plate.f90 (converged to ~1e-15). Timoshenko's tables give
# 0.00126 and 0.00560 (3 digits).
CLAMPED_UNIFORM = 0.00126531908748
CLAMPED_POINT = 0.00561202402028

PLATE_E, PLATE_NU, PLATE_T, PLATE_A = 1.092e7, 0.3, 0.01, 1.0   # D = 1


def square_plate(n, etype, support, load, split=None):
    """Square plate a = 1, D = 1, n x n mesh, support 'SS' or 'CL', load 'UNIFORM'
    (pressure 1) or 'POINT' (1 at the centre). split='RIGID' or a rotational
    stiffness per unit length cuts the plate at x = a/2 into parts L and R joined
    node by node (translations RIGID, rotations RIGID or g * tributary length)."""
    if split is None:
        p = Part("PLATE")
        nid = grid(p, n, n, lambda s, t: (s * PLATE_A, t * PLATE_A, 0.0), etype)
        parts = [p]
        edges = [nid(i, j) for j in range(n + 1) for i in range(n + 1) if i in (0, n) or j in (0, n)]
        p.nsets["EDGE"] = edges
        centre = (p.name, nid(n // 2, n // 2))
        bnd = [(f"{p.name}.EDGE", 1, 3 if support == "SS" else 6)]
        loads_c = [(f"{p.name}.{centre[1]}", 3, -1.0)] if load == "POINT" else []
        loads_d = [(f"{p.name}.ALL", "P", 1.0)] if load == "UNIFORM" else []
        contacts = []
    else:
        h = n // 2
        left, right = Part("L"), Part("R")
        nl = grid(left, h, n, lambda s, t: (s * PLATE_A / 2, t * PLATE_A, 0.0), etype, nxtot=n)
        nr = grid(right, h, n, lambda s, t: (PLATE_A / 2 + s * PLATE_A / 2, t * PLATE_A, 0.0), etype,
                  first_node=1001, first_elem=1001, ioff=h, nxtot=n)
        parts = [left, right]
        left.nsets["EDGE"] = [nl(i, j) for j in range(n + 1) for i in range(h + 1) if i == 0 or j in (0, n)]
        right.nsets["EDGE"] = [nr(i, j) for j in range(n + 1) for i in range(h + 1) if i == h or j in (0, n)]
        left.nsets["CUT"] = [nl(h, j) for j in range(n + 1)]
        right.nsets["CUT"] = [nr(0, j) for j in range(n + 1)]
        last = 6 if support == "CL" else 3
        bnd = [("L.EDGE", 1, last), ("R.EDGE", 1, last)]
        centre = ("L", nl(h, n // 2))
        loads_c = [(f"L.{centre[1]}", 3, -1.0)] if load == "POINT" else []
        loads_d = [("L.ALL", "P", 1.0), ("R.ALL", "P", 1.0)] if load == "UNIFORM" else []
        contacts = ["*CONTACT, NAME=JOINT, MASTER=L, SLAVE=R"]
        if split == "RIGID":
            contacts.append(" CUT, CUT, 1, 6, RIGID")
        else:
            contacts.append(" CUT, CUT, 1, 4, RIGID")
            contacts.append(" CUT, CUT, 6, 6, RIGID")
            dy = PLATE_A / n
            for j in range(n + 1):
                trib = dy / 2 if j in (0, n) else dy
                contacts.append(f" {nl(h, j)}, {nr(0, j)}, 5, 5, {fmt(split * trib)}")
    name = f"plate_{support}_{load}_{etype}_{n}" + ("" if split is None else f"_split")
    deck = deck_text(name, parts, PLATE_E, PLATE_NU, PLATE_T, bnd, loads_c, loads_d, contacts)
    if support == "SS" and split not in (None, "RIGID"):
        ref = levy_ss_joint(split, PLATE_NU)
        src = "Levy series with the joint"
    elif support == "SS":
        ref = navier_ss_uniform() if load == "UNIFORM" else levy_ss_point()
        src = "Navier series" if load == "UNIFORM" else "Levy series"
    else:
        ref = CLAMPED_UNIFORM if load == "UNIFORM" else CLAMPED_POINT
        src = "edge-moment superposition, Timoshenko §44"
    return Case(name, deck, centre[0], centre[1], 3, -ref, src, count_dofs(parts))


def scordelis_lo(n, etype, gravity=False):
    """Scordelis-Lo roof (MacNeal-Harder 1985): R 25, L 50, 80 degree arc, t 0.25,
    E 4.32e8, nu 0, self weight 90 per unit area; quarter model n x n; vertical
    displacement at the midpoint of the free edge, reference 0.3024."""
    r, length, phi0, t = 25.0, 50.0, math.radians(40.0), 0.25
    p = Part("ROOF")
    # s along the axis (0 = diaphragm, 1 = mid-span), u around the arc (0 = crown, 1 = free edge)
    nid = grid(p, n, n, lambda s, u: (s * length / 2, r * math.sin(u * phi0), r * math.cos(u * phi0)), etype)
    p.nsets["DIAPHRAGM"] = [nid(0, j) for j in range(n + 1)]
    p.nsets["MIDSPAN"] = [nid(n, j) for j in range(n + 1)]
    p.nsets["CROWN"] = [nid(i, 0) for i in range(n + 1)]
    bnd = [("ROOF.DIAPHRAGM", 2, 3), ("ROOF.MIDSPAN", 1, 1), ("ROOF.MIDSPAN", 5, 6),
           ("ROOF.CROWN", 2, 2), ("ROOF.CROWN", 4, 4), ("ROOF.CROWN", 6, 6)]
    # self weight as nodal forces: tributary area of each node on the grid
    dx, ds = length / 2 / n, r * phi0 / n
    loads = []
    for j in range(n + 1):
        for i in range(n + 1):
            w = (0.5 if i in (0, n) else 1.0) * (0.5 if j in (0, n) else 1.0)
            loads.append((f"ROOF.{nid(i, j)}", 3, fmt(-90.0 * dx * ds * w)))
    name = f"scordelis_lo_{etype}_{n}" + ("_grav" if gravity else "")
    if gravity:
        # self weight from *DENSITY and *DLOAD GRAV: 90 per unit area = density 360 x t 0.25 x 1
        deck = deck_text(name, [p], 4.32e8, 0.0, t, bnd, (), [(", GRAV", "1.0", "0.0", "0.0", "-1.0")])
        deck = deck.replace("*ELASTIC\n 432000000.0, 0.0\n", "*ELASTIC\n 432000000.0, 0.0\n*DENSITY\n 360.0\n")
        deck = deck.replace(" , GRAV,", " , GRAV,")
    else:
        deck = deck_text(name, [p], 4.32e8, 0.0, t, bnd, loads)
    return Case(name, deck, "ROOF", nid(n, n), 3, -0.3024,
                "MacNeal-Harder 1985", count_dofs([p]))


def pinched_hemisphere(n, etype):
    """Hemisphere with an 18 degree hole (MacNeal-Harder 1985): R 10, t 0.04,
    E 6.825e7, nu 0.3, pinched by +-2 at the equator; quarter model n x n with
    loads 1; radial displacement under the load, reference 0.094."""
    r, t = 10.0, 0.04
    lat0 = math.radians(72.0)
    p = Part("HEMI")

    def mapping(s, u):
        lat = s * lat0                      # 0 at the equator
        lon = u * math.pi / 2               # 0 on the x axis
        return (r * math.cos(lat) * math.cos(lon), r * math.cos(lat) * math.sin(lon), r * math.sin(lat))
    nid = grid(p, n, n, mapping, etype)
    p.nsets["XZ"] = [nid(i, 0) for i in range(n + 1)]        # plane y = 0
    p.nsets["YZ"] = [nid(i, n) for i in range(n + 1)]        # plane x = 0
    bnd = [("HEMI.XZ", 2, 2), ("HEMI.XZ", 4, 4), ("HEMI.XZ", 6, 6),
           ("HEMI.YZ", 1, 1), ("HEMI.YZ", 5, 5), ("HEMI.YZ", 6, 6),
           (f"HEMI.{nid(0, 0)}", 3, 3)]
    loads = [(f"HEMI.{nid(0, 0)}", 1, 1.0), (f"HEMI.{nid(0, n)}", 2, -1.0)]
    deck = deck_text(f"hemisphere_{etype}_{n}", [p], 6.825e7, 0.3, t, bnd, loads)
    return Case(f"hemisphere_{etype}_{n}", deck, "HEMI", nid(0, 0), 1, 0.094,
                "MacNeal-Harder 1985", count_dofs([p]))


def twisted_beam(nl, nw, etype, direction):
    """Twisted beam (MacNeal-Harder 1985): length 12, width 1.1, t 0.32, 90
    degree twist, E 29e6, nu 0.22, clamped, unit tip load in-plane (Y at the
    root: 'IN') or out-of-plane ('OUT'); tip deflection along the load,
    references 5.424e-3 and 1.754e-3. Every element is warped."""
    length, width, t = 12.0, 1.1, 0.32
    p = Part("BEAM")

    def mapping(s, u):
        beta = s * math.pi / 2
        w = (u - 0.5) * width
        return (s * length, w * math.cos(beta), w * math.sin(beta))
    nid = grid(p, nl, nw, mapping, etype)
    p.nsets["ROOT"] = [nid(0, j) for j in range(nw + 1)]
    bnd = [("BEAM.ROOT", 1, 6)]
    # at the tip the width runs along Z: in-plane load is along Z, out-of-plane along Y
    dof = 3 if direction == "IN" else 2
    loads = []
    for j in range(nw + 1):
        share = (0.5 if j in (0, nw) else 1.0) / nw
        loads.append((f"BEAM.{nid(nl, j)}", dof, fmt(share)))
    ref = 5.424e-3 if direction == "IN" else 1.754e-3
    deck = deck_text(f"twisted_{direction}_{etype}", [p], 29.0e6, 0.22, t, bnd, loads)
    return Case(f"twisted_beam_{direction}_{etype}_{nl}x{nw}", deck, "BEAM", nid(nl, nw // 2), dof, ref,
                "MacNeal-Harder 1985", count_dofs([p]))


def straight_cantilever(etype, load, shape="regular"):
    """MacNeal-Harder straight cantilever: 6 x 0.2, t 0.1, E 1e7, nu 0.3, 6 x 1
    mesh (regular, trapezoidal or parallelogram), clamped, unit tip load:
    in-plane shear 'IN' (reference 0.1081) or out-of-plane 'OUT' (0.4321, shells)."""
    length, h, t = 6.0, 0.2, 0.1
    p = Part("CANT")
    # bottom and top x positions of the 7 vertical lines
    xb = [float(i) for i in range(7)]
    xt = list(xb)
    if shape == "trapezoid":
        d = [0.0, 0.2, -0.2, 0.2, -0.2, 0.2, 0.0]       # +-45 degree edges: offset h
        xb = [x - di / 2 for x, di in zip(xb, d)]
        xt = [x + di / 2 for x, di in zip(xt, d)]
    elif shape == "parallelogram":
        xb = [x - (0.1 if 0 < i < 6 else 0.0) for i, x in enumerate(xb)]
        xt = [x + (0.1 if 0 < i < 6 else 0.0) for i, x in enumerate(xt)]
    for i in range(7):
        p.nodes[2 * i + 1] = (xb[i], 0.0, 0.0)
        p.nodes[2 * i + 2] = (xt[i], h, 0.0)
    for i in range(6):
        a, b = 2 * i + 1, 2 * i + 3
        p.elems.append((i + 1, etype, (a, b, b + 1, a + 1)))
    p.nsets["ROOT"] = [1, 2]
    plane = etype.startswith("CPS")
    bnd = [("CANT.ROOT", 1, 2 if plane else 6)]
    if not plane:
        # a plate strip in the XY plane: nothing else to hold
        pass
    dof = 2 if load == "IN" else 3
    loads = [("CANT.13", dof, 0.5), ("CANT.14", dof, 0.5)]
    section = "SOLID" if plane else "SHELL"
    deck = deck_text(f"cantilever_{etype}_{load}_{shape}", [p], 1.0e7, 0.3, t, bnd, loads, section=section)
    ref = 0.1081 if load == "IN" else 0.4321
    return Case(f"straight_cantilever_{etype}_{load}_{shape}", deck, "CANT", 14, dof, ref,
                "MacNeal-Harder 1985", count_dofs([p], 2 if plane else 6))


def stiffened_panel(n, joint):
    """Square S4 panel (a = 1, t 0.01, SS edges, pressure 1) with a B33
    stiffener along y = a/2. joint='SHARED': the beam shares the plate's nodes
    (one substructure); 'RIGID' or a number g: the beam is a substructure of
    its own, node by node joined to the plate by contacts on all six DOFs.
    Result: centre deflection (node at the middle of the stiffener line)."""
    plate = Part("PANEL")
    nid = grid(plate, n, n, lambda s, t: (s, t, 0.0), "S4")
    plate.nsets["EDGE"] = [nid(i, j) for j in range(n + 1) for i in range(n + 1) if i in (0, n) or j in (0, n)]
    mid = n // 2
    line = [nid(i, mid) for i in range(n + 1)]
    beam_sec = "*BEAM SECTION, ELSET=RIB, MATERIAL=MAT\n 1.0e-3, 2.0e-7, 1.0e-7, 5.0e-8\n"
    if joint == "SHARED":
        for i in range(n):
            plate.elems.append((10000 + i, "B33", (line[i], line[i + 1])))
        text = deck_text(f"panel_{n}_shared", [plate], PLATE_E, PLATE_NU, PLATE_T,
                         [("PANEL.EDGE", 1, 3)], (), [("PANEL.PLATE_SKIN", "P", 1.0)])
        # split the element set: S4 get the shell section, B33 the beam section
        text = text.replace("*ELEMENT, TYPE=S4, ELSET=ALL", "*ELEMENT, TYPE=S4, ELSET=PLATE_SKIN")
        text = text.replace("*ELEMENT, TYPE=B33, ELSET=ALL", "*ELEMENT, TYPE=B33, ELSET=RIB")
        text = text.replace("*SHELL SECTION, ELSET=ALL", beam_sec + "*SHELL SECTION, ELSET=PLATE_SKIN")
        return Case(f"panel_{n}_shared", text, "PANEL", line[mid], 3, 0.0, "same panel, shared nodes",
                    count_dofs([plate]))
    rib = Part("RIB")
    for i in range(n + 1):
        rib.nodes[i + 1] = (i / n, 0.5, 0.0)
    for i in range(n):
        rib.elems.append((i + 1, "B33", (i + 1, i + 2)))
    g = "RIGID" if joint == "RIGID" else fmt(joint)
    contacts = ["*CONTACT, NAME=WELD, MASTER=PANEL, SLAVE=RIB"]
    contacts += [f" {line[i]}, {i + 1}, 1, 6, {g}" for i in range(n + 1)]
    text = deck_text(f"panel_{n}_{joint}", [plate], PLATE_E, PLATE_NU, PLATE_T,
                     [("PANEL.EDGE", 1, 3)], (), [("PANEL.ALL", "P", 1.0)], contacts)
    rib_text = ["*SUBSTRUCTURE, NAME=RIB", "*NODE"]
    rib_text += [f" {i}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}" for i, x in sorted(rib.nodes.items())]
    rib_text.append("*ELEMENT, TYPE=B33, ELSET=RIB")
    rib_text += [f" {e}, {a}, {b}" for (e, _, (a, b)) in rib.elems]
    rib_text.append(beam_sec.rstrip("\n"))
    rib_text.append("*END SUBSTRUCTURE")
    text = text.replace("*CONTACT", "\n".join(rib_text) + "\n*CONTACT", 1)
    return Case(f"panel_{n}_{joint}", text, "PANEL", line[mid], 3, 0.0, "same panel, shared nodes",
                count_dofs([plate, rib]))


# MacNeal-Harder distorted patch: 0.24 x 0.12 rectangle, four interior nodes.
PATCH_NODES = {1: (0.0, 0.0), 2: (0.24, 0.0), 3: (0.24, 0.12), 4: (0.0, 0.12),
               5: (0.04, 0.02), 6: (0.18, 0.03), 7: (0.16, 0.08), 8: (0.08, 0.08)}
PATCH_QUADS = [(1, 2, 6, 5), (2, 3, 7, 6), (3, 4, 8, 7), (4, 1, 5, 8), (5, 6, 7, 8)]
PATCH_E, PATCH_NU, PATCH_T = 1.0e6, 0.25, 0.001


def patch_rotation():
    """A rotation taking the patch plane to an oblique plane in 3D (rows: images of x, y, z)."""
    a, b, c = math.radians(30.0), math.radians(-40.0), math.radians(25.0)
    rz = [[math.cos(a), -math.sin(a), 0.0], [math.sin(a), math.cos(a), 0.0], [0.0, 0.0, 1.0]]
    ry = [[math.cos(b), 0.0, math.sin(b)], [0.0, 1.0, 0.0], [-math.sin(b), 0.0, math.cos(b)]]
    rx = [[1.0, 0.0, 0.0], [0.0, math.cos(c), -math.sin(c)], [0.0, math.sin(c), math.cos(c)]]

    def mul(p, q):
        return [[sum(p[i][k] * q[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    return mul(rx, mul(ry, rz))


def patch_field(x, y):
    """Exact local field (u, v, w, theta_x, theta_y, theta_z) of the combined patch test."""
    u = 1e-3 * (x + y / 2)
    v = 1e-3 * (y + x / 2)
    w = 1e-3 * (x * x + x * y + y * y) / 2
    return (u, v, w, 1e-3 * (x / 2 + y), -1e-3 * (x + y / 2), 0.0)


def shell_patch(etype):
    """The patch (5 S4, or 10 S3) in an oblique plane; boundary nodes prescribed
    with the exact membrane + bending field, all six DOFs. Returns (deck, rot)."""
    rot = patch_rotation()

    def glob(v):
        return [sum(rot[i][k] * v[k] for k in range(3)) for i in range(3)]
    p = Part("PATCH")
    for i, (x, y) in PATCH_NODES.items():
        p.nodes[i] = tuple(glob((x, y, 0.0)))
    e = 1
    for q in PATCH_QUADS:
        if etype in ("S4", "S4R"):
            p.elems.append((e, etype, q))
            e += 1
        else:
            p.elems.append((e, etype, (q[0], q[1], q[2])))
            p.elems.append((e + 1, etype, (q[0], q[2], q[3])))
            e += 2
    bnd = []
    for i in (1, 2, 3, 4):
        f = patch_field(*PATCH_NODES[i])
        ug, rg = glob(f[0:3]), glob(f[3:6])
        for d in range(3):
            bnd.append((f"PATCH.{i}", d + 1, d + 1, fmt(ug[d])))
            bnd.append((f"PATCH.{i}", d + 4, d + 4, fmt(rg[d])))
    deck = deck_text(f"shell patch {etype}", [p], PATCH_E, PATCH_NU, PATCH_T, bnd)
    return deck, rot, p
