#!/usr/bin/env python3
"""CalculiX GraphiX reads superjoin's .frd and reports superjoin's values.

usage: frd_cgx.py SUPERJOIN OUTDIR        (exit 77: cgx not installed, skipped)

For a truss (truss.inp), a beam (b31.inp), a plane (planestrain.inp) and a
shell model (shell1lin.inp, with *NODE FILE U, RF and *EL FILE S, E added in
its copy) of tests/ccx: `superjoin -i JOB --csv csv` writes JOB.frd, then
`cgx -bg JOB.fbd` reads it and prints every component of every dataset at
every node (`ds N e K` then `prnt se all`, a set of all nodes). The script
checks that
- cgx reads the file: its node and element counts, and one dataset per result
  block of the file (DISP, STRESS, TOSTRAIN, FORC);
- the values cgx prints (6 digits) equal the file's (5 digits) at every node,
  within 1e-5 of the component's largest magnitude;
- the file's displacements equal superjoin's displacements.csv (full
  precision) within 1e-5 of the largest one, so cgx shows the solution;
- frame2d (decks/frame2d.deck, *EL FILE S added): the FJOINT block (the
  contact elements' forces F1..F3 in their axes, at both of their nodes)
  equals csv/contact_forces.csv;
- ener_b31 (a B31 cantilever, *EL FILE SF added): the SECTFORC block (beam
  section forces in the columns of ccx's *EL FILE, SECTION FORCES) equals
  the closed form V2 = P, M1 = -P (L - x) at every node; sectforc_b32 (the
  same cantilever of four B32, *EL FILE SF added): the same, the middle nodes
  included; sectforc_b32q (four B32 simply supported, L = 1000, under their
  weight q = 1 along -y): V2 = q (L/2 - x), M1 = q x (L - x)/2 at every node,
  the middle nodes from the element's equilibrium (the mean of the ends missed
  q h^2/8 there, h the element's length; ccx 2.20's own SECTION FORCES of this
  deck are farther off: M1 = 51429 at the support, V2 = 2491 for 500);
- truss: the two bars at 45 degrees in the x-z plane have |SZX| = SXX and
  SYZ = 0 at their end nodes (the frd order of the shear components).
Run by hand: cgx -bg JOB.fbd > JOB.cgx.log in OUTDIR/JOB (doc/calculix-dropin.md).
"""
import csv
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
# gfortran's -fcheck=all (the Debug build of the CI's sanitizer stage) reports each
# array temporary on stderr; that diagnostic of the build is not the program's output.
DEBUG_NOISE = re.compile(r'^At line \d+ of file [^\n]*\nFortran runtime warning: An array temporary was created[^\n]*\n',
                         re.M)
RTOL = 1.0e-5
FILES = '*NODE FILE\nU, RF\n*EL FILE\nS, E\n'
CASES = [('truss', None), ('b31', None), ('planestrain', None), ('shell1lin', FILES), ('frame2d', '*NODE FILE\nU\n*EL FILE\nS\n'),
         ('ener_b31', '*NODE FILE\nU\n*EL FILE\nSF\n'), ('sectforc_b32', '*NODE FILE\nU\n*EL FILE\nSF\n'),
         ('sectforc_b32q', '*NODE FILE\nU\n*EL FILE\nSF\n')]
# frame2d: decks/frame2d.deck (columns and a girder joined by two RIGID knees, three
# substructures): its contact elements are two-node elements (frd type 11) of material
# 1000 + the *CONTACT card, joining the file's numbers of their two nodes.
SOURCES = {'frame2d': os.path.join(HERE, '..', '..', 'decks', 'frame2d.deck')}


def fixed_name(line):
    """The name of a -4 or -5 record in its columns 6..13, left-justified, as
    FreeCAD's reader takes it (line[5:9] == 'DISP'); None when it is not."""
    name = line[5:13]
    return name.rstrip() if name[:1] != ' ' else None


def read_frd(path):
    """(node count, element count, [(name, [component], {node: [values]})])."""
    nnode = nelem = 0
    blocks, cur = [], None
    with open(path) as f:
        for line in f:
            if line.startswith('    2C'):
                nnode = int(line[6:36])
            elif line.startswith('    3C'):
                nelem = int(line[6:36])
            elif line.startswith(' -4'):
                cur = (fixed_name(line), [], {})
                blocks.append(cur)
            elif line.startswith(' -5') and cur is not None:
                if fixed_name(line) != 'ALL':
                    cur[1].append(fixed_name(line))
            elif line.startswith(' -1') and cur is not None:
                n = int(line[3:13])
                cur[2][n] = [float(line[13 + 12 * k:25 + 12 * k]) for k in range(len(cur[1]))]
            elif line.startswith(' -3'):
                cur = None
    return nnode, nelem, blocks


def read_links(path):
    """[node numbers] of the elements of material >= 1000 (contact elements)."""
    links, inside, cur = [], False, None
    with open(path) as f:
        for line in f:
            if line.startswith('    3C'):
                inside = True
            elif inside and line.startswith(' -3'):
                break
            elif inside and line.startswith(' -1'):
                w = line.split()
                cur = [] if int(w[2]) == 11 and int(w[4]) >= 1000 else None
                if cur is not None:
                    links.append(cur)
            elif inside and line.startswith(' -2') and cur is not None:
                cur.extend(int(v) for v in line.split()[1:])
    return links


def run_cgx(work, job, blocks):
    """{(dataset, component): {node: value}} as cgx prints them."""
    lines = [f'read {job}.frd', 'prnt info', 'seta nn n all']
    for i, (_, comps, _) in enumerate(blocks):
        for k in range(len(comps)):
            lines += [f'ds {i + 1} e {k + 1}', 'prnt se nn']
    lines.append('quit')
    with open(os.path.join(work, job + '.fbd'), 'w') as f:
        f.write('\n'.join(lines) + '\n')
    proc = subprocess.run(['cgx', '-bg', job + '.fbd'], cwd=work, stdout=subprocess.PIPE,
                          stderr=subprocess.STDOUT, text=True, timeout=120)
    with open(os.path.join(work, job + '.cgx.log'), 'w') as f:
        f.write(proc.stdout)
    values, which, k = {}, None, 0
    order = [(i, c) for i, (_, comps, _) in enumerate(blocks) for c in range(len(comps))]
    counts = re.search(r' n:(\d+) e:(\d+) ', proc.stdout)
    for line in proc.stdout.splitlines():
        if line.startswith(' node:    value:'):
            which = order[k]
            values[which] = {}
            k += 1
            continue
        m = re.match(r'\s+(\d+) (\S+)\s+\S+\s+\S+\s+\S+\s*$', line)
        if which is not None and m:
            values[which][int(m.group(1))] = float(m.group(2))
        elif which is not None and line.strip() and not m:
            which = None
    return values, counts


def check_joint_forces(work, blocks, links):
    """FJOINT (*EL FILE S with contact elements): at both nodes of the k-th contact
    element of the file, its force F1..F3 (contact axes, on the master) of
    csv/contact_forces.csv, within 1e-5 of the largest; 0 at other nodes."""
    with open(os.path.join(work, 'csv', 'contact_forces.csv')) as f:
        rows = list(csv.DictReader(f))
    steps = list(dict.fromkeys(r['step'] for r in rows))
    joint = [b[2] for b in blocks if b[0] == 'FJOINT']
    if len(joint) != len(steps):
        print(f'    FAIL {len(joint)} FJOINT blocks for {len(steps)} steps')
        return ['FJOINT blocks']
    failures = []
    for step, values in zip(steps, joint):
        pairs = {}
        for r in rows:
            if r['step'] == step and r['dof'] in ('1', '2', '3'):
                f = pairs.setdefault((r['contact'], r['master_node'], r['slave_node']), [0.0] * 3)
                f[int(r['dof']) - 1] = float(r['force'])
        want = {n: f for nodes, f in zip(links, pairs.values()) for n in nodes}
        scale = max([abs(v) for f in want.values() for v in f] + [1e-300])
        diff = max(abs(values[n][d] - (want[n][d] if n in want else 0.0)) for n in values for d in range(3))
        ok = diff <= RTOL * scale and len(pairs) == len(links)
        print(f"    {'ok  ' if ok else 'FAIL'} FJOINT of step {step} against contact_forces.csv: "
              f"|diff|/max {diff / scale:.1e} (max {scale:.5e})")
        if not ok:
            failures.append(f'FJOINT of step {step}')
    return failures


def check_case(binary, outdir, job, extra):
    failures = []
    work = os.path.join(outdir, job)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(SOURCES.get(job, os.path.join(HERE, job + '.inp'))) as f:
        deck = f.read()
    if extra:
        deck = re.sub(r'(?im)^\*END STEP', extra.replace('\\', r'\\') + '*END STEP', deck)
    with open(os.path.join(work, job + '.inp'), 'w') as f:
        f.write(deck)
    proc = subprocess.run([binary, '-i', job, '--csv', 'csv'], cwd=work, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)
    proc.stderr = DEBUG_NOISE.sub('', proc.stderr)
    if proc.returncode != 0 or proc.stderr:
        return [f'{job}: superjoin status {proc.returncode}: {proc.stderr}']
    nnode, nelem, blocks = read_frd(os.path.join(work, job + '.frd'))
    values, counts = run_cgx(work, job, blocks)
    if not counts or (int(counts.group(1)), int(counts.group(2))) != (nnode, nelem):
        failures.append(f'{job}: cgx counts {counts.group(0) if counts else None}, file {nnode} nodes {nelem} elements')
    print(f'  {job}: {nnode} nodes, {nelem} elements, blocks {[b[0] for b in blocks]}')
    if any(b[0] is None or None in b[1] for b in blocks):
        failures.append(f'{job}: a -4/-5 record name not left-justified in columns 6..13')
    for i, (name, comps, rows) in enumerate(blocks):
        for c, comp in enumerate(comps):
            got = values.get((i, c), {})
            scale = max([abs(r[c]) for r in rows.values()] + [1e-300])
            diff = max([abs(got[n] - r[c]) if n in got else float('inf') for n, r in rows.items()] + [0.0])
            ok = diff <= RTOL * scale and set(got) == set(rows)
            print(f"    {'ok  ' if ok else 'FAIL'} {name:8s} {comp:4s} {len(got):4d} nodes in cgx, "
                  f"max {scale:.5e}, |cgx - file|/max {diff / scale:.1e}")
            if not ok:
                failures.append(f'{job} {name} {comp}')
    if job == 'truss':
        # both bars lie at 45 degrees in the x-z plane: sxx = szz = |szx| at the
        # end nodes 1 and 3 (szx = +-sxx), syz = 0 (frd's component order)
        s = [b for b in blocks if b[0] == 'STRESS'][0][2]
        ok = all(abs(abs(s[n][5]) - s[n][0]) <= 1e-5 * s[n][0] and s[n][4] == 0.0 for n in (1, 3))
        print(f"    {'ok  ' if ok else 'FAIL'} STRESS of the 45-degree bars: |SZX| = SXX, SYZ = 0 at nodes 1, 3")
        if not ok:
            failures.append('truss STRESS components')
    if job in ('ener_b31', 'sectforc_b32'):
        # B31 (B32: 4 elements, middle nodes 2, 4, 6, 8) cantilever, L = 1000, 8 elements, tip load -100 along y, section 1-direction z: the
        # SECTFORC block in ccx's SECTION FORCES columns: SYY = V2 = 100, SYZ = M1 = -100 (1000 - x)
        sf = [b for b in blocks if b[0] == 'SECTFORC'][0][2]
        want = {n: [0.0, 100.0, 0.0, 0.0, -100.0 * (1000.0 - 125.0 * (n - 1)), 0.0] for n in range(1, 10)}
        diff = max(abs(sf[n][c] - want[n][c]) for n in want for c in range(6)) / 1e5
        ok = set(sf) == set(want) and diff <= RTOL
        print(f"    {'ok  ' if ok else 'FAIL'} SECTFORC against V2 = P, M1 = -P (L - x): |diff|/max {diff:.1e}")
        if not ok:
            failures.append(f'{job} SECTFORC')
    if job == 'sectforc_b32q':
        # simply supported, L = 1000, q = 1 along -y (nodes every 125, middle nodes 2, 4, 6, 8):
        # SYY = V2 = q (L/2 - x), SYZ = M1 = q x (L - x)/2, the rest 0
        sf = [b for b in blocks if b[0] == 'SECTFORC'][0][2]
        want = {n: [0.0, 500.0 - 125.0 * (n - 1), 0.0, 0.0, 125.0 * (n - 1) * (1000.0 - 125.0 * (n - 1)) / 2, 0.0]
                for n in range(1, 10)}
        diff = max(abs(sf[n][c] - want[n][c]) for n in want for c in range(6)) / 125000.0
        ok = set(sf) == set(want) and diff <= RTOL
        print(f"    {'ok  ' if ok else 'FAIL'} SECTFORC against V2 = q (L/2 - x), M1 = q x (L - x)/2: |diff|/max {diff:.1e}")
        if not ok:
            failures.append(f'{job} SECTFORC')
    if job in SOURCES:
        links = read_links(os.path.join(work, job + '.frd'))
        with open(os.path.join(work, job + '.lst')) as f:
            want = int(re.search(r'contact elements\s+(\d+)', f.read()).group(1))
        ok = len(links) == want and all(len(n) == 2 for n in links)
        print(f"    {'ok  ' if ok else 'FAIL'} {len(links)} contact elements in the file "
              f"(frd type 11, material >= 1000), the listing counts {want}")
        if not ok:
            failures.append(f'{job} contact elements')
        failures += check_joint_forces(work, blocks, links)
        return failures     # several substructures: the file numbers nodes on (no CSV ids)
    disp = [b for b in blocks if b[0] == 'DISP']
    if disp:
        with open(os.path.join(work, 'csv', 'displacements.csv')) as f:
            rows = list(csv.DictReader(f))
        scale = max(abs(float(r[k])) for r in rows for k in ('u1', 'u2', 'u3'))
        diff = max(abs(float(r[k]) - disp[0][2][int(r['node'])][j])
                   for r in rows for j, k in enumerate(('u1', 'u2', 'u3')))
        ok = diff <= RTOL * scale
        print(f"    {'ok  ' if ok else 'FAIL'} DISP against displacements.csv: |diff|/max {diff / scale:.1e}")
        if not ok:
            failures.append(f'{job} DISP against the CSV')
    return failures


def main():
    if shutil.which('cgx') is None:
        print('cgx (CalculiX GraphiX, Debian calculix-cgx) not installed: skipped')
        return 77
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    failures = []
    for job, extra in CASES:
        failures += check_case(binary, outdir, job, extra)
    print(f'{len(CASES)} models, {len(failures)} failures')
    for f in failures:
        print('  ' + f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
