#!/usr/bin/env python3
"""NAFEMS LE10 (thick elliptic plate under pressure) as a CalculiX deck, for
superjoin -i and ccx alike (tests/solids/verify_le10.py, bench/nafems_le10.py).

Quarter plate between the ellipses x^2/2^2 + y^2/1^2 = 1 (inner) and
x^2/3.25^2 + y^2/2.75^2 = 1 (outer), -0.3 <= z <= 0.3; E = 210 GPa, nu = 0.3;
pressure 1 MPa on the upper face z = 0.3. Supports as in NAFEMS's statement
(reproduced in the Fino/FeenoX LE10 case, seamplex.com/fino/cases/012-nafems-le10):
face DCD'C' (y = 0) u_y = 0; face ABA'B' (x = 0) u_x = 0; the outer curved face
BCB'C' u_x = u_y = 0; its mid-plane line (z = 0) u_z = 0. Target: sigma_yy at
D = (2, 0, 0.3) = -5.38 MPa (nodal value).

Hexahedra (C3D8, C3D8I, C3D20R, C3D20): structured n_theta x n_r x n_z in the
ellipse parameter a, straight radial lines from (2 cos a, sin a) to
(3.25 cos a, 2.75 sin a) (as bench/nafems_le1.py); every node, mid-side ones
too, lies on that map, so the boundary nodes lie on the ellipses.
Tetrahedra (C3D4, C3D10): gmsh's mesh of the same volume (two layers of
volumes split at z = 0 so that the mid-plane line carries nodes), only its
nodes and volume elements are taken; supports and the loaded faces are found
by coordinates here.
"""
import math
import os
import re
import subprocess

E, NU, P = 210.0e3, 0.3, 1.0          # MPa
H = 0.3                               # half thickness, m
TARGET = -5.38
TOL = 1.0e-9


def fmt(v):
    """At most 20 characters (CalculiX's field), round-off zeros as 0."""
    return "0." if abs(v) < 1.0e-12 else f"{v:.14g}"


def _point(a, s, z):
    xi, yi = 2.0 * math.cos(a), 1.0 * math.sin(a)
    xo, yo = 3.25 * math.cos(a), 2.75 * math.sin(a)
    return (xi + s * (xo - xi), yi + s * (yo - yi), z)


# corners of a hexahedron in (theta, r, z) index offsets: bottom 1-4 then top 5-8,
# 1 -> 2 outward (r), 1 -> 4 along theta: r x theta = +z, a positive Jacobian
HEX = [(0, 0, 0), (0, 1, 0), (1, 1, 0), (1, 0, 0), (0, 0, 1), (0, 1, 1), (1, 1, 1), (1, 0, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]


def hex_mesh(nt, nr, nz, quadratic):
    """Nodes {id: (x, y, z)} and elements [[node ids]] of the structured hexahedral mesh."""
    ids = {}

    def nid(p):
        if p not in ids:
            ids[p] = len(ids) + 1
        return ids[p]
    elems = []
    for i in range(nt):
        for j in range(nr):
            for k in range(nz):
                c = [(2 * (i + di), 2 * (j + dj), 2 * (k + dk)) for di, dj, dk in HEX]
                el = [nid(p) for p in c]
                if quadratic:
                    el += [nid(tuple((u + v) // 2 for u, v in zip(c[a], c[b]))) for a, b in HEX_EDGES]
                elems.append(el)
    nodes = {n: _point(math.pi / 2 * p[0] / (2 * nt), p[1] / (2 * nr), -H + 2 * H * p[2] / (2 * nz))
             for p, n in ids.items()}
    return nodes, elems


GEO = """SetFactory("Built-in");
Mesh.CharacteristicLengthMax = {h};
Mesh.ElementOrder = {order};
Point(1) = {{0, 0, -0.3}};
Point(2) = {{2, 0, -0.3}};
Point(3) = {{3.25, 0, -0.3}};
Point(4) = {{0, 2.75, -0.3}};
Point(5) = {{0, 1, -0.3}};
Line(1) = {{2, 3}};
Ellipse(2) = {{3, 1, 3, 4}};
Line(3) = {{4, 5}};
Ellipse(4) = {{5, 1, 2, 2}};
Curve Loop(1) = {{1, 2, 3, 4}};
Plane Surface(1) = {{1}};
low[] = Extrude {{0, 0, 0.3}} {{ Surface{{1}}; }};
high[] = Extrude {{0, 0, 0.3}} {{ Surface{{low[0]}}; }};
Physical Volume("PLATE") = {{low[1], high[1]}};
"""


def read_inp_mesh(path, types=('C3D4', 'C3D10')):
    """Nodes {id: coordinates} and the elements [[ids]] of the given types of a gmsh .inp."""
    nodes, elems, mode, per, buf = {}, [], None, 0, []
    sizes = {'C3D4': 4, 'C3D10': 10, 'CPS4': 4, 'CPS8': 8}
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith('**'):
                continue
            if s.startswith('*'):
                up = s.replace(' ', '').upper()
                mode = 'node' if up.startswith('*NODE') else None
                m = re.match(r'\*ELEMENT,TYPE=(\w+)', up)
                if m and m.group(1) in types:
                    mode, per = 'elem', sizes[m.group(1)]
                continue
            if mode == 'node':
                w = s.split(',')
                nodes[int(w[0])] = tuple(float(v) for v in w[1:4])
            elif mode == 'elem':
                buf += [int(v) for v in s.split(',') if v.strip()]
                if len(buf) >= per + 1:
                    elems.append(buf[1:])
                    buf = []
    used = {n for e in elems for n in e}
    return {n: x for n, x in nodes.items() if n in used}, elems


def element_lines(elems, etype, elset):
    """*ELEMENT card of elems, at most 16 entries on a line (CalculiX)."""
    out = [f"*ELEMENT, TYPE={etype}, ELSET={elset}"]
    for k, e in enumerate(elems, 1):
        ids = [str(k)] + [str(n) for n in e]
        while ids:
            head, ids = ids[:16], ids[16:]
            out.append(", ".join(head) + ("," if ids else ""))
    return out


def nset_lines(name, ids):
    """*NSET card, 12 ids on a line."""
    return [f"*NSET, NSET={name}"] + [", ".join(str(n) for n in ids[i:i + 12]) for i in range(0, len(ids), 12)]


def tet_mesh(work, h, quadratic):
    """gmsh's tetrahedral mesh of the quarter plate, characteristic length h."""
    os.makedirs(work, exist_ok=True)
    geo, inp = os.path.join(work, 'le10.geo'), os.path.join(work, 'le10_gmsh.inp')
    with open(geo, 'w') as f:
        f.write(GEO.format(h=h, order=2 if quadratic else 1))
    subprocess.run(['gmsh', '-3', '-format', 'inp', '-o', inp, geo], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return read_inp_mesh(inp)


# faces of the corner numbering (CalculiX's face numbers 1..)
HEX_FACES = [(0, 1, 2, 3), (4, 7, 6, 5), (0, 4, 5, 1), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 4, 0)]
TET_FACES = [(0, 1, 2), (0, 3, 1), (1, 3, 2), (2, 3, 0)]


def on_outer(x):
    return abs((x[0] / 3.25) ** 2 + (x[1] / 2.75) ** 2 - 1.0) < 1.0e-6


def deck(nodes, elems, etype):
    """The CalculiX deck (text) and the id of the node at D."""
    faces = HEX_FACES if len(elems[0]) in (8, 20) else TET_FACES
    out = ["*HEADING", f"NAFEMS LE10 thick plate, {etype}, {len(elems)} elements (tests/solids/le10_deck.py)",
           "*NODE, NSET=NALL"]
    out += [f"{n}, {fmt(x)}, {fmt(y)}, {fmt(z)}" for n, (x, y, z) in sorted(nodes.items())]
    out += element_lines(elems, etype, "PLATE")
    groups = {"YSYM": [], "XSYM": [], "OUTER": [], "MID": []}
    for n, x in sorted(nodes.items()):
        if abs(x[1]) < TOL:
            groups["YSYM"].append(n)
        if abs(x[0]) < TOL:
            groups["XSYM"].append(n)
        if on_outer(x):
            groups["OUTER"].append(n)
            if abs(x[2]) < TOL:
                groups["MID"].append(n)
    for name, ids in groups.items():
        out += nset_lines(name, ids)
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{fmt(E)}, {fmt(NU)}",
            "*SOLID SECTION, ELSET=PLATE, MATERIAL=STEEL",
            "*BOUNDARY", "YSYM, 2, 2", "XSYM, 1, 1", "OUTER, 1, 2", "MID, 3, 3",
            "*STEP", "*STATIC", "*DLOAD"]
    for k, e in enumerate(elems, 1):
        for f, face in enumerate(faces, 1):
            if all(abs(nodes[e[c]][2] - H) < TOL for c in face):
                out.append(f"{k}, P{f}, {fmt(P)}")
    out += ["*NODE PRINT, NSET=NALL, TOTALS=ONLY", "RF", "*EL FILE", "S", "*END STEP"]
    d = min(nodes, key=lambda n: math.dist(nodes[n], (2.0, 0.0, H)))
    assert math.dist(nodes[d], (2.0, 0.0, H)) < TOL, "no node at D"
    return "\n".join(out) + "\n", d


def frd_stress(path, node):
    """The STRESS row (SXX, SYY, SZZ, SXY, SYZ, SZX) of node in an ASCII .frd."""
    cur = False
    with open(path) as f:
        for line in f:
            if line.startswith(' -4'):
                cur = line.split()[1] == 'STRESS'
            elif line.startswith(' -3'):
                cur = False
            elif cur and line.startswith(' -1') and int(line[3:13]) == node:
                n = (len(line.rstrip()) - 13) // 12
                return [float(line[13 + 12 * i:25 + 12 * i]) for i in range(n)]
    raise ValueError(f"node {node} not in the STRESS block of {path}")


def mesh(etype, size, work):
    """Nodes and elements of the mesh `size`: (nt, nr, nz) for hexahedra, h for tetrahedra."""
    if etype in ("C3D4", "C3D10"):
        return tet_mesh(work, size, etype == "C3D10")
    nt, nr, nz = size
    return hex_mesh(nt, nr, nz, etype in ("C3D20", "C3D20R"))
