#!/usr/bin/env python3
"""Thick cylinder (Lame) under internal pressure, quarter model of CPS8 /
CPE8 (and CPS8R / CPE8R), *DLOAD P4 on the curved inner edges: the
consistent load of a pressure on a curved three-node edge, converging at
the element's rate.

usage: verify_lame.py SUPERJOIN WORKDIR

a = 1, b = 2, p = 10, E = 1000, nu = 0.3, t = 0.1; n elements across the
wall, 2n around the quarter, mid-side nodes on the circles (every arc edge
is a parabola through three points of the circle). Symmetry: v = 0 on
y = 0, u = 0 on x = 0. Exact: s_r = A - B/r^2, s_t = A + B/r^2 with
A = p a^2/(b^2 - a^2), B = p a^2 b^2/(b^2 - a^2);
u_r = ((1 - nu) A r + (1 + nu) B / r)/E (plane stress),
u_r = (1 + nu)((1 - 2 nu) A r + B / r)/E (plane strain).
Measured: the largest nodal error of u_r over the mesh, relative to u_r(a),
for n = 1, 2, 4, 8; the observed order log2(e(n)/e(2n)) must be at least
2.5 at every refinement and 3.5 at the last (quadratic elements with a
parabolic boundary: O(h^3) in the mean, nodal values superconverge towards
h^4; measured 3.3-3.9), and the finest error below 1e-5.
"""
import csv
import math
import os
import subprocess
import sys

A_IN, B_OUT, P, E, NU, T = 1.0, 2.0, 10.0, 1000.0, 0.3, 0.1
failures = []


def exact_ur(r, strain):
    a2, b2 = A_IN ** 2, B_OUT ** 2
    ca = P * a2 / (b2 - a2)
    cb = P * a2 * b2 / (b2 - a2)
    if strain:
        return (1 + NU) * ((1 - 2 * NU) * ca * r + cb / r) / E
    return ((1 - NU) * ca * r + (1 + NU) * cb / r) / E


def deck(etype, n):
    nr, nt = n, 2 * n
    out = ['*HEADING', f'Lame cylinder, quarter, {etype} {nr} x {nt}', '*MATERIAL, NAME=M', '*ELASTIC',
           f'{E!r}, {NU!r}', '*NODE']
    ids, coords = {}, {}
    for i in range(2 * nr + 1):
        r = A_IN + (B_OUT - A_IN) * i / (2 * nr)
        for j in range(2 * nt + 1):
            if i % 2 == 1 and j % 2 == 1:
                continue
            th = 0.5 * math.pi * j / (2 * nt)
            x, y = r * math.cos(th), r * math.sin(th)
            if j == 0:
                y = 0.0
            if j == 2 * nt:
                x = 0.0
            ids[(i, j)] = len(ids) + 1
            coords[ids[(i, j)]] = (x, y)
            out.append(f'{ids[(i, j)]}, {x!r}, {y!r}')
    out.append(f'*ELEMENT, TYPE={etype}, ELSET=ALL')
    inner = []
    for i in range(nr):
        for j in range(nt):
            I, J = 2 * i, 2 * j
            c = [ids[(I, J)], ids[(I + 2, J)], ids[(I + 2, J + 2)], ids[(I, J + 2)],
                 ids[(I + 1, J)], ids[(I + 2, J + 1)], ids[(I + 1, J + 2)], ids[(I, J + 1)]]
            e = i * nt + j + 1
            out.append(f'{e}, ' + ', '.join(map(str, c)))
            if i == 0:
                inner.append(e)
    out += ['*ELSET, ELSET=INNER', ', '.join(map(str, inner)),
            '*SOLID SECTION, ELSET=ALL, MATERIAL=M', f'{T!r}', '*BOUNDARY']
    out += [f'{ids[(i, 0)]}, 2, 2' for i in range(2 * nr + 1)]
    out += [f'{ids[(i, 2 * nt)]}, 1, 1' for i in range(2 * nr + 1)]
    # face 4 of every inner element runs along r = a: a pressure into the wall
    out += ['*STEP', '*STATIC', '*DLOAD', f'INNER, P4, {P!r}', '*END STEP']
    return '\n'.join(out) + '\n', coords


def max_error(exe, work, etype, n):
    text, coords = deck(etype, n)
    name = f'lame_{etype}_{n}'
    path = os.path.join(work, name + '.deck')
    with open(path, 'w') as f:
        f.write(text)
    csvdir = os.path.join(work, name + '.csv')
    proc = subprocess.run([exe, '-q', path, '-o', os.path.join(work, name + '.lst'), '--csv', csvdir],
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        print(f'FAIL: superjoin exited with {proc.returncode} on {path}\n{proc.stderr}')
        sys.exit(1)
    strain = etype.startswith('CPE')
    worst = 0.0
    with open(os.path.join(csvdir, 'displacements.csv')) as f:
        for row in csv.DictReader(f):
            x, y = coords[int(row['node'])]
            r = math.hypot(x, y)
            ur = (float(row['u1']) * x + float(row['u2']) * y) / r
            ut = (-float(row['u1']) * y + float(row['u2']) * x) / r
            worst = max(worst, abs(ur - exact_ur(r, strain)), abs(ut))
    return worst / exact_ur(A_IN, strain)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    exe, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    print('| element | n (wall x quarter) | max nodal error / u_r(a) | order |')
    print('|---|---|---|---|')
    for etype in ('CPS8', 'CPE8', 'CPS8R', 'CPE8R'):
        prev = None
        orders = []
        for n in (1, 2, 4, 8):
            err = max_error(exe, work, etype, n)
            order = math.log2(prev / err) if prev else None
            if order is not None:
                orders.append(order)
            print(f'| {etype} | {n} x {2 * n} | {err:.3e} | {"-" if order is None else f"{order:.2f}"} |')
            prev = err
        if orders[-1] < 3.5 or min(orders) < 2.5:
            failures.append(f'{etype}: orders {orders} (expected at least 2.5, and 3.5 at the last)')
        if prev > 1e-5:
            failures.append(f'{etype}: finest error {prev:.2e} above 1e-5')
    for f in failures:
        print('FAIL:', f)
    if failures:
        sys.exit(1)
    print('all Lame checks passed')


if __name__ == '__main__':
    main()
