#!/usr/bin/env python3
"""*PRE-TENSION SECTION against closed forms, and its deck errors.

usage: check_pretension.py SUPERJOIN OUTDIR

bar.inp: a bar of two C3D8 blocks (x from 0 to L = 2, section A = 1, E = 210000)
cut at x = 1 by a pretension section, both ends held in x (symmetry planes
y = 0, z = 0). A force F = 1000 on the pretension node gives the uniform stress
sxx = F/A in both blocks and the gap d = F L/(E A) on the node's DOF 1; a
prescribed gap d = 0.01 gives the force d E A/L, the stress d E/L. The error
decks must stop with `file:line: error:` naming the card's line: a node
surface, a pretension node that belongs to an element, a surface without faces.
"""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
E, L, A = 210000.0, 2.0, 1.0
CARD_LINE = 34   # the *PRE-TENSION SECTION line of bar.inp


def run(binary, outdir, job, text):
    with open(os.path.join(outdir, job + '.inp'), 'w') as f:
        f.write(text)
    return subprocess.run([binary, '-i', job], cwd=outdir, capture_output=True, text=True)


def dat_values(path, title):
    """Rows of the first block whose title starts with `title`: lists of floats."""
    rows, on = [], False
    for line in open(path):
        if line.strip().startswith(title):
            on = True
            continue
        if on and line.strip():
            if not re.match(r'\s*\d', line):
                break
            rows.append([float(w) for w in line.split()])
    return rows


def check(name, got, want, tol=1e-9):
    ok = abs(got - want) <= tol*max(1.0, abs(want))
    print(f"  {'ok  ' if ok else 'FAIL'} {name}: {got:.9g} (closed form {want:.9g})")
    return [] if ok else [name]


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    base = open(os.path.join(HERE, 'bar.inp')).read()
    failures = []
    F = 1000.0
    cases = {'force': (base, F/A, F*L/(E*A)),
             'gap': (base.replace('*CLOAD\n99, 1, 1000.\n', '*BOUNDARY\n99, 1, 1, 0.01\n'),
                     0.01*E/L, 0.01)}
    for job, (text, sxx, gap) in cases.items():
        proc = run(binary, outdir, job, text)
        if proc.returncode != 0:
            print(f'  FAIL {job}: status {proc.returncode}: {proc.stderr.strip()}')
            failures.append(job)
            continue
        dat = os.path.join(outdir, job + '.dat')
        u = dat_values(dat, 'displacements')
        s = dat_values(dat, 'stresses')
        failures += check(job + ' gap on DOF 1 of the pretension node', u[0][1], gap, 1e-6)
        failures += check(job + ' sxx, smallest over the 16 points', min(r[2] for r in s), sxx)
        failures += check(job + ' sxx, largest over the 16 points', max(r[2] for r in s), sxx)
        failures += check(job + ' other components, largest', max(abs(v) for r in s for v in r[3:]), 0.0, 1e-9*sxx)
    errors = {'node_surface': (base.replace('*SURFACE, NAME=CUT\n1, S4\n', '*SURFACE, NAME=CUT, TYPE=NODE\n2\n'),
                               'is a node surface'),
              'node_in_element': (base.replace('NODE=99', 'NODE=2'), 'belongs to an element'),
              'empty_surface': (base.replace('*SURFACE, NAME=CUT\n1, S4\n', '*ELSET, ELSET=NONE\n'
                                             '*SURFACE, NAME=CUT\nNONE, S4\n'), 'has no faces')}
    for job, (text, words) in errors.items():
        line = CARD_LINE + (1 if job == 'empty_surface' else 0)
        proc = run(binary, outdir, job, text)
        want = f'{job}.inp:{line}: error: *PRE-TENSION SECTION'
        ok = proc.returncode == 1 and want in proc.stderr and words in proc.stderr
        print(f"  {'ok  ' if ok else 'FAIL'} {job}: {proc.stderr.strip().splitlines()[0] if proc.stderr else ''}")
        if not ok:
            failures.append(job)
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
