#!/usr/bin/env python3
"""A flat strip 2 m x 1 m x 0.01 m (E = 2e11, nu = 0.3) pulled along its length
by 1 MN, given as nodal forces on the free edge x = 2 (F/ny per node, half at
the two corners: the consistent loads of a uniform traction for a bilinear
membrane). doc/verification.md, "Drilling membranes", concentrated forces
normal to a free edge.

usage: gen_pulled_strip.py NX NY TYPE [--roller] [--edge-moments] > strip.deck
  TYPE            S4, S4R, S3, S3R (shells: all six DOFs held at x = 0; S3: two
                  triangles per cell) or CPS4
  --roller        x = 0 held in x only, node 1 in y too, and the shells' w,
                  ur1, ur2 held everywhere: the exact answer is the uniform
                  stress state, u1 = 1e-3 and u2 = -1.5e-4 y at x = 2
  --edge-moments  also the drilling moments -p l^2/12, +p l^2/12 at the two
                  ends of each loaded edge element (p = 1e6 N/m, l its length):
                  with them the nodal loads are consistent with the drilling
                  membrane's edge bubbles too
"""
import sys


def main():
    args = [a for a in sys.argv[1:] if not a.startswith('--')]
    opts = {a for a in sys.argv[1:] if a.startswith('--')}
    if len(args) != 3 or not opts <= {'--roller', '--edge-moments'}:
        sys.exit(__doc__)
    nx, ny, et = int(args[0]), int(args[1]), args[2].upper()
    shell = not et.startswith('CPS')
    length, width, force = 2.0, 1.0, 1.0e6

    def nid(i, j):
        return j * (nx + 1) + i + 1

    out = ['*HEADING', f'strip {nx} x {ny} of {et} pulled by nodal forces, bench/gen_pulled_strip.py',
           '*MATERIAL, NAME=STEEL', '*ELASTIC', '2.0e11, 0.3', '*NODE']
    for j in range(ny + 1):
        for i in range(nx + 1):
            out.append(f'{nid(i, j)}, {length * i / nx}, {width * j / ny}, 0.0')
    out.append(f'*ELEMENT, TYPE={et}, ELSET=ALL')
    e = 1
    for j in range(ny):
        for i in range(nx):
            if et.startswith('S3'):   # two triangles per cell
                out.append(f'{e}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}')
                out.append(f'{e + 1}, {nid(i, j)}, {nid(i + 1, j + 1)}, {nid(i, j + 1)}')
                e += 2
            else:
                out.append(f'{e}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}, {nid(i, j + 1)}')
                e += 1
    out += ['*SHELL SECTION, ELSET=ALL, MATERIAL=STEEL' if shell else
            '*SOLID SECTION, ELSET=ALL, MATERIAL=STEEL', '0.01', '*BOUNDARY']
    if '--roller' in opts:
        out += [f'{nid(0, j)}, 1, 1' for j in range(ny + 1)] + [f'{nid(0, 0)}, 2, 2']
        if shell:
            out += [f'{n}, 3, 5' for n in range(1, (nx + 1) * (ny + 1) + 1)]
    else:
        out += [f'{nid(0, j)}, 1, {6 if shell else 2}' for j in range(ny + 1)]
    out += ['*STEP', '*STATIC', '*CLOAD']
    for j in range(ny + 1):
        share = 0.5 if j in (0, ny) else 1.0
        out.append(f'{nid(nx, j)}, 1, {force * share / ny!r}')
    if '--edge-moments' in opts and shell:
        p, edge = force / width, width / ny
        moment = [0.0] * (ny + 1)
        for j in range(ny):   # edge from nid(nx, j) to nid(nx, j + 1), counterclockwise in its element
            moment[j] -= p * edge**2 / 12
            moment[j + 1] += p * edge**2 / 12
        out += [f'{nid(nx, j)}, 6, {m!r}' for j, m in enumerate(moment) if m != 0.0]
    out.append('*END STEP')
    print('\n'.join(out))


if __name__ == '__main__':
    main()
