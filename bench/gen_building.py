#!/usr/bin/env python3
"""A building of floors of bays: parts made of parts (issue 26).

usage: gen_building.py [--mesh M] [--floors N] [--grid G] [--turn DEG] [--explicit] [--edge-joined] > building.deck

One *PART BAY: a square S4 slab (side 4 m, M x M elements, 0.2 m thick,
concrete) at the top of four B33 columns (0.4 m square) standing under its
corners. A *PART FLOOR holds G x G *INSTANCE cards of BAY (BAY1 .. BAYG^2,
row by row, 4 m apart) and the *CONTACT cards joining neighbouring bays at
their shared slab corners (translations 1e11, rotations 4e9: no loop of
RIGID joints); a *PART BUILDING holds N
*INSTANCE cards of FLOOR (F1 .. FN, 3 m apart) and, per bay and floor, a
*CONTACT joining the feet of bay F(k+1).BAYn to the slab corners of bay
F(k).BAYn (translations RIGID, rotations 4e9). The assembly places one
instance B of BUILDING: node 12 of bay 2 of floor 3 is B.F3.BAY2.12. The feet
of the first floor are clamped; the top floor carries horizontal loads at two
corners, every floor a vertical load at the middle of one bay, and one slab a
pressure. With --turn DEG the instance B is turned by DEG degrees about the
axis from (8, 8, 0) to (9, 9, 1) (so every bay is placed by three composed
placements).

With --explicit the same building is written with one level only: *PART BAY and
N G^2 *INSTANCE cards named F3_BAY2 (the placement composed here: one
translation), the contacts in the same order (F3_J1, K3_2), for comparison
(tests/parts/building.py maps B.F3.BAY2 to F3_BAY2 and compares).

With --edge-joined the bays of a floor are joined along their whole shared
slab edge (every edge node, the same contact stiffnesses; the bay has node sets
E, W, N, S of its edges; with --spacing S every S-th edge node only, corners
included: slabs joined at a few points along each edge, as precast slabs by
their shear keys) instead of at the corners only; floors still meet only
at the columns (the feet on the slab corners). A floor then has reduced
unknowns no other floor sees (its edge joints' roots and Δu): the interior a
condensation by level eliminates (src/analysis/level_solver.f90).

Run with `superjoin --condense yes` for the one-level condensed run (one
condensation of BAY, reused by every bay).
"""
import argparse

SIDE = 4.0
HEIGHT = 3.0
THICK = 0.2
E, NU = 3.0e10, 0.2
COL = 0.4
G_ROT = 4.0e9
G_TRA = 1.0e11


def bay(m, edges=False, spacing=1):
    """The *PART BAY block (edges: also the node sets E, W, N, S of the slab's edges, every spacing-th
    node from corner to corner)."""
    n = m + 1
    out = ["*PART, NAME=BAY", "*NODE"]
    for j in range(n):
        for i in range(n):
            out.append(f"{j * n + i + 1}, {SIDE * i / m!r}, {SIDE * j / m!r}, {HEIGHT!r}")
    corners = [1, n, n * n, n * n - m]          # SW, SE, NE, NW
    feet = [n * n + k for k in range(1, 5)]
    for f, c in zip(feet, corners):
        x = SIDE * ((c - 1) % n) / m
        y = SIDE * ((c - 1) // n) / m
        out.append(f"{f}, {x!r}, {y!r}, 0.0")
    for k, c in enumerate(corners, 1):
        out += [f"*NSET, NSET=C{k}", str(c)]
    for k, f in enumerate(feet, 1):
        out += [f"*NSET, NSET=F{k}", str(f)]
    out += ["*NSET, NSET=FOOT", ", ".join(map(str, feet))]
    if edges:
        on = range(0, n, spacing)
        for name, nodes in (("S", [i + 1 for i in on]), ("N", [m * n + i + 1 for i in on]),
                            ("W", [j * n + 1 for j in on]), ("E", [j * n + n for j in on])):
            out += [f"*NSET, NSET={name}", ", ".join(map(str, nodes))]
    out.append("*ELEMENT, TYPE=S4, ELSET=SLAB")
    e = 0
    for j in range(m):
        for i in range(m):
            e += 1
            a = j * n + i + 1
            out.append(f"{e}, {a}, {a + 1}, {a + n + 1}, {a + n}")
    out.append("*ELEMENT, TYPE=B33, ELSET=COLS")
    for f, c in zip(feet, corners):
        e += 1
        out.append(f"{e}, {f}, {c}")
    out += ["*SHELL SECTION, ELSET=SLAB, MATERIAL=CONCRETE", f"{THICK!r}",
            "*BEAM SECTION, ELSET=COLS, MATERIAL=CONCRETE, SECTION=RECT", f"{COL!r}, {COL!r}",
            "*END PART"]
    return out, (n * n) // 2 + 1


def bay_pairs(g, edges=False):
    """Neighbouring bays of a floor: (master, slave, [(master set, slave set)]); edges: the whole shared
    slab edge (node sets E-W, N-S, paired in order) instead of its two corners."""
    out = []
    for r in range(g):
        for c in range(g):
            b = r * g + c + 1
            if c + 1 < g:
                out.append((b, b + 1, [("E", "W")] if edges else [("C2", "C1"), ("C3", "C4")]))
            if r + 1 < g:
                out.append((b, b + g, [("N", "S")] if edges else [("C4", "C1"), ("C3", "C2")]))
    return out


def floor_contacts(g, name, inst, edges=False):
    """The contacts between the bays of one floor; inst(b) names bay b."""
    out = []
    for k, (a, b, sets) in enumerate(bay_pairs(g, edges), 1):
        out.append(f"*CONTACT, NAME={name(k)}, MASTER={inst(a)}, SLAVE={inst(b)}")
        for sm, ss in sets:
            out.append(f"{inst(a)}.{sm}, {inst(b)}.{ss}, 1, 3, {G_TRA!r}")
            out.append(f"{inst(a)}.{sm}, {inst(b)}.{ss}, 4, 6, {G_ROT!r}")
    return out


def storey_contacts(g, k, name, inst):
    """Floor k+1's feet on floor k's slab corners, bay by bay; inst(k, b) names bay b of floor k."""
    out = []
    for b in range(1, g * g + 1):
        out.append(f"*CONTACT, NAME={name(k, b)}, MASTER={inst(k, b)}, SLAVE={inst(k + 1, b)}")
        for c in range(1, 5):
            out.append(f"{inst(k, b)}.C{c}, {inst(k + 1, b)}.F{c}, 1, 3, RIGID")
            out.append(f"{inst(k, b)}.C{c}, {inst(k + 1, b)}.F{c}, 4, 6, {G_ROT!r}")
    return out


def turn_line(deg):
    """The rotation line of B (the explicit deck's instances take it after their composed translation)."""
    return f"8.0, 8.0, 0.0, 9.0, 9.0, 1.0, {float(deg)!r}"


def placement(g, b):
    r, c = divmod(b - 1, g)
    return SIDE * c, SIDE * r


def loads(args, path, mid):
    """Supports and the step; path(k, b) names bay b of floor k."""
    g, n = args.grid, args.floors
    out = ["*BOUNDARY"]
    out += [f"{path(1, b)}.FOOT, ENCASTRE" for b in range(1, g * g + 1)]
    out += ["*STEP, NAME=WIND", "*CLOAD",
            f"{path(n, g * g)}.{(args.mesh + 1) ** 2 - args.mesh}, 1, 2.0e5",
            f"{path(n, g)}.{args.mesh + 1}, 2, -1.5e5"]
    for k in range(1, n + 1):
        out.append(f"{path(k, (k - 1) % (g * g) + 1)}.{mid}, 3, {-1.0e5 - 1.0e3 * k!r}")
    out += ["*DLOAD", f"{path(min(2, n), 1)}.SLAB, P, 5.0e3", "*END STEP"]
    return out


def nested(args, bay_lines, mid):
    g, n = args.grid, args.floors
    out = list(bay_lines)
    out.append("*PART, NAME=FLOOR")
    for b in range(1, g * g + 1):
        x, y = placement(g, b)
        out += [f"*INSTANCE, NAME=BAY{b}, PART=BAY", f"{x!r}, {y!r}, 0.0", "*END INSTANCE"]
    out += floor_contacts(g, lambda k: f"J{k}", lambda b: f"BAY{b}", args.edge_joined)
    out += ["*END PART", "*PART, NAME=BUILDING"]
    for k in range(1, n + 1):
        out += [f"*INSTANCE, NAME=F{k}, PART=FLOOR", f"0.0, 0.0, {HEIGHT * (k - 1)!r}", "*END INSTANCE"]
    for k in range(1, n):
        out += storey_contacts(g, k, lambda k, b: f"K{k}_{b}", lambda k, b: f"F{k}.BAY{b}")
    out += ["*END PART", "*ASSEMBLY, NAME=SITE", "*INSTANCE, NAME=B, PART=BUILDING"]
    if args.turn:
        out += ["0.0, 0.0, 0.0", turn_line(args.turn)]
    out += ["*END INSTANCE", "*END ASSEMBLY"]
    out += loads(args, lambda k, b: f"B.F{k}.BAY{b}", mid)
    return out


def explicit(args, bay_lines, mid):
    g, n = args.grid, args.floors
    out = list(bay_lines)
    out.append("*ASSEMBLY, NAME=SITE")
    for k in range(1, n + 1):
        for b in range(1, g * g + 1):
            x, y = placement(g, b)
            out += [f"*INSTANCE, NAME=F{k}_BAY{b}, PART=BAY", f"{x!r}, {y!r}, {HEIGHT * (k - 1)!r}"]
            if args.turn:
                out.append(turn_line(args.turn))
            out.append("*END INSTANCE")
    # the order of the unfolded nested deck: each floor's contacts, then the building's
    for k in range(1, n + 1):
        out += floor_contacts(g, lambda j: f"F{k}_J{j}", lambda b: f"F{k}_BAY{b}", args.edge_joined)
    for k in range(1, n):
        out += storey_contacts(g, k, lambda k, b: f"K{k}_{b}", lambda k, b: f"F{k}_BAY{b}")
    out.append("*END ASSEMBLY")
    out += loads(args, lambda k, b: f"F{k}_BAY{b}", mid)
    return out


def main():
    p = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    p.add_argument("--mesh", type=int, default=4)
    p.add_argument("--floors", type=int, default=3)
    p.add_argument("--grid", type=int, default=2)
    p.add_argument("--turn", type=float, default=0.0)
    p.add_argument("--explicit", action="store_true")
    p.add_argument("--edge-joined", action="store_true",
                   help="join the bays of a floor along their whole shared slab edge (every edge node)")
    p.add_argument("--spacing", type=int, default=1,
                   help="with --edge-joined: join every SPACING-th edge node only (corners always; M a multiple)")
    args = p.parse_args()
    if args.mesh % args.spacing:
        p.error("--spacing must divide --mesh (the corners are joined)")
    head = ["*HEADING",
            f"A building of {args.floors} floors of {args.grid}x{args.grid} bays "
            f"({'one level' if args.explicit else 'parts made of parts'}"
            f"{', bays joined along their edges' if args.edge_joined else ''}"
            f"{f' every {args.spacing} nodes' if args.edge_joined and args.spacing > 1 else ''}; bench/gen_building.py)",
            "*MATERIAL, NAME=CONCRETE", "*ELASTIC", f"{E!r}, {NU!r}"]
    bay_lines, mid = bay(args.mesh, args.edge_joined, args.spacing)
    body = explicit(args, bay_lines, mid) if args.explicit else nested(args, bay_lines, mid)
    print("\n".join(head + body))


if __name__ == "__main__":
    main()
