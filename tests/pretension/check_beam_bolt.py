#!/usr/bin/env python3
"""*PRE-TENSION SECTION, ELEMENT= (a beam bolt) against closed forms, and its deck errors.

usage: check_beam_bolt.py SUPERJOIN OUTDIR

bolt.inp: the pretension element 1 (B31, nodes 1-2) removed as CalculiX does, its
ends tied by n.(u2 - u1) + u99 = 0; the shank 2-3 (EA/L: k_b = 210000*100/0.9), the
clamped sleeve 1-3 (k_s = 210000*400/1), node 1 held. A force F = 1000 on node 99
gives N = F in the shank and -F in the sleeve, the gap u99 = F/k_b + F/k_s; a
prescribed gap d = 0.01 gives N = d k_eff, 1/k_eff = 1/k_b + 1/k_s (the removed
element adds no compliance). ccx 2.20 on the same decks prints the same values to
its 7 digits (u2 = -5.476190E-05, shank 1.000000E+01, sleeve -2.500000E+00; gap:
shank 1.826087E+03, sleeve -4.565217E+02). The variant 'beam_shank' makes the shank a
B31 (same area): its axial stress is N/A too. An *EL PRINT of a set holding the
removed element prints the others only (as ccx). The error decks must stop with
`file:line: error:` on the card's line.

'planar': the same bolt in the XY plane (B21 bolt, T2D2 shank and sleeve) along an
axis at 30 degrees, nodes 2 and 3 held across it in a *TRANSFORM system, and the
normal given with an out-of-plane component (c, s, 0.8): a planar bolt's normal is
its in-plane part made unit, so the closed forms are those of 'force' (the whole
normal, cut to two components without that, would scale the gap by 0.73). ccx 2.20
cannot check this one: it expands the planar elements to 3D and leaves the
out-of-plane motion free (its answer is of order 1e9).
"""
import math
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
E, AB, LB, AS, LS = 210000.0, 100.0, 0.9, 400.0, 1.0
KB, KS = E*AB/LB, E*AS/LS
CARD_LINE = 27   # the *PRE-TENSION SECTION line of bolt.inp


def run(binary, outdir, job, text):
    with open(os.path.join(outdir, job + '.inp'), 'w') as f:
        f.write(text)
    return subprocess.run([binary, '-i', job], cwd=outdir, capture_output=True, text=True)


def blocks(path):
    """{title start: rows of floats} of every block of a .dat (titles cut at ' and time')."""
    out, title = {}, None
    for line in open(path):
        s = line.strip()
        if not s:
            continue
        if re.match(r'-?\d', s):
            if title is not None:
                out[title].append([float(w) for w in s.split() if w != "L"])   # L: a *TRANSFORM system
        else:
            title = s.split(' and time')[0]
            out[title] = []
    return out


def check(name, got, want, tol=1e-6):
    ok = abs(got - want) <= tol*max(1.0, abs(want))
    print(f"  {'ok  ' if ok else 'FAIL'} {name}: {got:.9g} (closed form {want:.9g})")
    return [] if ok else [name]


def check_case(binary, outdir, job, text, n_shank, gap):
    proc = run(binary, outdir, job, text)
    if proc.returncode != 0:
        print(f'  FAIL {job}: status {proc.returncode}: {proc.stderr.strip()}')
        return [job]
    b = blocks(os.path.join(outdir, job + '.dat'))
    u = {int(r[0]): r[1:] for r in b['displacements (vx,vy,vz) for set NALL']}
    title = 'stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set '
    f = check(job + ' gap u99', u[99][0], gap)
    f += check(job + ' u3 (sleeve shortening)', u[3][0], -n_shank/KS)
    f += check(job + ' u2 = u3 - N/k_b', u[2][0], -n_shank/KS - n_shank/KB)
    for name, want in (('SHANK', n_shank/AB), ('SLEEVE', -n_shank/AS)):
        rows = b[title + name]
        if not rows:   # a B31 shank: its fibre stresses sxx (last column) are in the listing
            rows = [[0, 0, float(line.split()[-1])] for line in open(os.path.join(outdir, job + '.lst'))
                    if re.match(r'\s+MAIN\s+2\s+B31\s', line)]
        f += check(f'{job} {name} sxx, smallest', min(r[2] for r in rows), want)
        f += check(f'{job} {name} sxx, largest', max(r[2] for r in rows), want)
    elems = sorted({int(r[0]) for r in b[title + 'EALL']})
    ok = elems == ([3] if job == 'beam_shank' else [2, 3])   # a B31's S is in the listing only
    print(f"  {'ok  ' if ok else 'FAIL'} {job} EALL prints elements {elems} (the bolt element 1 removed)")
    return f + ([] if ok else [job + ' EALL'])


def planar_deck(base):
    """bolt.inp in the XY plane along an axis at 30 degrees (see the module's text)."""
    c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
    text = base.replace('TYPE=B31', 'TYPE=B21').replace('TYPE=T3D2', 'TYPE=T2D2')
    text = text.replace('2, 0.1, 0., 0.\n', f'2, {0.1*c!r}, {0.1*s!r}, 0.\n')
    text = text.replace('3, 1., 0., 0.\n', f'3, {c!r}, {s!r}, 0.\n').replace('99, 5., 5., 5.\n', '99, 5., 5., 0.\n')
    text = text.replace('10., 10.\n0., 0., 1.\n', '10., 10.\n')
    text = text.replace('NODE=99\n', f'NODE=99\n{c!r}, {s!r}, 0.8\n')
    text = text.replace('*NSET, NSET=PN\n99\n', '*NSET, NSET=PN\n99\n*NSET, NSET=AX\n2, 3\n')
    text = text.replace('1, 1, 3\n2, 2, 3\n3, 2, 3\n', '1, 1, 2\n*TRANSFORM, NSET=AX\n'
                        f'{c!r}, {s!r}, 0., {-s!r}, {c!r}, 0.\n*BOUNDARY\n2, 2\n3, 2\n')
    assert text.count('TYPE=T2D2') == 2 and '*TRANSFORM' in text and ', 0.8\n' in text
    return text, c, s


def check_planar(binary, outdir, base, F):
    """The planar bolt: displacements along the axis (nodes 2, 3 in their *TRANSFORM
    system), the gap, and the axial stress N/A seen in global axes."""
    text, c, s = planar_deck(base)
    proc = run(binary, outdir, 'planar', text)
    if proc.returncode != 0:
        print(f'  FAIL planar: status {proc.returncode}: {proc.stderr.strip()}')
        return ['planar']
    b = blocks(os.path.join(outdir, 'planar.dat'))
    u = {int(r[0]): r[1:] for r in b['displacements (vx,vy,vz) for set NALL']}
    f = check('planar gap u99', u[99][0], F/KB + F/KS)
    f += check('planar u3 along the axis', u[3][0], -F/KS)
    f += check('planar u2 along the axis', u[2][0], -F/KS - F/KB)
    title = 'stresses (elem, integ.pnt.,sxx,syy,szz,sxy,sxz,syz) for set '
    for name, sigma in (('SHANK', F/AB), ('SLEEVE', -F/AS)):
        rows = b[title + name]
        for col, want, what in ((2, sigma*c*c, 'sxx'), (3, sigma*s*s, 'syy'), (5, sigma*c*s, 'sxy')):
            f += check(f'planar {name} {what}, smallest', min(r[col] for r in rows), want)
            f += check(f'planar {name} {what}, largest', max(r[col] for r in rows), want)
    off = run(binary, outdir, 'planar_off', text.replace(f'NODE=99\n{c!r}, {s!r}, 0.8\n', 'NODE=99\n0., 0., 1.\n'))
    ok = off.returncode == 1 and 'planar_off.inp:26: error: ' in off.stderr and \
        "the normal has no component in the model's plane" in off.stderr
    print(f"  {'ok  ' if ok else 'FAIL'} planar_off: {off.stderr.strip().splitlines()[0] if off.stderr else ''}")
    return f + ([] if ok else ['planar_off'])


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    base = open(os.path.join(HERE, 'bolt.inp')).read()
    F, d = 1000.0, 0.01
    keff = 1.0/(1.0/KB + 1.0/KS)
    gap_deck = base.replace('*CLOAD\n99, 1, 1000.\n', '*BOUNDARY\n99, 1, 1, 0.01\n')
    beam = base.replace('*ELEMENT, TYPE=T3D2, ELSET=SHANK', '*ELEMENT, TYPE=B31, ELSET=SHANK').replace(
        '*SOLID SECTION, ELSET=SHANK, MATERIAL=STEEL\n100.\n',
        '*BEAM SECTION, ELSET=SHANK, MATERIAL=STEEL, SECTION=RECT\n10., 10.\n0., 0., 1.\n').replace(
        '3, 2, 3\n', '3, 2, 4\n')
    assert gap_deck != base and beam.count('TYPE=B31') == 2 and '3, 2, 4' in beam
    failures = check_case(binary, outdir, 'force', base, F, F/KB + F/KS)
    failures += check_case(binary, outdir, 'gap', gap_deck, d*keff, d)
    failures += check_case(binary, outdir, 'beam_shank', beam, F, F/KB + F/KS)
    failures += check_planar(binary, outdir, base, F)
    card = '*PRE-TENSION SECTION, ELEMENT=1, NODE=99\n'
    errors = {'both': (base.replace(card, '*SURFACE, NAME=CUT\n1, S1\n' + card.replace('ELEMENT=1', 'SURFACE=CUT, '
                                                                                      'ELEMENT=1')),
                       'takes one of SURFACE=', 2),
              'set_of_three': (base.replace('ELEMENT=1', 'ELEMENT=EALL'), 'holds 3 elements', 0),
              'undefined': (base.replace('ELEMENT=1', 'ELEMENT=7'), 'undefined element 7', 0),
              'node_in_element': (base.replace('NODE=99', 'NODE=3'), 'belongs to an element', 0),
              'coincident': (base.replace('2, 0.1, 0., 0.\n', '2, 0., 0., 0.\n'), 'has coincident nodes', 0),
              'not_two_nodes': (base.replace('3, 1., 0., 0.\n', '3, 1., 0., 0.\n4, 0.05, 0., 0.\n').replace(
                  '*ELEMENT, TYPE=B31, ELSET=PRE\n1, 1, 2\n', '*ELEMENT, TYPE=B32, ELSET=PRE\n1, 1, 4, 2\n'),
                  'is a B32 (ELEMENT= takes a 2-node beam or truss', 1)}
    for job, (text, words, shift) in errors.items():
        proc = run(binary, outdir, job, text)
        want = f'{job}.inp:{CARD_LINE + shift}: error: '
        ok = proc.returncode == 1 and want in proc.stderr and words in proc.stderr
        print(f"  {'ok  ' if ok else 'FAIL'} {job}: {proc.stderr.strip().splitlines()[0] if proc.stderr else ''}")
        if not ok:
            failures.append(job)
    # a *DLOAD on the bolt element goes with it: the listing says so
    proc = run(binary, outdir, 'dload', base.replace('*CLOAD\n', '*DLOAD\n1, P1, 5.\n*CLOAD\n'))
    with open(os.path.join(outdir, 'dload.lst')) as f:
        listing = ' '.join(f.read().split())
    said = proc.returncode == 0 and 'its 1 distributed load (*DLOAD, temperature) went with it' in listing
    print(f"  {'ok  ' if said else 'FAIL'} dload: the listing notes the bolt element's distributed load")
    if not said:
        failures.append('dload')
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
