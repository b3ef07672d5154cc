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

The copies of the cut's nodes are numbered as ccx 2.20 numbers them, whatever
the order of the *NODE lines: after the largest node id, the surface's faces
in turn, each face's nodes in CalculiX's face order, a node at its first
face. A 2 x 2 x 1 block of each solid type (linear and quadratic hexahedra,
tetrahedra, wedges) cut at x = 1, its *NODE lines in descending order: the
copies' coordinates in id order are those ccx 2.20 gave for the same decks
(COPIES; with `ccx` on the PATH, also against ccx itself, every solid type).
"""
import itertools
import os
import re
import shutil
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


# ccx 2.20's copies 501, 502, ... of the cut grid (cut_grid) per element type, each
# copy's coordinates doubled as three digits (x y z); '-rev': the surface's faces
# listed in the opposite order.
COPIES = {
    'C3D8': '220 200 202 222 240 242',
    'C3D8-rev': '240 220 222 242 200 202',
    'C3D20': '220 200 202 222 210 201 212 221 240 242 230 232 241',
    'C3D6': '220 200 202 222 240 242',
    'C3D15': '220 200 202 222 210 201 212 221 240 242 230 232 241',
    'C3D4': '200 222 220 202 242 240',
    'C3D10': '200 222 220 211 221 210 202 201 212 242 240 231 241 230 232',
}
EDGES = {'hex': [(1, 2), (2, 3), (3, 4), (4, 1), (5, 6), (6, 7), (7, 8), (8, 5), (1, 5), (2, 6), (3, 7), (4, 8)],
         'tet': [(1, 2), (2, 3), (3, 1), (1, 4), (2, 4), (3, 4)],
         'wedge': [(1, 2), (2, 3), (3, 1), (4, 5), (5, 6), (6, 4), (1, 4), (2, 5), (3, 6)]}
FACES = {'hex': [(1, 2, 3, 4), (5, 6, 7, 8), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 8, 4), (4, 8, 5, 1)],
         'tet': [(1, 2, 3), (1, 4, 2), (2, 4, 3), (3, 4, 1)],
         'wedge': [(1, 2, 3), (4, 5, 6), (1, 4, 5, 2), (2, 5, 6, 3), (3, 6, 4, 1)]}


def cut_grid(etype, reverse):
    """A 2 x 2 x 1 block of unit cells of etype, held at x = 0 and x = 2, cut at
    x = 1 by a pretension section on the faces of the elements beyond it (node
    500 the section's node); *NODE lines in descending id order."""
    fam = 'tet' if etype in ('C3D4', 'C3D10') else 'wedge' if etype in ('C3D6', 'C3D15') else 'hex'
    x = {1 + i + 3*j + 9*k: (i, j, k) for k in range(2) for j in range(3) for i in range(3)}
    def n(i, j, k):
        return 1 + i + 3*j + 9*k
    els = []
    for j in range(2):
        for i in range(2):
            c = [n(i, j, 0), n(i + 1, j, 0), n(i + 1, j + 1, 0), n(i, j + 1, 0),
                 n(i, j, 1), n(i + 1, j, 1), n(i + 1, j + 1, 1), n(i, j + 1, 1)]
            if fam == 'hex':
                els.append(c)
            elif fam == 'wedge':
                els += [[c[0], c[1], c[2], c[4], c[5], c[6]], [c[0], c[2], c[3], c[4], c[6], c[7]]]
            else:   # six tetrahedra along the cell's diagonal, each turned to a positive volume
                for perm in itertools.permutations(range(3)):
                    p, t = [0, 0, 0], [n(i, j, 0)]
                    for ax in perm:
                        p[ax] = 1
                        t.append(n(i + p[0], j + p[1], p[2]))
                    a, b, c2, d = ([x[q][m] - x[t[0]][m] for m in range(3)] for q in t)
                    if (b[0]*(c2[1]*d[2] - c2[2]*d[1]) - b[1]*(c2[0]*d[2] - c2[2]*d[0])
                            + b[2]*(c2[0]*d[1] - c2[1]*d[0])) < 0:
                        t[1], t[2] = t[2], t[1]
                    els.append(t)
    if etype in ('C3D20', 'C3D20R', 'C3D15', 'C3D10'):
        mid = {}
        for e in els:
            for a, b in EDGES[fam]:
                key = tuple(sorted((e[a - 1], e[b - 1])))
                if key not in mid:
                    mid[key] = 19 + len(mid)
                    x[mid[key]] = tuple((x[key[0]][m] + x[key[1]][m])/2 for m in range(3))
        els = [e + [mid[tuple(sorted((e[a - 1], e[b - 1])))] for a, b in EDGES[fam]] for e in els]
    x[500] = (9, 9, 9)
    surf = [(k, f) for k, e in enumerate(els, 1) for f, corners in enumerate(FACES[fam], 1)
            if all(x[e[c - 1]][0] == 1 for c in corners) and all(x[q][0] >= 1 for q in e)]
    if reverse:
        surf.reverse()
    lines = ['*NODE, NSET=NALL'] + [f'{i}, {float(x[i][0])}, {float(x[i][1])}, {float(x[i][2])}'
                                   for i in sorted(x, reverse=True)]
    lines.append(f'*ELEMENT, TYPE={etype}, ELSET=BLOCK')
    for k, e in enumerate(els, 1):   # at most 16 fields on a line, as ccx reads them
        lines.append(f'{k}, ' + ', '.join(map(str, e[:15])) + (',' if len(e) > 15 else ''))
        if len(e) > 15:
            lines.append(', '.join(map(str, e[15:])))
    lines += ['*MATERIAL, NAME=M', '*ELASTIC', '1000.0, 0.3', '*SOLID SECTION, ELSET=BLOCK, MATERIAL=M',
              '*NSET, NSET=ROOT'] + [str(i) for i in sorted(x) if x[i][0] == 0] + \
             ['*NSET, NSET=FAR'] + [str(i) for i in sorted(x) if x[i][0] == 2]
    lines += ['*SURFACE, NAME=CUT, TYPE=ELEMENT'] + [f'{k}, S{f}' for k, f in surf]
    lines += ['*PRE-TENSION SECTION, SURFACE=CUT, NODE=500', '1.0, 0.0, 0.0', '*BOUNDARY', 'ROOT, 1, 3',
              'FAR, 1, 3', '*STEP', '*STATIC', '*CLOAD', '500, 1, 5.0', '*NODE FILE', 'U', '*END STEP']
    return '\n'.join(lines) + '\n'


def doubled(v):
    return ''.join('%g' % (2*float(c)) for c in v)


def copies_superjoin(binary, outdir, job):
    csv_dir = os.path.join(outdir, job + '_csv')
    proc = subprocess.run([binary, '-q', job + '.inp', '-o', job + '.lst', '--csv', csv_dir], cwd=outdir,
                          capture_output=True, text=True)
    if proc.returncode != 0:
        return f'status {proc.returncode}: {proc.stderr.strip()}'
    rows = [r.split(',') for r in open(os.path.join(csv_dir, 'nodes.csv')).read().split('\n')[1:] if r]
    return ' '.join(doubled(r[2:5]) for r in sorted(rows, key=lambda r: int(r[1])) if int(r[1]) > 500)


def copies_ccx(outdir, job):
    try:
        subprocess.run(['ccx', '-i', job], cwd=outdir, capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return 'no answer from ccx within 60 s'
    co, on = {}, False
    for line in open(os.path.join(outdir, job + '.frd')):
        if line.startswith('    2C'):
            on = True
        elif on and line.startswith(' -3'):
            break
        elif on and line.startswith(' -1'):
            co[int(line[3:13])] = (line[13:25], line[25:37], line[37:49])
    return ' '.join(doubled(co[k]) for k in sorted(co) if k > 500)


def check_copy_order(binary, outdir):
    failures = []
    live = shutil.which('ccx') is not None
    cases = list(COPIES) + ([c for c in ('C3D8I', 'C3D8R', 'C3D20R', 'C3D20-rev', 'C3D10-rev', 'C3D15-rev')]
                            if live else [])
    for case in cases:
        etype, reverse = case.split('-')[0], case.endswith('-rev')
        job = 'copies_' + case.replace('-', '_')
        with open(os.path.join(outdir, job + '.inp'), 'w') as f:
            f.write(cut_grid(etype, reverse))
        got = copies_superjoin(binary, outdir, job)
        wants = ([('ccx 2.20, recorded', COPIES[case])] if case in COPIES else []) + \
                ([('ccx on the PATH', copies_ccx(outdir, job))] if live else [])
        for who, want in wants:
            ok = got == want
            print(f"  {'ok  ' if ok else 'FAIL'} {case} copies against {who}: {got}" +
                  ('' if ok else f' (want {want})'))
            if not ok:
                failures.append(f'{case} copies')
    return failures


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
    failures += check_copy_order(binary, outdir)
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
