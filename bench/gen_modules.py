#!/usr/bin/env python3
"""A tower of identical storey modules, as *PART and *INSTANCE cards.

usage: gen_modules.py [--mesh M] [--storeys N] [--no-turn] [--joint G] [--row] [--explicit] > tower.deck

One *PART MODULE: a square S4 slab (side 4 m, M x M elements, 0.2 m thick,
concrete) at the top of four B33 columns (0.4 m square) standing on the corners.
N instances are stacked 3 m apart; instance k is turned by 90 (k-1) degrees
about the vertical axis through the middle of the plan (unless --no-turn), so
that the condensation of the part is reused turned. The column feet of storey
k+1 are joined to the slab corners of storey k by contacts found with
PAIR=NEAREST (RIGID on all six DOFs, or translations RIGID and rotations of
stiffness G with --joint G); the feet of the first storey are clamped. Every
slab carries its own pressure (it grows with the storey) and the top slab a
horizontal load at one corner, so that the tower sways and twists.

With --row the N modules stand side by side along x instead (a floor of
panels, each on its own four clamped columns, each turned about its own
vertical axis), neighbouring slabs joined at their two shared corners: the
structure the identical-parts benchmark uses (a tall tower of slender columns
is conditioned so that no method gets its answer to better than about 1e-8).

With --explicit the same tower is written without parts: one *SUBSTRUCTURE per
storey with its nodes placed here as Abaqus places an instance (translation,
then rotation about the axis: x' = a + R (x + t - a)), for comparison.

A module has 6 (M+1)^2 + 24 DOFs of which 48 are on its boundary (the four
feet and the four slab corners): M = 56 gives 19 518 DOFs per module.
"""
import argparse
import math

from slab_mesh import corners_and_feet, slab_and_columns

SIDE = 4.0
HEIGHT = 3.0
THICK = 0.2
E, NU = 3.0e10, 0.2
COL = 0.4


def module(m):
    out = ["*PART, NAME=MODULE", "*NODE"]
    n1 = m + 1
    for j in range(n1):
        for i in range(n1):
            out.append(f"{j * n1 + i + 1}, {SIDE * i / m:.12g}, {SIDE * j / m:.12g}, {HEIGHT:.12g}")
    corners, feet = corners_and_feet(m)
    for f, c in zip(feet, [(0, 0), (SIDE, 0), (SIDE, SIDE), (0, SIDE)]):
        out.append(f"{f}, {c[0]:.12g}, {c[1]:.12g}, 0")
    out += slab_and_columns(m)
    out.append("*NSET, NSET=TOP")
    out.append(", ".join(str(c) for c in corners))
    out.append("*NSET, NSET=BOT")
    out.append(", ".join(str(f) for f in feet))
    for k, c in enumerate(corners):
        out.append(f"*NSET, NSET=C{k + 1}")
        out.append(str(c))
    out.append("*NSET, NSET=LOADED")
    out.append(str(corners[2]))
    out.append("*SHELL SECTION, ELSET=SLAB, MATERIAL=CONCRETE")
    out.append(f"{THICK}")
    area = COL * COL
    inertia = COL ** 4 / 12
    torsion = 0.141 * COL ** 4
    out.append("*BEAM SECTION, ELSET=COLUMNS, MATERIAL=CONCRETE")
    out.append(f"{area:.12g}, {inertia:.12g}, {inertia:.12g}, {torsion:.12g}")
    out.append("*END PART")
    return out


def corner_positions(k, no_turn):
    """Plan positions of the slab corners C1..C4 of module k in a row."""
    angle = 0 if no_turn else (90 * (k - 1)) % 360
    ca, sa = round(math.cos(math.radians(angle))), round(math.sin(math.radians(angle)))
    c = SIDE / 2
    pos = []
    for x, y in ((0, 0), (SIDE, 0), (SIDE, SIDE), (0, SIDE)):
        pos.append(((k - 1) * SIDE + c + ca * (x - c) - sa * (y - c), c + sa * (x - c) + ca * (y - c)))
    return pos


def shared_corners(ka, kb, no_turn):
    """Pairs (i, j): corner Ci of module ka at the place of corner Cj of module kb."""
    pa, pb = corner_positions(ka, no_turn), corner_positions(kb, no_turn)
    return [(i + 1, j + 1) for i, a in enumerate(pa) for j, b in enumerate(pb)
            if abs(a[0] - b[0]) < 1e-9 and abs(a[1] - b[1]) < 1e-9]


def explicit(part, k, shift, angle, cx=SIDE / 2):
    """The part's cards as *SUBSTRUCTURE S<k>, nodes placed (shift: (dx, dz))."""
    c = SIDE / 2
    ca, sa = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    out = [f"*SUBSTRUCTURE, NAME=S{k}"]
    in_nodes = False
    for line in part[1:-1]:
        if line.startswith("*"):
            in_nodes = line == "*NODE"
            out.append(line)
            continue
        if out[-1].startswith("*BEAM SECTION"):
            # the columns' default orientation (global X, being vertical) turns with the instance
            out.append(line)
            out.append(f"{ca:.17g}, {sa:.17g}, 0")
            continue
        if in_nodes:
            nid, x, y, z = line.split(", ")
            x, y, z = float(x) + shift[0], float(y), float(z) + shift[1]
            xr = cx + ca * (x - cx) - sa * (y - c)
            yr = c + sa * (x - cx) + ca * (y - c)
            out.append(f"{nid}, {xr:.17g}, {yr:.17g}, {z:.17g}")
        else:
            out.append(line)
    out.append("*END SUBSTRUCTURE")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", type=int, default=8)
    ap.add_argument("--storeys", type=int, default=4)
    ap.add_argument("--no-turn", action="store_true")
    ap.add_argument("--joint", default="RIGID", help="rotational stiffness of the joints (default RIGID)")
    ap.add_argument("--explicit", action="store_true", help="the same tower without *PART/*INSTANCE")
    ap.add_argument("--row", action="store_true", help="modules side by side on their own columns")
    args = ap.parse_args()
    m, n = args.mesh, args.storeys
    out = ["*HEADING", f"Tower of {n} identical storey modules ({m}x{m} S4 slab on four B33 columns), "
           f"bench/gen_modules.py --mesh {m} --storeys {n}" + (" --no-turn" if args.no_turn else "")
           + (f" --joint {args.joint}" if args.joint != "RIGID" else ""),
           "*MATERIAL, NAME=CONCRETE", "*ELASTIC", f"{E:.6g}, {NU}"]
    c = SIDE / 2
    part = module(m)
    if not args.explicit:
        out += part
        out.append("*ASSEMBLY, NAME=TOWER")
    for k in range(1, n + 1):
        angle = 0 if args.no_turn else (90 * (k - 1)) % 360
        dx, dz = ((k - 1) * SIDE, 0.0) if args.row else (0.0, (k - 1) * HEIGHT)
        if args.explicit:
            out += explicit(part, k, (dx, dz), angle, c + dx)
            continue
        out.append(f"*INSTANCE, NAME=S{k}, PART=MODULE")
        out.append(f"{dx:.12g}, 0, {dz:.12g}")
        out.append(f"{c + dx:.12g}, {c:.12g}, 0, {c + dx:.12g}, {c:.12g}, 1, {angle}")
        out.append("*END INSTANCE")
    for k in range(2, n + 1):
        if args.row:
            # corners i of module k-1 and j of module k at the same place
            out.append(f"*CONTACT, NAME=J{k}, MASTER=S{k - 1}, SLAVE=S{k}")
            for i, j in shared_corners(k - 1, k, args.no_turn):
                out.append(f"C{i}, C{j}, 1, 6, RIGID")
            continue
        out.append(f"*CONTACT, NAME=J{k}, MASTER=S{k - 1}, SLAVE=S{k}, PAIR=NEAREST, TOL=1.0e-6")
        if args.joint.upper() == "RIGID":
            out.append("TOP, BOT, 1, 6, RIGID")
        else:
            out.append("TOP, BOT, 1, 3, RIGID")
            out.append(f"TOP, BOT, 4, 6, {args.joint}")
    if not args.explicit:
        out.append("*END ASSEMBLY")
    out.append("*BOUNDARY")
    if args.row:
        for k in range(1, n + 1):
            out.append(f"S{k}.BOT, 1, 6")
    else:
        out.append("S1.BOT, 1, 6")
    out.append("*STEP, NAME=SERVICE")
    out.append("*DLOAD")
    for k in range(1, n + 1):
        out.append(f"S{k}.SLAB, P, {-5.0e3 * (1 + 0.1 * k):.6g}")   # *DLOAD P pushes along the normal
    out.append("*CLOAD")
    out.append(f"S{n}.LOADED, 1, 2.0e5")
    out.append(f"S{n}.LOADED, 2, 1.0e5")
    out.append("*END STEP")
    print("\n".join(out))


if __name__ == "__main__":
    main()
