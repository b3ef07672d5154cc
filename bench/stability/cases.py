"""Stress-test structures for sweep.py.

A case turns one value of its swept variable into the substitutions of its deck
template (templates/NAME.deck.in, Python str.format fields), the probe node
whose six displacements are compared, and their exact values (None when the
value makes the structure a mechanism: then exit status 3 is the right answer).

To add a structure (e.g. a shell joined to a beam once S4 exists): write
templates/<name>.deck.in, add a function returning Case(...) below and register
it in CASES with its default values.
"""
import math
from dataclasses import dataclass, field

import exact

RIGID = 'RIGID'


@dataclass
class Case:
    template: str
    subst: dict
    probe: tuple            # (substructure, node id)
    exact: list = None      # u1 u2 u3 ur1 ur2 ur3 at the probe, None for a mechanism
    note: str = ''
    extra: dict = field(default_factory=dict)


def g_text(g):
    return RIGID if g is None else repr(float(g))


def scaled(value, k):
    """value: a factor, 0, or RIGID -> g (None for RIGID)."""
    if value == RIGID:
        return None
    return float(value) * k


def _line_nodes(first_id, x0, x1, n):
    return '\n'.join('%d, %r, 0.0' % (first_id + i, x0 + (x1 - x0) * i / n) for i in range(n + 1))


def _line_elements(first_node, n):
    return '\n'.join('%d, %d, %d' % (i + 1, first_node + i, first_node + i + 1) for i in range(n))


def _cantilever(g1, g2, g6, e1=2.0e11, e2=2.0e11, a=1.0e-2, inertia=1.0e-4, length=4.0, nel=8,
                factor='', n_load=5000.0, p_load=-1000.0):
    """Two-part B23 cantilever along X, joint at mid-length, tip load (N, P)."""
    half = length / 2
    subst = dict(nel=nel, L=length, factor=factor, E1=repr(e1), E2=repr(e2), A=repr(a), I=repr(inertia),
                 nodes_I=_line_nodes(1, 0.0, half, nel), elements_I=_line_elements(1, nel),
                 nodes_II=_line_nodes(1, half, length, nel), elements_II=_line_elements(1, nel),
                 joint_I=nel + 1, tip=nel + 1, g1=g_text(g1), g2=g_text(g2), g6=g_text(g6),
                 N=repr(n_load), P=repr(p_load))
    try:
        segs = [exact.beam_segment([half * i / nel, 0, 0], [half * (i + 1) / nel, 0, 0], e1, 0.3, a,
                                   inertia, inertia, inertia) for i in range(nel)]
        segs.append(exact.joint_segment([half, 0, 0], [g1, g2, None], [None, None, g6]))
        segs += [exact.beam_segment([half + half * i / nel, 0, 0], [half + half * (i + 1) / nel, 0, 0], e2,
                                    0.3, a, inertia, inertia, inertia) for i in range(nel)]
        ex = exact.chain_tip(segs, [length, 0, 0], [n_load, p_load, 0.0], [0.0, 0.0, 0.0])
    except ZeroDivisionError:
        ex = None
    return Case('cantilever', subst, ('II', nel + 1), ex)


def cantilever(value):
    """Joint stiffness sweep: g = value x 3EI/L^3 on DOFs 1, 2 and value x EI/L on DOF 6
    (EA/L would overflow at value = 1e300; the axial joint is 530 times softer
    relative to the bar than the transverse one)."""
    e, i, length = 2.0e11, 1.0e-4, 4.0
    kt = 3 * e * i / length**3
    return _cantilever(scaled(value, kt), scaled(value, kt), scaled(value, e * i / length),
                       factor='joint g = %s x (3EI/L^3, 3EI/L^3, EI/L) on DOFs 1, 2, 6' % value)


def contrast(value):
    """Stiffness contrast: part II has E_II = value x E_I, RIGID joint."""
    return _cantilever(None, None, None, e2=2.0e11 * float(value), factor='RIGID joint, E_II / E_I = %s' % value)


def slender(value):
    """Slender member: radius of gyration L / value (A fixed), RIGID joint."""
    a, length = 1.0e-2, 4.0
    r = length / float(value)
    return _cantilever(None, None, None, a=a, inertia=a * r * r,
                       factor='RIGID joint, slenderness L / r = %s' % value)


def hinge(value):
    """Near-mechanism: translations RIGID, rotational g6 = value x EI/L (0: a hinge)."""
    e, i, length = 2.0e11, 1.0e-4, 4.0
    return _cantilever(None, None, scaled(value, e * i / length), factor='joint RIGID on DOFs 1, 2; g6 = %s x EI/L' % value)


def frame3d(value):
    """3D frame: column (Z), girder (X), arm (Y) of B33, two oblique joints with
    g = value x (3EIz/L^3, EIz/L) x (1, 2, 0.5) on local DOFs 1-3 and 4-6."""
    e, nu, a, iy, iz, j = 2.0e11, 0.3, 1.0e-2, 1.0e-4, 2.0e-4, 1.5e-4
    lg = 4.0
    kt, kr = 3 * e * iz / lg**3, e * iz / lg
    mult = [1.0, 2.0, 0.5]
    gt = [None if value == RIGID else scaled(value, kt) * c for c in mult]
    gr = [None if value == RIGID else scaled(value, kr) * c for c in mult]
    members = [('COL', [0.0, 0.0, 0.0], [0.0, 0.0, 3.0], 6),
               ('GIRD', [0.0, 0.0, 3.0], [lg, 0.0, 3.0], 8),
               ('ARM', [lg, 0.0, 3.0], [lg, 2.0, 3.0], 4)]
    parts = []
    segs = []
    f1 = exact.frame_axes([1.0, 1.0, 0.0], [0.0, 1.0, 1.0])
    f2 = exact.frame_axes([0.0, 1.0, 1.0], [1.0, 0.0, 0.2])
    try:
        for k, (name, x0, x1, n) in enumerate(members):
            pts = [[x0[c] + (x1[c] - x0[c]) * s / n for c in range(3)] for s in range(n + 1)]
            parts.append('*SUBSTRUCTURE, NAME=%s\n*NODE\n%s\n*ELEMENT, TYPE=B33, ELSET=B\n%s\n'
                         '*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r, %r, %r\n*END SUBSTRUCTURE'
                         % (name, '\n'.join('%d, %r, %r, %r' % (s + 1, *p) for s, p in enumerate(pts)),
                            _line_elements(1, n), a, iy, iz, j))
            if k == 1:
                segs.append(exact.joint_segment(x0, gt, gr, f1))
            elif k == 2:
                segs.append(exact.joint_segment(x0, gt, gr, f2))
            segs += [exact.beam_segment(pts[s], pts[s + 1], e, nu, a, iy, iz, j) for s in range(n)]
        load_f, load_m = [1.0e3, -2.0e3, 3.0e3], [500.0, 0.0, -400.0]
        ex = exact.chain_tip(segs, members[2][2], load_f, load_m)
    except ZeroDivisionError:
        ex = None
    load_f, load_m = [1.0e3, -2.0e3, 3.0e3], [500.0, 0.0, -400.0]

    def joint(master):
        return '\n'.join(' %d, 1, %d, %d, %s' % (master, d, d, g_text((gt + gr)[d - 1])) for d in range(1, 7))
    loads = '\n'.join(' ARM.5, %d, %r' % (d + 1, v) for d, v in enumerate(load_f + load_m) if v != 0.0)
    subst = dict(factor=value, E=repr(e), nu=repr(nu), parts='\n'.join(parts), joint1=joint(7), joint2=joint(9),
                 loads=loads)
    return Case('frame3d', subst, ('ARM', 5), ex)


G_VALUES = ['0', '1e-6', '1e-3', '1', '1e3', '1e6', '1e8', '1e10', '1e12', '1e14', '1e16', '1e20', '1e50',
            '1e100', '1e200', '1e300', RIGID]

CASES = {
    'cantilever': (cantilever, G_VALUES),
    'frame3d': (frame3d, G_VALUES),
    'contrast': (contrast, ['1e-12', '1e-9', '1e-6', '1e-3', '1', '1e3', '1e6', '1e9', '1e12']),
    'slender': (slender, ['10', '100', '1e3', '1e4', '1e5', '1e6']),
    'hinge': (hinge, ['1', '1e-3', '1e-6', '1e-8', '1e-10', '1e-12', '1e-14', '1e-16', '0']),
}
