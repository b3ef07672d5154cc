"""Pratt truss, simply supported, span 60 m, depth 3 m, n panels, a load P at
every bottom-chord node; probe: midspan deflection.

Exact answer (unit-load method on the statically determinate truss): member
forces from the method of sections, with M_j the bending moment at panel point
j and V_j the shear in panel j of the equivalent simply supported beam:
bottom chord M/h and top chord -M/h at the opposite panel point, diagonals
(sloping down towards midspan, in tension) |V| d/h, verticals -|V| (0 at
midspan); delta = sum N n L / (E A) with n the forces of a unit midspan load.
"""
import math

NAME = 'truss'
DESCRIPTION = 'Pratt truss (T2D2 / CalculiX T3D2), span 60 m, depth 3 m, n panels, midspan deflection'
SPAN, DEPTH, E, AREA, P = 60.0, 3.0, 2.1e11, 4.0e-3, 1.0e4
SIZES = {'quick': [1e3, 1e4, 1e5], 'full': [1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6]}
CCX_SIZES = {'quick': [1e2, 1e3, 5e3], 'full': [1e2, 3e2, 1e3, 3e3, 1e4, 3e4, 5e4]}  # model sizes: ccx expands T3D2 (x26)


def panels(dofs):
    """Even number of panels n for about dofs equations (4n + 1)."""
    n = max(2, int(round(dofs / 4.0)))
    return n + (n % 2)


def geometry(n):
    a = SPAN / n
    nodes = [(j * a, 0.0) for j in range(n + 1)] + [(j * a, DEPTH) for j in range(n + 1)]
    bot = lambda j: j + 1                 # node ids
    top = lambda j: n + 2 + j
    members = []                          # (i, j, kind, index)
    for j in range(n):
        members.append((bot(j), bot(j + 1), 'bottom', j))
        members.append((top(j), top(j + 1), 'top', j))
        if j < n // 2:
            members.append((top(j), bot(j + 1), 'diag', j))
        else:
            members.append((bot(j), top(j + 1), 'diag', j))
    for j in range(n + 1):
        members.append((bot(j), top(j), 'vert', j))
    return a, nodes, members, bot, top


def member_forces(n, loads):
    """Axial forces (tension +) for downward loads[j] at bottom nodes j = 1..n-1."""
    a = SPAN / n
    d = math.hypot(a, DEPTH)
    r_left = sum(loads[j] * (n - j) / n for j in range(1, n))
    m = [0.0] * (n + 1)
    v = [0.0] * n
    acc_w, acc_mw = 0.0, 0.0              # sum of loads left of j, and of their moments
    for j in range(n + 1):
        m[j] = r_left * j * a - (acc_w * j * a - acc_mw)
        if j < n:
            if j >= 1:
                acc_w += loads[j]
                acc_mw += loads[j] * j * a
            v[j] = r_left - acc_w
    forces = {}
    for j in range(n):
        left = j < n // 2
        forces[('bottom', j)] = (m[j] if left else m[j + 1]) / DEPTH
        forces[('top', j)] = -(m[j + 1] if left else m[j]) / DEPTH
        forces[('diag', j)] = (v[j] if left else -v[j]) * d / DEPTH
    for j in range(n + 1):
        if j < n // 2:
            forces[('vert', j)] = -v[j]
        elif j > n // 2:
            forces[('vert', j)] = v[j - 1]
        else:
            forces[('vert', j)] = 0.0
    return forces


def exact(dofs):
    n = panels(dofs)
    a, nodes, members, _, _ = geometry(n)
    d = math.hypot(a, DEPTH)
    length = {'bottom': a, 'top': a, 'diag': d, 'vert': DEPTH}
    big = member_forces(n, [0.0] + [P] * (n - 1) + [0.0])
    unit = [0.0] * (n + 1)
    unit[n // 2] = 1.0
    small = member_forces(n, unit)
    return -math.fsum(big[k] * small[k] * length[k[0]] for k in big) / (E * AREA)


def superjoin_deck(dofs):
    n = panels(dofs)
    _, nodes, members, bot, top = geometry(n)
    out = ['*HEADING', 'Pratt truss, %d panels' % n, '*MATERIAL, NAME=STEEL', '*ELASTIC', '%r, 0.3' % E, '*NODE']
    out += ['%d, %r, %r' % (i + 1, x, y) for i, (x, y) in enumerate(nodes)]
    out.append('*ELEMENT, TYPE=T2D2, ELSET=BARS')
    out += ['%d, %d, %d' % (k + 1, i, j) for k, (i, j, _, _) in enumerate(members)]
    out += ['*SOLID SECTION, ELSET=BARS, MATERIAL=STEEL', repr(AREA), '*SUPPORT',
            '%d, 1, 2' % bot(0), '%d, 2, 2' % bot(n), '*STEP, NAME=LOAD', '*CLOAD']
    out += ['%d, 2, %r' % (bot(j), -P) for j in range(1, n)]
    out.append('*END STEP')
    return '\n'.join(out) + '\n', ('MAIN', bot(n // 2), 1)


def ccx_deck(dofs):
    n = panels(dofs)
    _, nodes, members, bot, top = geometry(n)
    out = ['*NODE, NSET=NALL']
    out += ['%d, %r, %r, 0.0' % (i + 1, x, y) for i, (x, y) in enumerate(nodes)]
    out.append('*ELEMENT, TYPE=T3D2, ELSET=BARS')
    out += ['%d, %d, %d' % (k + 1, i, j) for k, (i, j, _, _) in enumerate(members)]
    out += ['*NSET, NSET=MID', str(bot(n // 2)), '*MATERIAL, NAME=STEEL', '*ELASTIC', '%r, 0.3' % E,
            '*SOLID SECTION, ELSET=BARS, MATERIAL=STEEL', repr(AREA), '*BOUNDARY', 'NALL, 3, 3',
            '%d, 1, 2' % bot(0), '%d, 2, 2' % bot(n), '*STEP', '*STATIC', '*CLOAD']
    out += ['%d, 2, %r' % (bot(j), -P) for j in range(1, n)]
    out += ['*NODE PRINT, NSET=MID', 'U', '*END STEP']
    return '\n'.join(out) + '\n', bot(n // 2), 1
