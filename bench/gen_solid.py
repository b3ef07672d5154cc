#!/usr/bin/env python3
"""gen_solid.py -- a structured solid cantilever as a CalculiX deck that both
superjoin and ccx read unchanged.

Two shapes (units m, steel E = 210 GPa, nu = 0.3): `plate` (default), a
bracket plate L x W x T = 2 x 1 x 0.05 cut into 2n x n x 2 cells (two cells
through the thickness: the fill of a plate-like part), and `block`, an arm
4 x 1 x 1 cut into 4n x n x n cells (a chunky part: 3D fill, nnz(L) ~ N^(4/3)).
C3D20R takes one 20-node brick per cell, C3D10 six 10-node tetrahedra per cell
(Kuhn's split along the main diagonal, conforming between cells). The face x = 0 is clamped, every node of
the face x = L carries a vertical load (total 10 kN), the node at the middle of
the tip's top edge is printed (*NODE PRINT), nothing else is written.

usage: gen_solid.py --type C3D20R|C3D10 [--shape plate|block] (--dofs N | --n n) OUT.inp
prints "gen_solid: TYPE nx x ny x nz cells, E elements, N nodes, D DOFs" on stderr.
"""
import argparse
import itertools
import sys

SHAPES = {'plate': ((2, 1, 0), (2.0, 1.0, 0.05)), 'block': ((4, 1, 1), (4.0, 1.0, 1.0))}
SHAPE = 'plate'


def grid(n):
    """Cells (nx, ny, nz) of the current shape for n cells across."""
    (ax, ay, az), _ = SHAPES[SHAPE]
    return ax * n, ay * n, (az * n if az else 2)


def cells_for(etype, dofs):
    """Smallest n whose mesh has at least dofs nodal DOFs."""
    n = 1
    while count_dofs(etype, n) < dofs:
        n += 1
    return n


def count_nodes(etype, n):
    nx, ny, nz = grid(n)
    full = (2 * nx + 1) * (2 * ny + 1) * (2 * nz + 1)
    if etype == 'C3D10':
        return full
    # no face centres, no cell centres
    faces = nx * ny * (nz + 1) + nx * (ny + 1) * nz + (nx + 1) * ny * nz
    return full - faces - nx * ny * nz


def count_dofs(etype, n):
    return 3 * count_nodes(etype, n)


def used(etype, i, j, k):
    """Is doubled-grid point (i, j, k) a node of the mesh?"""
    return etype == 'C3D10' or (i % 2) + (j % 2) + (k % 2) <= 1


# C3D20R: corners in Abaqus order, then the mid-edge nodes 9..20 as corner pairs.
HEX_CORNERS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
HEX_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
# C3D10: corners 1..4, mid-edge nodes 5..10 on 1-2, 2-3, 3-1, 1-4, 2-4, 3-4.
TET_EDGES = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]


def kuhn_tets():
    """Six tetrahedra of the unit cube along 000-111, each positively oriented."""
    tets = []
    for perm in itertools.permutations(range(3)):
        p = [0, 0, 0]
        path = [tuple(p)]
        for axis in perm:
            p[axis] = 1
            path.append(tuple(p))
        a, b, c, d = path
        u = [b[i] - a[i] for i in range(3)]
        v = [c[i] - a[i] for i in range(3)]
        w = [d[i] - a[i] for i in range(3)]
        det = (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
               + u[2] * (v[0] * w[1] - v[1] * w[0]))
        tets.append([a, c, b, d] if det < 0 else [a, b, c, d])
    return tets


def write_deck(etype, n, out):
    nx, ny, nz = grid(n)
    LX, LY, LZ = SHAPES[SHAPE][1]
    mx, my, mz = 2 * nx + 1, 2 * ny + 1, 2 * nz + 1
    ids = {}
    lines = ['*HEADING', 'gen_solid.py: %s cantilever %s %d x %d x %d cells' % (etype, SHAPE, nx, ny, nz),
             '*NODE, NSET=NALL']
    nid = 0
    for k in range(mz):
        for j in range(my):
            for i in range(mx):
                if not used(etype, i, j, k):
                    continue
                nid += 1
                ids[(i, j, k)] = nid
                lines.append('%d, %.10g, %.10g, %.10g' % (nid, LX * i / (2 * nx), LY * j / (2 * ny), LZ * k / (2 * nz)))
    lines.append('*ELEMENT, TYPE=%s, ELSET=EALL' % etype)
    eid = 0
    tets = kuhn_tets()
    for k in range(nz):
        for j in range(ny):
            for i in range(nx):
                base = (2 * i, 2 * j, 2 * k)

                def at(c):
                    return (base[0] + 2 * c[0], base[1] + 2 * c[1], base[2] + 2 * c[2])

                def mid(a, b):
                    return ((a[0] + b[0]) // 2, (a[1] + b[1]) // 2, (a[2] + b[2]) // 2)

                if etype == 'C3D20R':
                    corners = [at(c) for c in HEX_CORNERS]
                    pts = corners + [mid(corners[a], corners[b]) for a, b in HEX_EDGES]
                    eid += 1
                    conn = [ids[p] for p in pts]
                    lines.append('%d, %s,' % (eid, ', '.join(map(str, conn[:15]))))
                    lines.append(', '.join(map(str, conn[15:])))
                else:
                    for tet in tets:
                        corners = [at(c) for c in tet]
                        pts = corners + [mid(corners[a], corners[b]) for a, b in TET_EDGES]
                        eid += 1
                        lines.append('%d, %s' % (eid, ', '.join(str(ids[p]) for p in pts)))
    fixed = [ids[(0, j, k)] for k in range(mz) for j in range(my) if (0, j, k) in ids]
    tip = [ids[(mx - 1, j, k)] for k in range(mz) for j in range(my) if (mx - 1, j, k) in ids]
    probe = ids[(mx - 1, ny, mz - 1)]
    lines.append('*NSET, NSET=FIXED')
    lines.extend(chunks(fixed))
    lines.append('*NSET, NSET=PROBE')
    lines.append(str(probe))
    lines += ['*MATERIAL, NAME=STEEL', '*ELASTIC', '210000000000.0, 0.3',
              '*SOLID SECTION, ELSET=EALL, MATERIAL=STEEL',
              '*BOUNDARY', 'FIXED, 1, 3',
              '*STEP', '*STATIC', '*CLOAD']
    f = -1.0e4 / len(tip)
    lines.extend('%d, 3, %.10g' % (t, f) for t in tip)
    lines += ['*NODE PRINT, NSET=PROBE', 'U', '*END STEP']
    with open(out, 'w') as fh:
        fh.write('\n'.join(lines) + '\n')
    return nx, ny, nz, eid, nid


def chunks(values, width=12):
    return [', '.join(map(str, values[i:i + width])) + ',' for i in range(0, len(values), width)]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--type', choices=['C3D20R', 'C3D10'], required=True)
    ap.add_argument('--shape', choices=sorted(SHAPES), default='plate')
    g = ap.add_mutually_exclusive_group(required=True)
    g.add_argument('--dofs', type=float, help='nodal DOFs wanted (the smallest mesh with at least this many)')
    g.add_argument('--n', type=int, help='cells across (nx = 4 n)')
    ap.add_argument('out')
    a = ap.parse_args()
    global SHAPE
    SHAPE = a.shape
    n = a.n if a.n else cells_for(a.type, a.dofs)
    nx, ny, nz, ne, nn = write_deck(a.type, n, a.out)
    print('gen_solid: %s %d x %d x %d cells, %d elements, %d nodes, %d DOFs' % (a.type, nx, ny, nz, ne, nn, 3 * nn),
          file=sys.stderr)


if __name__ == '__main__':
    main()
