"""Cantilever under a uniform load: L = 10 m, square section 0.1 m (L/h = 100),
q = 1 kN/m in -Y, n elements; probe: tip deflection, exact -qL^4/(8EI)
(Euler-Bernoulli).  superjoin's B33 with consistent loads is exact at the nodes
for any n; CalculiX expands each B31 into 3D C3D20R bricks, so its answer also
carries the shear deformation (about 1e-4 here) and the bricks' discretization.
"""
NAME = 'beam'
DESCRIPTION = 'cantilever, uniform load, B33 / CalculiX B31 (expanded to C3D20R), tip deflection'
LENGTH, H, E, NU, Q = 10.0, 0.1, 2.1e11, 0.3, 1.0e3
INERTIA = H**4 / 12
SIZES = {'quick': [1e3, 1e4, 1e5], 'full': [1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6]}
CCX_SIZES = {'quick': [3e2, 1e3, 3e3], 'full': [3e2, 1e3, 3e3, 1e4, 3e4, 1e5]}


def elements(dofs):
    return max(1, int(round(dofs / 6.0)))


def exact(dofs):
    return -Q * LENGTH**4 / (8 * E * INERTIA)


def superjoin_deck(dofs):
    n = elements(dofs)
    out = ['*HEADING', 'Cantilever, uniform load, %d elements' % n, '*MATERIAL, NAME=STEEL', '*ELASTIC',
           '%r, %r' % (E, NU), '*NODE']
    out += ['%d, %r, 0.0, 0.0' % (i + 1, LENGTH * i / n) for i in range(n + 1)]
    out.append('*ELEMENT, TYPE=B33, ELSET=BEAM')
    out += ['%d, %d, %d' % (i + 1, i + 1, i + 2) for i in range(n)]
    out += ['*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL', '%r, %r, %r, %r' % (H * H, INERTIA, INERTIA, 0.1406 * H**4),
            '*SUPPORT', '1, 1, 6', '*STEP, NAME=LOAD', '*DLOAD', 'BEAM, PY, %r' % -Q, '*END STEP']
    return '\n'.join(out) + '\n', ('MAIN', n + 1, 1)


def ccx_deck(dofs):
    # CalculiX expands every B31 into a C3D20R brick: about 21.6 equations per element
    n = max(1, int(round(dofs / 21.6)))
    out = ['*NODE, NSET=NALL']
    out += ['%d, %r, 0.0, 0.0' % (i + 1, LENGTH * i / n) for i in range(n + 1)]
    out.append('*ELEMENT, TYPE=B31, ELSET=EALL')
    out += ['%d, %d, %d' % (i + 1, i + 1, i + 2) for i in range(n)]
    # P2 acts along local 2 = t x n1 = -Y and is a pressure on the expanded face: force/length / width.
    out += ['*NSET, NSET=TIP', str(n + 1), '*MATERIAL, NAME=STEEL', '*ELASTIC', '%r, %r' % (E, NU),
            '*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=RECT', '%r, %r' % (H, H), '0.0, 0.0, 1.0',
            '*BOUNDARY', '1, 1, 6', '*STEP', '*STATIC', '*DLOAD', 'EALL, P2, %r' % (Q / H),
            '*NODE PRINT, NSET=TIP', 'U', '*END STEP']
    return '\n'.join(out) + '\n', n + 1, 1
