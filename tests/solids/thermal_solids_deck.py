#!/usr/bin/env python3
"""Write tests/decks/thermal_solids.deck: thermal loads on every solid type.

usage: thermal_solids_deck.py [OUTPUT]   (default: tests/decks/thermal_solids.deck)

The meshes are those of verify_solids.py (class Mesh): 2 x 2 x 2 blocks of
cells, Kuhn's six tetrahedra or two wedges per cell, the interior nodes moved
by a smooth bump (distorted; mid-side nodes halfway along straight edges).

- F_<type>: a free distorted block, heated from 20 to 120 (dT = 100):
  u = alpha dT x at every node, the stresses 0 (round-off);
- C_<type>: one cell of the block's size with every node held: no motion,
  the stress of the prevented expansion -E alpha dT/(1 - 2 nu) in all three
  directions, no shear; the hexahedra's reaction at the origin is that
  stress's share of the face x = 0 (C3D8: A/4, C3D20: -A/12 at a corner);
- G_<type> (the quadratic types and C3D8I): a free regular bar 2 x 0.5 x 0.5 (2 x 2 x 2
  cells) whose temperature rises linearly along x, T = 20 + 40 (1 + x): its
  free expansion u = alpha (dT0 x + g (x^2 - y^2 - z^2)/2, g x y, g x z),
  dT0 = 40, g = 40, is quadratic, so the quadratic elements hold it and are
  stress-free, and so is C3D8I, whose modes hold it on this regular bar (the
  other linear types cannot hold it and are left out).
Supports of the free blocks: the corner at the origin holds 1-3, the corner
(Lx, 0, 0) holds 2 and 3, the corner (0, Ly, 0) holds 3 (statically
determinate: no reaction).
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from verify_solids import Mesh  # noqa: E402

TYPES = ("C3D8", "C3D8I", "C3D8R", "C3D20", "C3D20R", "C3D4", "C3D10", "C3D6", "C3D15")
QUADRATIC = ("C3D20", "C3D20R", "C3D10", "C3D15")
E, NU, ALPHA, T0, T1 = 2.1e5, 0.3, 1.2e-5, 20.0, 120.0
SIZE = (1.0, 0.8, 0.6)
BAR = (2.0, 0.5, 0.5)
G0, G = 40.0, 40.0


def fmt(v):
    return repr(float(v)) if v != int(v) else f"{v:.1f}"


def corner(mesh, p):
    """The node at the half-index grid point p."""
    return mesh.nid(p)


def substructure(name, mesh, nodes):
    """The substructure's cards; PICK: its first and last elements and the nodes `nodes` (printed)."""
    out = [f"*SUBSTRUCTURE, NAME={name}", "*NODE, NSET=ALL"]
    out += [f"{n}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}" for n, x in sorted(mesh.nodes.items())]
    edge = sorted(n for n in mesh.nodes if mesh.boundary(n))
    out.append("*NSET, NSET=EDGE")
    out += [", ".join(str(n) for n in edge[c:c + 16]) for c in range(0, len(edge), 16)]
    out.append(f"*ELEMENT, TYPE={mesh.etype}, ELSET=ALL")
    for k, el in enumerate(mesh.elems, 1):
        fields = [str(k)] + [str(v) for v in el]
        for c in range(0, len(fields), 16):
            tail = "," if c + 16 < len(fields) else ""
            out.append(", ".join(fields[c:c + 16]) + tail)
    out += ["*NSET, NSET=PICK", ", ".join(str(n) for n in sorted(set(nodes))),
            "*ELSET, ELSET=PICK", f"1, {len(mesh.elems)}"]
    out += ["*SOLID SECTION, ELSET=ALL, MATERIAL=M", "*END SUBSTRUCTURE"]
    return out


def supports(name, mesh):
    n = mesh.n
    return [f" {name}.{corner(mesh, (0, 0, 0))}, 1, 3", f" {name}.{corner(mesh, (2 * n[0], 0, 0))}, 2, 3",
            f" {name}.{corner(mesh, (0, 2 * n[1], 0))}, 3, 3"]


def interior(mesh):
    """The node at the middle of the block (moved by the distortion)."""
    return mesh.nid(tuple(mesh.n[d] for d in range(3)))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "decks", "thermal_solids.deck")
    head = ["*HEADING",
            "Thermal loads on the solids (issue 23), written by tests/solids/thermal_solids_deck.py: a free",
            "distorted block of every type heated uniformly (u = alpha dT x, no stress), the same block held at its",
            "boundary (s = -E alpha dT/(1 - 2 nu) in all three directions), a free bar with a temperature linear",
            "along it (stress-free for the quadratic types, which hold its quadratic free expansion).",
            f"** let: E = {E}", f"** let: nu = {NU}", f"** let: al = {ALPHA}", f"** let: dT = {T1 - T0}",
            "** let: e0 = al*dT", "** let: SC = -E*al*dT/(1-2*nu)",
            f"** let: g0 = {G0}", f"** let: g = {G}",
            "** The bars G_*: the quadratic types and C3D8I (its modes hold the quadratic free expansion on a",
            "** regular bar); C3D8, C3D4, C3D6 cannot hold it and are left out."]
    body, bnd, temps, expects = [], [], [], []
    for t in TYPES:
        free = Mesh((2, 2, 2), SIZE, t, True)
        far = corner(free, tuple(2 * free.n[d] for d in range(3)))
        mid = interior(free)
        xm = free.nodes[mid]
        body += substructure("F_" + t, free, [far, mid])
        bnd += supports("F_" + t, free)
        temps.append(f" F_{t}.ALL, {T1}")
        expects += [f"** expect: displacements step=HEAT substructure=F_{t} node={far} u1 == e0*{SIZE[0]} rtol=1e-10",
                    f"** expect: displacements step=HEAT substructure=F_{t} node={far} u3 == e0*{SIZE[2]} rtol=1e-10",
                    f"** expect: displacements step=HEAT substructure=F_{t} node={mid} u1 == e0*{xm[0]!r} rtol=1e-10",
                    f"** expect: displacements step=HEAT substructure=F_{t} node={mid} u2 == e0*{xm[1]!r} rtol=1e-10",
                    f"** expect: point_stresses step=HEAT substructure=F_{t} element=1 point=1 sxx == 0 atol=1e-9",
                    f"** expect: point_stresses step=HEAT substructure=F_{t} element={len(free.elems)} point=1 "
                    "syz == 0 atol=1e-9"]
        held = Mesh((1, 1, 1), SIZE, t, False)
        far = corner(held, (2, 2, 2))
        body += substructure("C_" + t, held, [far, corner(held, (0, 0, 0))])
        bnd.append(f" C_{t}.EDGE, 1, 3")
        temps.append(f" C_{t}.ALL, {T1}")
        last = len(held.elems)
        expects += [f"** expect: point_stresses step=HEAT substructure=C_{t} element=1 point=1 sxx == SC rtol=1e-10",
                    f"** expect: point_stresses step=HEAT substructure=C_{t} element={last} point=1 syy == SC rtol=1e-10",
                    f"** expect: point_stresses step=HEAT substructure=C_{t} element={last} point=1 szz == SC rtol=1e-10",
                    f"** expect: point_stresses step=HEAT substructure=C_{t} element=1 point=1 sxz == 0 atol=1e-9",
                    f"** expect: displacements step=HEAT substructure=C_{t} node={far} u1 == 0 atol=1e-15"]
        origin = corner(held, (0, 0, 0))
        share = {"C3D8": "-0.48/4", "C3D8I": "-0.48/4", "C3D8R": "-0.48/4", "C3D20": "0.48/12", "C3D20R": "0.48/12"}
        if t in share:      # the origin corner's share of the stress on the face x = 0 (outward normal -x)
            expects.append(f"** expect: reactions step=HEAT substructure=C_{t} node={origin} dof=1 force == "
                           f"SC*{share[t]} rtol=1e-10")
        if t not in QUADRATIC + ("C3D8I",):
            continue
        bar = Mesh((2, 2, 2), BAR, t, False)
        end = corner(bar, tuple(2 * bar.n[d] for d in range(3)))
        body += substructure("G_" + t, bar, [end])
        bnd += supports("G_" + t, bar)
        temps += [f" G_{t}.{n}, {T0 + G0 + G * x[0]!r}" for n, x in sorted(bar.nodes.items())]
        lx, ly, lz = BAR
        expects += [f"** expect: displacements step=HEAT substructure=G_{t} node={end} u1 == "
                    f"al*(g0*{lx} + g*({lx}**2 - {ly}**2 - {lz}**2)/2) rtol=1e-10",
                    f"** expect: displacements step=HEAT substructure=G_{t} node={end} u2 == "
                    f"al*(g0*{ly} + g*{lx}*{ly}) rtol=1e-10",
                    f"** expect: displacements step=HEAT substructure=G_{t} node={end} u3 == "
                    f"al*(g0*{lz} + g*{lx}*{lz}) rtol=1e-10",
                    f"** expect: point_stresses step=HEAT substructure=G_{t} element={len(bar.elems)} point=1 "
                    "sxx == 0 atol=1e-9",
                    f"** expect: point_stresses step=HEAT substructure=G_{t} element=1 point=2 "
                    "syy == 0 atol=1e-9"]
    out = head + expects + ["*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}", "*EXPANSION", f"{ALPHA}"] + body
    # the steps a scale for the equilibrium check of the listing (the thermal loads sum to 0)
    out += ["*SUBSTRUCTURE, NAME=BAR", "*NODE", "1, 0.0, 0.0, 0.0", "2, 1.0, 0.0, 0.0",
            "*ELEMENT, TYPE=T3D2, ELSET=ALL", "1, 1, 2", "*SOLID SECTION, ELSET=ALL, MATERIAL=M", "0.01",
            "*END SUBSTRUCTURE"]
    out += ["*BOUNDARY", " BAR.1, 1, 3", " BAR.2, 2, 3"] + bnd
    bars = QUADRATIC + ("C3D8I",)
    out += ["*INITIAL CONDITIONS, TYPE=TEMPERATURE"] + [f" {p}{t}.ALL, {T0}" for p in ("F_", "C_", "G_")
                                                       for t in TYPES if p != "G_" or t in bars]
    out += ["*STEP, NAME=HEAT", "*STATIC", "*CLOAD", " BAR.2, 1, 1.0", "*TEMPERATURE"] + temps
    for p in ("F_", "C_", "G_"):
        for t in TYPES:
            if p == "G_" and t not in bars:
                continue
            out += [f"*NODE PRINT, NSET={p}{t}.PICK", "U, RF", f"*EL PRINT, ELSET={p}{t}.PICK", "S"]
    # an *EL FILE of printed elements: the deck test's runs with and without CSV compute the same elements
    out += ["*EL FILE, ELSET=F_C3D8.PICK", "S", "*END STEP"]
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
