#!/usr/bin/env python3
"""Eccentric contacts (*CONTACT, OFFSET=RIGID): pairs of decks that must give the
same displacements to round-off although the transform treats them differently.

usage: check_equivalent.py SUPERJOIN SOURCE_DIR WORK_DIR

Each pair is made from a verification deck of tests/decks by text substitution:
  flipped    master and slave swapped (the tree child is then the master: the
             arm enters the master's own map, u_m = u_s - theta_m x r - delta)
  loop       the stiffener's end held along x as well as the strip's: the two
             supports and the eccentric weld close a RIGID loop whose constraint
             (theta_z = 0 through the arm) is eliminated, against the same
             restraint written directly as a rotation support
  duplicate  a second identical eccentric contact: a redundant RIGID loop
  plain      finite g on every DOF, TRANSFORM (g on the diagonal of delta)
             against PENALTY (the eccentric spring assembled in plain form
             on u_m, theta_m and u_s); no large number is involved, so the two
             agree to round-off
  condensed  --condense yes against no condensation (the master's rotations are
             boundary DOFs of its substructure)
  solvers    lapack, cholmod and umfpack
  equation   the rigid arm written as three *EQUATIONs (equation_knee.deck)
             against OFFSET=RIGID, and that deck condensed and under PENALTY
             (equations are eliminated exactly under both formulations)
"""
import csv
import os
import subprocess
import sys

TOL = 1.0e-10


def solve(exe, deck_text, work, tag, args=()):
    path = os.path.join(work, tag + '.deck')
    with open(path, 'w') as f:
        f.write(deck_text)
    out = os.path.join(work, tag)
    r = subprocess.run([exe, '-q', path, '-o', out + '.lst', '--csv', out] + list(args),
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError('%s: exit %d\n%s' % (tag, r.returncode, r.stderr))
    rows = {}
    with open(os.path.join(out, 'displacements.csv')) as f:
        for row in csv.DictReader(f):
            rows[(row['step'], row['substructure'], row['node'])] = [
                float(row[k]) for k in ('u1', 'u2', 'u3', 'ur1', 'ur2', 'ur3')]
    return rows


def difference(a, b):
    if set(a) != set(b):
        return float('inf')
    scale = max(abs(x) for v in a.values() for x in v)
    return max(abs(x - y) for k in a for x, y in zip(a[k], b[k])) / scale


def replace(text, old, new):
    if old not in text:
        raise RuntimeError('pattern not found: %r' % old)
    return text.replace(old, new)


def main(argv):
    exe, src, work = argv[1:4]
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(src, 'decks', 'cranked_cantilever.deck')) as f:
        crank = f.read()
    with open(os.path.join(src, 'decks', 'offset_stiffener.deck')) as f:
        stiff = f.read()
    pairs = []
    flipped = replace(crank, 'MASTER=COL, SLAVE=GIRDER, OFFSET=RIGID', 'MASTER=GIRDER, SLAVE=COL, OFFSET=RIGID')
    flipped = replace(replace(flipped, '\n 3, 1, 1, 2, RIGID', '\n 1, 3, 1, 2, RIGID'),
                      '\n 3, 1, 6, 6, RIGID', '\n 1, 3, 6, 6, RIGID')
    pairs.append(('flipped', crank, (), flipped, ()))
    held = replace(stiff, '\n STRIP.1, 6, 6\n', '\n STRIP.1, 6, 6\n STRIP.5, 1, 1\n STIFF.5, 1, 1\n')
    held = replace(held, 'STRIP.5, 6, 1000.0', 'STRIP.5, 2, 1000.0')
    direct = replace(stiff, '\n STRIP.1, 6, 6\n', '\n STRIP.1, 6, 6\n STRIP.5, 1, 1\n STRIP.5, 6, 6\n')
    direct = replace(direct, 'STRIP.5, 6, 1000.0', 'STRIP.5, 2, 1000.0')
    pairs.append(('loop', held, (), direct, ()))
    dup = replace(crank, '*SUPPORT\n', '*CONTACT, NAME=J2, MASTER=COL, SLAVE=GIRDER, OFFSET=RIGID\n'
                  ' 3, 1, 1, 2, RIGID\n 3, 1, 6, 6, RIGID\n*SUPPORT\n')
    pairs.append(('duplicate', crank, (), dup, ()))
    soft = replace(replace(crank, '\n 3, 1, 1, 2, RIGID', '\n 3, 1, 1, 1, 3.0e8\n 3, 1, 2, 2, 1.0e8'),
                   '\n 3, 1, 6, 6, RIGID', '\n 3, 1, 6, 6, 2.0e6')
    pairs.append(('plain', soft, ('--formulation', 'transform'), soft, ('--formulation', 'penalty')))
    pairs.append(('condensed', crank, (), crank, ('--condense', 'yes')))
    with open(os.path.join(src, 'decks', 'equation_knee.deck')) as f:
        eqk = f.read()
    pairs.append(('equation', crank, (), eqk, ()))
    pairs.append(('equation condensed', eqk, (), eqk, ('--condense', 'yes')))
    pairs.append(('equation penalty', eqk, (), eqk, ('--formulation', 'penalty')))
    for solver in ('lapack', 'cholmod', 'umfpack'):
        pairs.append(('solver ' + solver, stiff, ('--solver', 'lapack'), stiff, ('--solver', solver)))
    fails = 0
    for name, a, aa, b, ba in pairs:
        tag = name.replace(' ', '_')
        try:
            ua = solve(exe, a, work, tag + '_a', aa)
            ub = solve(exe, b, work, tag + '_b', ba)
        except RuntimeError as e:
            print('FAIL: %s: %s' % (name, e))
            fails += 1
            continue
        d = difference(ua, ub)
        ok = d <= TOL
        fails += not ok
        print('%s: %s: max |difference| / max |u| = %.1e (tolerance %.0e)' % ('ok' if ok else 'FAIL', name, d, TOL))
    return 1 if fails else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
