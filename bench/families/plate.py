"""Simply supported square plate under uniform pressure (a = 1, t = 0.01, a/t = 100,
E = 1.092e7, nu = 0.3 so that D = 1, pressure 1), n x n mesh of S4 (DKQ) or S3
(DKT, alternating diagonals); probe: centre deflection, exact -q a^4 / D times
the Navier double series (tests/shells/shellgen.py, converged below 1e-13).
Kirchhoff plate theory: the discrete answer converges to it at O(h^2).

CalculiX gets the same plate as S4, which it expands into C3D20R bricks (one
layer through the thickness, about 14.3 equations per shell node): a 3D
continuum, so its answer also carries the transverse shear deformation that
Kirchhoff theory leaves out.  mindlin_shear() below gives that share for a
Reissner-Mindlin plate (shear factor 5/6): about 5.2e-4 of the deflection at
a/t = 100, the floor under CalculiX's error against the Navier value.
Both decks hold the edges in u1..u3 (the flat plate's membrane is uncoupled;
CalculiX gives the same 7 digits with only u3 held on the edges).
"""
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                'tests', 'shells'))
import shellgen  # noqa: E402

NAME = 'plate'
DESCRIPTION = ('SS plate a/t = 100, pressure: S4, S3 / CalculiX S4 (C3D20R), '
               'centre deflection vs Navier')
VARIANTS = ['S4', 'S3']
CCX_EQ_PER_NODE = 14.3      # CalculiX's equations per shell node after the C3D20R expansion

# target sizes are the nodal DOFs 6 (n + 1)^2 of an n x n mesh (n = 2, 4, 8, ... 256, 408)
SIZES = {'quick': [54, 486, 6534, 25350],
         'full': [54, 150, 486, 1734, 6534, 25350, 99846, 396294, 1003686]}
# CalculiX: target equations (n = 4, 8, 16, 32, 64, 128)
CCX_SIZES = {'quick': [360, 1160, 4130],
             'full': [360, 1160, 4130, 15600, 60500, 238000]}

_NAVIER = shellgen.navier_ss_uniform()


def mesh(dofs, per_node=6.0):
    """Even n with per_node (n + 1)^2 closest to dofs (n >= 2, so a node sits at the centre)."""
    n = math.sqrt(dofs / per_node) - 1.0
    return max(2, 2 * int(round(n / 2.0)))


def exact(dofs):
    q, a = 1.0, shellgen.PLATE_A
    d = shellgen.PLATE_E * shellgen.PLATE_T**3 / (12.0 * (1.0 - shellgen.PLATE_NU**2))
    return -_NAVIER * q * a**4 / d


def mindlin_shear(nterms=801):
    """Shear share of the centre deflection of the Reissner-Mindlin plate (kappa = 5/6)
    relative to the Kirchhoff one: sum of 16 q / (pi^2 m n kappa G t k^2) over odd m, n."""
    e, nu, t, a = shellgen.PLATE_E, shellgen.PLATE_NU, shellgen.PLATE_T, shellgen.PLATE_A
    shear_stiffness = 5.0 / 6.0 * e / (2.0 * (1.0 + nu)) * t
    s = 0.0
    for m in range(1, nterms + 1, 2):
        for n in range(1, nterms + 1, 2):
            k2 = (m * math.pi / a)**2 + (n * math.pi / a)**2
            s += (-1)**((m - 1) // 2 + (n - 1) // 2) * 16.0 / (math.pi**2 * m * n * shear_stiffness * k2)
    return s / abs(exact(0))



def superjoin_deck(dofs, variant='S4'):
    case = shellgen.square_plate(mesh(dofs), variant, 'SS', 'UNIFORM')
    return case.deck, (case.sub, case.node, case.dof - 1)


def ccx_deck(dofs):
    n = mesh(dofs, CCX_EQ_PER_NODE)
    a = shellgen.PLATE_A

    def nid(i, j):
        return 1 + j * (n + 1) + i
    out = ['*NODE, NSET=NALL']
    out += ['%d, %r, %r, 0.0' % (nid(i, j), i * a / n, j * a / n) for j in range(n + 1) for i in range(n + 1)]
    out.append('*ELEMENT, TYPE=S4, ELSET=EALL')
    e = 1
    for j in range(n):
        for i in range(n):
            out.append('%d, %d, %d, %d, %d' % (e, nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)))
            e += 1
    edge = [nid(i, j) for j in range(n + 1) for i in range(n + 1) if i in (0, n) or j in (0, n)]
    out.append('*NSET, NSET=EDGE')
    out += [', '.join(map(str, edge[k:k + 16])) for k in range(0, len(edge), 16)]
    centre = nid(n // 2, n // 2)
    # CalculiX's P on a shell pushes along +Z for this node order; -1 loads it like superjoin's P = 1 in a
    # step without *STATIC (superjoin reads this deck's *STATIC step as CalculiX does)
    out += ['*NSET, NSET=CENTRE', str(centre), '*MATERIAL, NAME=MAT', '*ELASTIC',
            '%r, %r' % (shellgen.PLATE_E, shellgen.PLATE_NU),
            '*SHELL SECTION, ELSET=EALL, MATERIAL=MAT', repr(shellgen.PLATE_T),
            '*BOUNDARY', 'EDGE, 1, 3', '*STEP', '*STATIC', '*DLOAD', 'EALL, P, -1.0',
            '*NODE PRINT, NSET=CENTRE', 'U', '*END STEP']
    return '\n'.join(out) + '\n', centre, 2
