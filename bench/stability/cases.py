"""Stress-test structures for sweep.py.

A case turns one value of its swept variable into the substitutions of its deck
template (templates/NAME.deck.in, Python str.format fields), the probe node
whose six displacements are compared, and their exact values (None when the
value makes the structure a mechanism: then exit status 3 is the right answer).

To add a structure: write templates/<name>.deck.in, add a function returning
Case(...) below and register it in CASES with its default values.

A case without a closed form (the stiffened panel) names a reference deck in
extra['reference_deck'] instead: sweep.py solves it once with dense LAPACK and
takes the probe's displacements as the exact answer for the values at or above
extra['judged_from'] (and RIGID); below, where the joint's own compliance is
part of the answer, the run is reported ('compliant') but not judged.
"""
import math
import os
import sys
from dataclasses import dataclass, field

import exact

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                'tests', 'shells'))
import shellgen  # noqa: E402

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
                factor='', n_load=5000.0, p_load=-1000.0, etype='B23'):
    """Two-part B23 (or B21: Timoshenko, shear stiffness G A) cantilever along X,
    joint at mid-length, tip load (N, P)."""
    half = length / 2
    subst = dict(nel=nel, L=length, factor=factor, E1=repr(e1), E2=repr(e2), A=repr(a), I=repr(inertia),
                 etype=etype,
                 nodes_I=_line_nodes(1, 0.0, half, nel), elements_I=_line_elements(1, nel),
                 nodes_II=_line_nodes(1, half, length, nel), elements_II=_line_elements(1, nel),
                 joint_I=nel + 1, tip=nel + 1, g1=g_text(g1), g2=g_text(g2), g6=g_text(g6),
                 N=repr(n_load), P=repr(p_load))
    try:
        def shear(e):
            k = e / (2 * 1.3) * a
            return (k, k) if etype == 'B21' else None
        segs = [exact.beam_segment([half * i / nel, 0, 0], [half * (i + 1) / nel, 0, 0], e1, 0.3, a,
                                   inertia, inertia, inertia, shear=shear(e1)) for i in range(nel)]
        segs.append(exact.joint_segment([half, 0, 0], [g1, g2, None], [None, None, g6]))
        segs += [exact.beam_segment([half + half * i / nel, 0, 0], [half + half * (i + 1) / nel, 0, 0], e2,
                                    0.3, a, inertia, inertia, inertia, shear=shear(e2)) for i in range(nel)]
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


def timoshenko(value):
    """Joint stiffness sweep on a deep two-part B21 (Timoshenko) cantilever (L/r = 12.6,
    shear 5 % of the tip deflection): g = value x 3EI/L^3 on DOFs 1, 2 and value x EI/L on 6."""
    e, i, length = 2.0e11, 1.0e-3, 4.0
    kt = 3 * e * i / length**3
    return _cantilever(scaled(value, kt), scaled(value, kt), scaled(value, e * i / length), inertia=i,
                       etype='B21', factor='B21 joint g = %s x (3EI/L^3, 3EI/L^3, EI/L) on DOFs 1, 2, 6' % value)


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
    return _frame3d(value, [[0.0, 0.0, 0.0], [0.0, 0.0, 3.0], [4.0, 0.0, 3.0]],
                    [[0.0, 0.0, 3.0], [4.0, 0.0, 3.0], [4.0, 2.0, 3.0]], 'frame3d')


def eccentric(value):
    """The 3D frame of frame3d with eccentric joints (*CONTACT, OFFSET=RIGID): the
    girder starts 0.2, 0.3, 0.4 m away from the column top and the arm 0.5, 0.1,
    -0.3 m away from the girder's end; the slave hangs on a rigid arm from the
    master, the joint's springs sit at the slave end (exact.joint_segment there)."""
    return _frame3d(value, [[0.0, 0.0, 0.0], [0.2, 0.3, 3.4], [4.7, 0.4, 3.1]],
                    [[0.0, 0.0, 3.0], [4.2, 0.3, 3.4], [4.7, 2.4, 3.1]], 'eccentric')


def _frame3d(value, starts, ends, template):
    e, nu, a, iy, iz, j = 2.0e11, 0.3, 1.0e-2, 1.0e-4, 2.0e-4, 1.5e-4
    lg = 4.0
    kt, kr = 3 * e * iz / lg**3, e * iz / lg
    mult = [1.0, 2.0, 0.5]
    gt = [None if value == RIGID else scaled(value, kt) * c for c in mult]
    gr = [None if value == RIGID else scaled(value, kr) * c for c in mult]
    members = [('COL', starts[0], ends[0], 6),
               ('GIRD', starts[1], ends[1], 8),
               ('ARM', starts[2], ends[2], 4)]
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
    return Case(template, subst, ('ARM', 5), ex)


def panel(value, n=8):
    """Shell joined to a beam: S4 panel (shellgen.stiffened_panel: a = 1, t = 0.01,
    D = 1, SS edges, pressure 1) with a B33 rib along y = a/2 in a substructure of
    its own, joined node by node on all six DOFs by g = value x k_t on the
    translations and value x k_t a^2 on the rotations, k_t = 86.2 D/a^2 the
    panel's stiffness under a central point load (Levy series).  Exact answer
    for RIGID and large g: the same panel with the rib on the plate's own nodes
    (shellgen 'SHARED'); its difference from a finite-g answer is the joint's
    compliance, 0.32 / value relative (measured: 3.24e-7 at 1e6, 3.24e-11 at
    1e10), so values from 1e12 on (3e-13) are judged against it.  Probe: the
    plate node at x = a/4 on the rib line (w and the slope about y are nonzero).
    g = 0 is no mechanism here: the free rib is unloaded, so the answer is the
    bare plate (shellgen.square_plate), judged against it."""
    a = shellgen.PLATE_A
    kt = 1.0 / (shellgen.levy_ss_point() * a * a)
    kr = kt * a * a
    plate = shellgen.Part('PANEL')
    nid = shellgen.grid(plate, n, n, lambda s, t: (s * a, t * a, 0.0), 'S4')
    edge = sorted(nid(i, j) for j in range(n + 1) for i in range(n + 1) if i in (0, n) or j in (0, n))
    mid = n // 2
    line = [nid(i, mid) for i in range(n + 1)]
    gt, gr = scaled(value, kt), scaled(value, kr)
    contacts = []
    for i in range(n + 1):
        contacts.append(' %d, %d, 1, 3, %s' % (line[i], i + 1, g_text(gt)))
        contacts.append(' %d, %d, 4, 6, %s' % (line[i], i + 1, g_text(gr)))
    subst = dict(n=n, factor='joint g = %s x (k_t on u, k_t a^2 on theta), k_t = %.6g' % (value, kt),
                 E=repr(shellgen.PLATE_E), nu=repr(shellgen.PLATE_NU), t=repr(shellgen.PLATE_T),
                 panel_nodes='\n'.join(' %d, %r, %r, %r' % (k, *x) for k, x in sorted(plate.nodes.items())),
                 panel_elements='\n'.join(' %d, %s' % (e, ', '.join(map(str, ns))) for e, _, ns in plate.elems),
                 edge='\n'.join(' ' + ', '.join(map(str, edge[k:k + 16])) for k in range(0, len(edge), 16)),
                 rib_nodes='\n'.join(' %d, %r, %r, 0.0' % (i + 1, i * a / n, 0.5 * a) for i in range(n + 1)),
                 rib_elements='\n'.join(' %d, %d, %d' % (i + 1, i + 1, i + 2) for i in range(n)),
                 rib_section='1.0e-3, 2.0e-7, 1.0e-7, 5.0e-8', contacts='\n'.join(contacts))
    if value != RIGID and float(value) == 0.0:
        # g = 0: the rib floats free but carries no load; superjoin leaves unknowns that
        # no load reaches at zero ("coupled to no load"), so the plate is the bare plate
        ref = shellgen.square_plate(n, 'S4', 'SS', 'UNIFORM').deck.replace('PLATE', 'PANEL')
    else:
        ref = shellgen.stiffened_panel(n, 'SHARED').deck
    return Case('panel', subst, ('PANEL', line[n // 4]), [], extra=dict(reference_deck=ref, judged_from=1.0e12))


def thickjoint(value, n=8, a_over_t=10, etype='S4R'):
    """Two thick-shell parts joined: a square S4R plate (a = 1, a/t = 10, D = 1,
    hard simply supported edges with u, v held, pressure 1) cut at x = a/2 into
    substructures L and R, joined node by node on all six DOFs by g = value x
    k_t on the translations and value x k_t a^2 on the rotations (k_t as for
    the panel).  Exact answer for RIGID and large g: the one-piece plate on the
    same mesh (its substructure named L, the probe's id kept); for g = 0 the
    two halves apart (each is supported on three edges, no mechanism).  The
    joint's compliance is about 1/value relative, so values from 1e12 on are
    judged.  Probe: the L node on the cut at y = a/4 (w, both slopes nonzero).
    The two cut nodes on the supported edges y = 0, a are held on the master
    side only: with the supports on both sides of a joined DOF as well, TRANSFORM
    reports the slave's rotation (DOF 4, about the edge normal, nearly free at
    the corner) numerically singular from g = 1e12 k on (the same with S4).
    etype='S8R' (case thickjoint8): the same plate of eight-node shells, each
    on a 2 x 2 block of the n x n node grid (the block centres are no nodes)."""
    a = shellgen.PLATE_A
    t = a / a_over_t
    e = 12.0 * (1.0 - shellgen.PLATE_NU ** 2) / t ** 3
    kt = 1.0 / (shellgen.levy_ss_point() * a * a)
    kr = kt * a * a
    h = n // 2

    def lid(i, j):
        return 1 + j * (h + 1) + i

    def rid(i, j):                      # i = h .. n
        return 1001 + j * (h + 1) + (i - h)
    left = shellgen.Part('L')
    right = shellgen.Part('R')
    quad8 = etype == 'S8R'
    for j in range(n + 1):
        for i in range(h + 1):
            if quad8 and i % 2 and j % 2:
                continue
            left.nodes[lid(i, j)] = (i * a / n, j * a / n, 0.0)
            right.nodes[rid(h + i, j)] = ((h + i) * a / n, j * a / n, 0.0)
    k = 1
    for j in range(0, n, 2 if quad8 else 1):
        for i in range(0, h, 2 if quad8 else 1):
            if quad8:
                def block(f):
                    return (f(i, j), f(i + 2, j), f(i + 2, j + 2), f(i, j + 2),
                            f(i + 1, j), f(i + 2, j + 1), f(i + 1, j + 2), f(i, j + 1))
                left.elems.append((k, 'S8R', block(lid)))
                right.elems.append((1000 + k, 'S8R', block(lambda ii, jj: rid(h + ii, jj))))
                k += 1
                continue
            left.elems.append((k, 'S4R', (lid(i, j), lid(i + 1, j), lid(i + 1, j + 1), lid(i, j + 1))))
            right.elems.append((1000 + k, 'S4R', (rid(h + i, j), rid(h + i + 1, j), rid(h + i + 1, j + 1),
                                                  rid(h + i, j + 1))))
            k += 1
    # hard simple support: w, u, v and the rotation about the edge normal
    left.nsets['XE'] = [lid(0, j) for j in range(n + 1)]
    left.nsets['YE'] = [lid(i, j) for i in range(h + 1) for j in (0, n)]
    right.nsets['XE'] = [rid(n, j) for j in range(n + 1)]
    right.nsets['YE'] = [rid(i, j) for i in range(h + 1, n + 1) for j in (0, n)]
    bnd = []
    for p in ('L', 'R'):
        bnd += [(p + '.XE', 1, 4), (p + '.YE', 1, 3), (p + '.YE', 5, 5)]
    loads = [('L.ALL', 'P', 1.0), ('R.ALL', 'P', 1.0)]
    gt, gr = scaled(value, kt), scaled(value, kr)
    contacts = []
    if value == RIGID or float(value) != 0.0:
        contacts.append('*CONTACT, NAME=JOINT, MASTER=L, SLAVE=R')
        for j in range(n + 1):
            contacts.append(' %d, %d, 1, 3, %s' % (lid(h, j), rid(h, j), g_text(gt)))
            contacts.append(' %d, %d, 4, 6, %s' % (lid(h, j), rid(h, j), g_text(gr)))
    title = 'thick-shell joint, g = %s x (k_t on u, k_t a^2 on theta), k_t = %.6g' % (value, kt)
    deck = shellgen.deck_text(title, [left, right], e, shellgen.PLATE_NU, t, bnd, (), loads, contacts)
    if value != RIGID and float(value) == 0.0:
        ref = deck
    else:
        one = shellgen.Part('L')
        one.nodes.update(left.nodes)
        ren = {rid(i, j): (lid(h, j) if i == h else rid(i, j)) for j in range(n + 1) for i in range(h, n + 1)}
        one.nodes.update({ren[i]: x for i, x in right.nodes.items() if ren[i] == i})
        one.elems = left.elems + [(e_, t_, tuple(ren[v] for v in ns)) for (e_, t_, ns) in right.elems]
        one.nsets['XE'] = left.nsets['XE'] + right.nsets['XE']
        one.nsets['YE'] = left.nsets['YE'] + [ren[v] for v in right.nsets['YE']]
        ref = shellgen.deck_text(title + ' (one piece)', [one], e, shellgen.PLATE_NU, t,
                                 [('L.XE', 1, 4), ('L.YE', 1, 3), ('L.YE', 5, 5)], (), [('L.ALL', 'P', 1.0)])
    return Case('thickjoint', dict(deck=deck), ('L', lid(h, n // 4)), [],
                extra=dict(reference_deck=ref, judged_from=1.0e12))


G_VALUES = ['0', '1e-6', '1e-3', '1', '1e3', '1e6', '1e8', '1e10', '1e12', '1e14', '1e16', '1e20', '1e50',
            '1e100', '1e200', '1e300', RIGID]

CASES = {
    'cantilever': (cantilever, G_VALUES),
    'frame3d': (frame3d, G_VALUES),
    'eccentric': (eccentric, ['0'] + G_VALUES[G_VALUES.index('1'):]),
    'panel': (panel, G_VALUES),
    'thickjoint': (thickjoint, G_VALUES),
    'thickjoint8': (lambda value: thickjoint(value, etype='S8R'), G_VALUES),
    'timoshenko': (timoshenko, G_VALUES),
    'contrast': (contrast, ['1e-12', '1e-9', '1e-6', '1e-3', '1', '1e3', '1e6', '1e9', '1e12']),
    'slender': (slender, ['10', '100', '1e3', '1e4', '1e5', '1e6']),
    'hinge': (hinge, ['1', '1e-3', '1e-6', '1e-8', '1e-10', '1e-12', '1e-14', '1e-16', '0']),
}
