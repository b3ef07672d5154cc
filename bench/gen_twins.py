#!/usr/bin/env python3
"""Copies of one part written out as separate substructures (no *PART/*INSTANCE):
the identical parts that superjoin finds by their geometry (--twins, issue 26).

usage: gen_twins.py [--mesh M] [--copies N] [--checks] [--rect-brace] > twins.deck

The part: a square S4 slab (side 4 m, M x M elements, 0.2 m thick) on four B33
columns (0.3 x 0.5 m, orientation vector given: global X in the original) with
a diagonal B33 brace from the first foot to the third slab corner (a tube,
Iy = Iz, the default orientation vector; with --rect-brace a 0.1 x 0.3 m
rectangle, whose default orientation does not turn with the copy). Copy 1 is
the original, copy 2 the original moved, copies 3..N turned by arbitrary proper
rotations (no axis parallel to a global one) and moved; each copy's nodes and
orientation vectors are printed with 17 digits, so that the copies are the
original to round-off. Every substructure is CONDENSE=YES, its four feet
clamped; the third slab corners hang on a B33 chain (substructure LINK, not
condensed) by RIGID contacts. Each copy carries its own pressure and corner
load.

With --checks three more copies that must NOT be found identical to the
original: MOVED (turned, one slab node moved by 1e-6 m), MIRROR (the original
mirrored, x -> -x, and moved: not a proper rotation), WRONGV (turned, its
columns' orientation vector left as in the original).
"""
import argparse
import math

from slab_mesh import corners_and_feet, slab_and_columns

SIDE = 4.0
HEIGHT = 3.0
THICK = 0.2
E, NU = 3.0e10, 0.2
SPACING = 12.0


def rotation(axis, angle):
    """The proper rotation by angle degrees about axis (Rodrigues)."""
    n = math.sqrt(sum(a * a for a in axis))
    x, y, z = (a / n for a in axis)
    c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
    C = 1 - c
    return [[c + x * x * C, x * y * C - z * s, x * z * C + y * s],
            [y * x * C + z * s, c + y * y * C, y * z * C - x * s],
            [z * x * C - y * s, z * y * C + x * s, c + z * z * C]]


def apply(r, v):
    return [sum(r[i][j] * v[j] for j in range(3)) for i in range(3)]


def nodes(m):
    """Node coordinates of the part (slab grid, then the four feet)."""
    n1 = m + 1
    xs = [(SIDE * i / m, SIDE * j / m, HEIGHT) for j in range(n1) for i in range(n1)]
    xs += [(0.0, 0.0, 0.0), (SIDE, 0.0, 0.0), (SIDE, SIDE, 0.0), (0.0, SIDE, 0.0)]
    return xs


def substructure(name, m, r, t, vcol, moved=None, mirror=False, rect_brace=False):
    """One copy: nodes x' = R x + t (mirror: x -> -x first), orientation vector vcol."""
    out = [f"*SUBSTRUCTURE, NAME={name}, CONDENSE=YES", "*NODE"]
    for k, x in enumerate(nodes(m), start=1):
        x = (-x[0], x[1], x[2]) if mirror else x
        y = [a + b for a, b in zip(apply(r, x), t)]
        if moved == k:
            y[2] += 1.0e-6
        out.append(f"{k}, {y[0]!r}, {y[1]!r}, {y[2]!r}")
    corners, feet = corners_and_feet(m)
    out += slab_and_columns(m)
    out.append("*ELEMENT, TYPE=B33, ELSET=BRACE")
    out.append(f"{m * m + 5}, {feet[0]}, {corners[2]}")
    out.append("*NSET, NSET=BOT")
    out.append(", ".join(str(f) for f in feet))
    out.append("*NSET, NSET=HANG")
    out.append(str(corners[2]))
    out.append("*NSET, NSET=LOADED")
    out.append(str(corners[1]))
    out.append("*SHELL SECTION, ELSET=SLAB, MATERIAL=CONCRETE")
    out.append(f"{THICK}")
    b, h = 0.3, 0.5
    out.append("*BEAM SECTION, ELSET=COLUMNS, MATERIAL=CONCRETE")
    out.append(f"{b * h!r}, {b * h ** 3 / 12!r}, {h * b ** 3 / 12!r}, {0.0286 * 1.0!r}")
    out.append(f"{vcol[0]!r}, {vcol[1]!r}, {vcol[2]!r}")
    out.append("*BEAM SECTION, ELSET=BRACE, MATERIAL=CONCRETE")
    if rect_brace:
        out.append(f"{0.03!r}, {0.1 * 0.3 ** 3 / 12!r}, {0.3 * 0.1 ** 3 / 12!r}, {1.0e-4!r}")
    else:
        out.append("0.01, 4.0e-5, 4.0e-5, 8.0e-5")
    out.append("*END SUBSTRUCTURE")
    return out


def copies(n, checks):
    """(name, R, t, v turned, moved node, mirror) of every copy."""
    ident = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    out = [("P1", ident, [0.0, 0.0, 0.0], True, None, False)]
    if n >= 2:
        out.append(("P2", ident, [SPACING, 0.5, 0.25], True, None, False))
    for k in range(3, n + 1):
        r = rotation([1.0, 2.0 - 0.3 * k, 3.0 + 0.1 * k], 23.0 + 37.0 * k)
        out.append((f"P{k}", r, [SPACING * (k - 1), 1.5 * (k % 3), 0.7 * (k % 2)], True, None, False))
    if checks:
        r = rotation([2.0, -1.0, 0.5], 71.0)
        out.append(("MOVED", r, [SPACING * n, 3.0, 1.0], True, 7, False))
        out.append(("MIRROR", ident, [SPACING * (n + 1), 0.0, 0.0], True, None, True))
        out.append(("WRONGV", r, [SPACING * (n + 2), -2.0, 0.5], False, None, False))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", type=int, default=8)
    ap.add_argument("--copies", type=int, default=4)
    ap.add_argument("--checks", action="store_true", help="add copies that must not be found identical")
    ap.add_argument("--rect-brace", action="store_true", help="a rectangular brace with the default orientation")
    args = ap.parse_args()
    m = args.mesh
    out = ["*HEADING", f"{args.copies} copies of one slab-on-columns part written as substructures, "
           f"bench/gen_twins.py --mesh {m} --copies {args.copies}" + (" --checks" if args.checks else "")
           + (" --rect-brace" if args.rect_brace else ""),
           "*MATERIAL, NAME=CONCRETE", "*ELASTIC", f"{E:.6g}, {NU}"]
    n1 = m + 1
    hang = n1 * n1   # the third slab corner
    cs = copies(args.copies, args.checks)
    links = []
    for name, r, t, turn_v, moved, mirror in cs:
        v = apply(r, [1.0, 0.0, 0.0]) if turn_v else [1.0, 0.0, 0.0]
        out += substructure(name, m, r, t, v, moved, mirror, args.rect_brace)
        x = nodes(m)[hang - 1]
        x = (-x[0], x[1], x[2]) if mirror else x
        links.append([a + b for a, b in zip(apply(r, x), t)])
    out += ["*SUBSTRUCTURE, NAME=LINK, CONDENSE=NO", "*NODE"]
    for k, x in enumerate(links, start=1):
        out.append(f"{k}, {x[0]!r}, {x[1]!r}, {x[2]!r}")
    out.append("*ELEMENT, TYPE=B33, ELSET=CHAIN")
    for k in range(1, len(links)):
        out.append(f"{k}, {k}, {k + 1}")
    for k in range(1, len(links) + 1):
        out += [f"*NSET, NSET=L{k}", str(k)]
    out += ["*BEAM SECTION, ELSET=CHAIN, MATERIAL=CONCRETE", "0.02, 1.0e-4, 1.0e-4, 2.0e-4", "0.0, 0.0, 1.0",
            "*END SUBSTRUCTURE"]
    for k, c in enumerate(cs, start=1):
        out += [f"*CONTACT, NAME=J{k}, MASTER=LINK, SLAVE={c[0]}", f"L{k}, HANG, 1, 6, RIGID"]
    out.append("*BOUNDARY")
    for c in cs:
        out.append(f"{c[0]}.BOT, 1, 6")
    out += ["*STEP, NAME=SERVICE", "*DLOAD"]
    for k, c in enumerate(cs, start=1):
        out.append(f"{c[0]}.SLAB, P, {-5.0e3 * (1 + 0.1 * k):.6g}")
    out.append("*CLOAD")
    for k, c in enumerate(cs, start=1):
        out.append(f"{c[0]}.LOADED, 1, {2.0e4 * k:.6g}")
        out.append(f"{c[0]}.LOADED, 3, {-1.0e4 * (k % 3 + 1):.6g}")
    out.append("*END STEP")
    print("\n".join(out))


if __name__ == "__main__":
    main()
