#!/usr/bin/env python3
"""NAFEMS LE11 (solid cylinder/taper/sphere, temperature load) as a
CalculiX deck of a quarter of the part in hexahedra (C3D20R, C3D8I, ...), for
superjoin -i and ccx alike (bench/nafems_le11.py). (Not axisymmetric CAX
elements: superjoin has no thermal load for them.)

The profile in (r, z) is the key points of Krysl's FinEALE example
pub_LE11NAFEMS_H20.m (github PetrKryslUCSD/FinEALE,
fineale/examples/thermo_mechanical/3-d), taken from the drawing of NAFEMS's
TNSB Rev. 3 (1990):
  A (1, 0), B (1.4, 0): the bottom face AB, z = 0;
  the inner boundary a sphere of radius 1 about the origin from A to
  E (sqrt(1/2), sqrt(1/2)), then a bore of radius sqrt(1/2) up to
  H (sqrt(1/2), 1.79);
  the outer boundary a sphere of radius 1.4 from B to D (sqrt(1.4^2 - 0.7^2), 0.7),
  a straight taper from D to G (1, 1.39) (through F (1.1062, 1.045)), a
  cylinder of radius 1 from G to I (1, 1.79); the top face HI, z = 1.79.
FeenoX's nafems-le11.geo (github seamplex/feenox, examples) draws the same
part with D at z = sqrt(1/2) instead of 0.7 (so G at 1.3971, the top at
1.7971): variant "feenox" below, to show how much that moves sigma_zz at A.
Supports (both sources): u_z = 0 on the bottom and top faces, symmetry on the
planes x = 0 and y = 0. Material E = 210 GPa, nu = 0.3, alpha = 2.3e-4 /deg;
temperature T = sqrt(x^2 + y^2) + z at every node, reference 0. Target:
sigma_zz at A = (1, 0, 0) = -105 MPa.

The profile is meshed by gmsh (quadrangles, recombined; 8-node for the
quadratic hexahedra) at characteristic length h; only its nodes and elements
are taken. They are swept about the z axis through 90 degrees in n_phi layers
(mid-side nodes on the circles); supports and temperatures are set here by
coordinates.
"""
import math
import os
import subprocess

from le10_deck import element_lines, fmt, nset_lines, read_inp_mesh

E, NU, ALPHA = 210.0e3, 0.3, 2.3e-4
TARGET = -105.0
TOL = 1.0e-9
C45 = math.sqrt(0.5)
VARIANTS = {"finEALE": (0.7, 1.39, 1.79), "feenox": (C45, C45 + 0.69, C45 + 1.09)}

GEO = """SetFactory("Built-in");
Mesh.CharacteristicLengthMax = {h};
Mesh.RecombineAll = 1;
Mesh.Algorithm = 6;
Mesh.SubdivisionAlgorithm = 1;
Mesh.ElementOrder = {order};
Mesh.SecondOrderIncomplete = 1;
Point(1) = {{0, 0, 0}};
Point(2) = {{1, 0, 0}};
Point(3) = {{1.4, 0, 0}};
Point(4) = {{{xd}, {zd}, 0}};
Point(5) = {{1, {zg}, 0}};
Point(6) = {{1, {zt}, 0}};
Point(7) = {{{c45}, {zt}, 0}};
Point(8) = {{{c45}, {c45}, 0}};
Line(1) = {{2, 3}};
Circle(2) = {{3, 1, 4}};
Line(3) = {{4, 5}};
Line(4) = {{5, 6}};
Line(5) = {{6, 7}};
Line(6) = {{7, 8}};
Circle(7) = {{8, 1, 2}};
Curve Loop(1) = {{1, 2, 3, 4, 5, 6, 7}};
Plane Surface(1) = {{1}};
Physical Surface("PART") = {{1}};
"""




def mesh(work, h, quadratic, variant="finEALE"):
    """Nodes {id: (r, z)} and elements [[ids]] (4 or 8 nodes) of gmsh's quadrangles."""
    zd, zg, zt = VARIANTS[variant]
    os.makedirs(work, exist_ok=True)
    geo, inp = os.path.join(work, 'le11.geo'), os.path.join(work, 'le11_gmsh.inp')
    with open(geo, 'w') as f:
        f.write(GEO.format(h=h, order=2 if quadratic else 1, xd=math.sqrt(1.96 - zd * zd), zd=zd, zg=zg, zt=zt,
                           c45=C45))
    subprocess.run(['gmsh', '-2', '-format', 'inp', '-o', inp, geo], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    nodes, elems = read_inp_mesh(inp, ('CPS4', 'CPS8'))
    return {n: x[:2] for n, x in nodes.items()}, elems, zt


def revolve(nodes, elems, nphi):
    """The hexahedra (8 or 20 nodes) of the quadrangles swept about the z axis
    through 90 degrees in nphi layers: nodes {id: (x, y, z)}, elements."""
    quadratic = len(elems[0]) == 8
    ids, xyz = {}, {}

    def nid(n, k2):                       # node n of the profile at angle k2 / (2 nphi) of 90 degrees
        if (n, k2) not in ids:
            ids[(n, k2)] = len(ids) + 1
            r, z = nodes[n]
            phi = math.pi / 2 * k2 / (2 * nphi)
            xyz[ids[(n, k2)]] = (r * math.cos(phi), r * math.sin(phi), z)
        return ids[(n, k2)]
    hexes = []
    for e in elems:
        (r1, z1), (r2, z2), (r4, z4) = nodes[e[0]], nodes[e[1]], nodes[e[3]]
        # (r, z) counter-clockwise makes e_r x e_z = -e_phi: reverse it so that
        # 1 -> 2, 1 -> 4 and the sweep are right-handed
        flip = (r2 - r1) * (z4 - z1) - (z2 - z1) * (r4 - r1) > 0
        c = [e[0], e[3], e[2], e[1]] if flip else list(e[:4])
        mids = ([e[7], e[6], e[5], e[4]] if flip else list(e[4:8])) if quadratic else []
        for k in range(nphi):
            lo, hi, mid = 2 * k, 2 * k + 2, 2 * k + 1
            el = [nid(n, lo) for n in c] + [nid(n, hi) for n in c]
            if quadratic:
                el += [nid(n, lo) for n in mids] + [nid(n, hi) for n in mids] + [nid(n, mid) for n in c]
            hexes.append(el)
    return xyz, hexes


def deck3d(xyz, hexes, etype, zt):
    """The CalculiX deck of the swept quarter (text) and the id of the node at A."""
    out = ["*HEADING", f"NAFEMS LE11 cylinder/taper/sphere, {etype}, {len(hexes)} elements (tests/solids/le11_deck.py)",
           "*NODE, NSET=NALL"]
    out += [f"{n}, {fmt(x)}, {fmt(y)}, {fmt(z)}" for n, (x, y, z) in sorted(xyz.items())]
    out += element_lines(hexes, etype, "PART")
    sets = {"ENDS": lambda p: abs(p[2]) < TOL or abs(p[2] - zt) < TOL,
            "YSYM": lambda p: abs(p[1]) < TOL, "XSYM": lambda p: abs(p[0]) < TOL}
    for name, test in sets.items():
        out += nset_lines(name, [n for n, p in sorted(xyz.items()) if test(p)])
    out += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f"{fmt(E)}, {fmt(NU)}", "*EXPANSION, ZERO=0.", fmt(ALPHA),
            "*SOLID SECTION, ELSET=PART, MATERIAL=STEEL", "*INITIAL CONDITIONS, TYPE=TEMPERATURE", "NALL, 0.",
            "*BOUNDARY", "ENDS, 3, 3", "YSYM, 2, 2", "XSYM, 1, 1", "*STEP", "*STATIC", "*TEMPERATURE"]
    out += [f"{n}, {fmt(math.hypot(x, y) + z)}" for n, (x, y, z) in sorted(xyz.items())]
    out += ["*EL FILE", "S", "*END STEP"]
    a = min(xyz, key=lambda n: math.dist(xyz[n], (1.0, 0.0, 0.0)))
    assert math.dist(xyz[a], (1.0, 0.0, 0.0)) < TOL, "no node at A"
    return "\n".join(out) + "\n", a
