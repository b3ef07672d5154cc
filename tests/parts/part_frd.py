#!/usr/bin/env python3
"""*NODE FILE and *EL FILE with parts: the .frd of a deck of one *PART and two
*INSTANCE cards (B moved by (0, 4, 0), then turned 90 degrees about z) against
the same model written flat (one MAIN, B's nodes and elements numbered on).

usage: part_frd.py SUPERJOIN OUTDIR

Cases (superjoin -i JOB, each compared with its flat twin):
- 'in_part': the file requests written inside the *PART (U, RF; S, E), so each
  instance writes them;
- 'by_instance': the requests in the step naming an instance's sets
  (*NODE FILE, NSET=B.FAR; *EL FILE, ELSET=B.BLOCK).
With several substructures the file numbers nodes and elements on through them
in order (doc/calculix-dropin.md): A's nodes 1..12 and elements 1, 2, then B's
13..24 and 3, 4, which are the flat model's own ids. The two files must have
the same blocks (coordinates, elements, DISP, STRESS, TOSTRAIN, FORC) with the
same rows; the numbers agree within 1e-5 of each block's largest magnitude
(the file's 6 digits; the stresses differ in round-off, ~1e-16 of them).
"""
import os
import subprocess
import sys

PART = """*MATERIAL, NAME=M
*ELASTIC
 1000.0, 0.3
*PART, NAME=BLK
*NODE
{nodes}
*ELEMENT, TYPE=C3D8, ELSET=BLOCK
 1, 1, 5, 7, 3, 2, 6, 8, 4
 2, 5, 9, 11, 7, 6, 10, 12, 8
*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
*NSET, NSET=ROOT
 1, 2, 3, 4
*NSET, NSET=FAR
 9, 10, 11, 12
{in_part}*END PART
*ASSEMBLY, NAME=PAIR
*INSTANCE, NAME=A, PART=BLK
*END INSTANCE
*INSTANCE, NAME=B, PART=BLK
 0.0, 4.0, 0.0
 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 90.0
*END INSTANCE
*END ASSEMBLY
*BOUNDARY
 A.ROOT, 1, 3
 B.ROOT, 1, 3
*STEP
*STATIC
*CLOAD
 A.FAR, 1, 1.0
 A.FAR, 2, 0.3
 B.FAR, 2, 0.5
{in_step}*END STEP
"""
FLAT = """*MATERIAL, NAME=M
*ELASTIC
 1000.0, 0.3
*NODE
{nodes}
*ELEMENT, TYPE=C3D8, ELSET=BLOCK
 1, 1, 5, 7, 3, 2, 6, 8, 4
 2, 5, 9, 11, 7, 6, 10, 12, 8
 3, 13, 17, 19, 15, 14, 18, 20, 16
 4, 17, 21, 23, 19, 18, 22, 24, 20
*SOLID SECTION, ELSET=BLOCK, MATERIAL=M
*ELSET, ELSET=BB
 3, 4
*NSET, NSET=ROOT
 1, 2, 3, 4, 13, 14, 15, 16
*NSET, NSET=AFAR
 9, 10, 11, 12
*NSET, NSET=BFAR
 21, 22, 23, 24
*BOUNDARY
 ROOT, 1, 3
*STEP
*STATIC
*CLOAD
 AFAR, 1, 1.0
 AFAR, 2, 0.3
 BFAR, 2, 0.5
{in_step}*END STEP
"""
PART_NODES = [(1, 0, 0, 0), (2, 0, 0, 1), (3, 0, 1, 0), (4, 0, 1, 1), (5, 1, 0, 0), (6, 1, 0, 1), (7, 1, 1, 0),
              (8, 1, 1, 1), (9, 2, 0, 0), (10, 2, 0, 1), (11, 2, 1, 0), (12, 2, 1, 1)]
FILES = '*NODE FILE\nU, RF\n*EL FILE\nS, E\n'


def read_frd(path):
    """[(block name, {row key: [numbers]})] in file order: '2C' nodes, '3C' elements, then each -4 block."""
    blocks, cur = [], None
    for line in open(path):
        if line.startswith('    2C') or line.startswith('    3C'):
            cur = {}
            blocks.append((line[4:6], cur))
        elif line.startswith(' -4'):
            cur = {}
            blocks.append((line.split()[1], cur))
        elif line.startswith(' -3'):
            cur = None
        elif cur is not None and line.startswith(' -1'):
            key = int(line[3:13])
            rest = line[13:].rstrip('\n')
            cur[key] = [float(rest[12*k:12*k + 12]) for k in range(len(rest)//12)] if '.' in rest else \
                [int(w) for w in rest.split()]
        elif cur is not None and line.startswith(' -2'):
            cur[('nodes', len(cur))] = [int(w) for w in line[3:].split()]
    return blocks


def run(binary, outdir, job, text):
    with open(os.path.join(outdir, job + '.inp'), 'w') as f:
        f.write(text)
    proc = subprocess.run([binary, '-i', job], cwd=outdir, capture_output=True, text=True)
    if proc.returncode != 0:
        print(f'  FAIL {job}: status {proc.returncode}: {proc.stderr.strip()}')
        return None
    return read_frd(os.path.join(outdir, job + '.frd'))


def compare(case, got, want):
    if got is None or want is None:
        return [case]
    names = [b[0] for b in got]
    ok = names == [b[0] for b in want]
    print(f"  {'ok  ' if ok else 'FAIL'} {case}: blocks {names} (flat: {[b[0] for b in want]})")
    if not ok:
        return [case]
    failures = []
    for (name, g), (_, w) in zip(got, want):
        same = list(g) == list(w)
        scale = max([abs(v) for r in w.values() for v in r] + [1e-300])
        diff = max([abs(a - b) for k in w for a, b in zip(g.get(k, []), w[k])] + [0.0]) / scale if same else 1.0
        ok = same and diff <= 1e-5
        print(f"  {'ok  ' if ok else 'FAIL'} {case} {name:8s} {len(g):3d} rows (flat {len(w)}), "
              f"|diff|/max {diff:.1e}")
        if not ok:
            failures.append(f'{case} {name}')
    return failures


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    part_nodes = '\n'.join(f' {i}, {x:.1f}, {y:.1f}, {z:.1f}' for i, x, y, z in PART_NODES)
    # B: x' = R (x + t), t = (0, 4, 0), R 90 degrees about z: (x, y, z) -> (-(y + 4), x, z)
    flat_nodes = part_nodes + '\n' + '\n'.join(f' {i + 12}, {-(y + 4.0):.1f}, {x:.1f}, {z:.1f}'
                                               for i, x, y, z in PART_NODES)
    cases = {'in_part': (FILES, '', FILES),
             'by_instance': ('', '*NODE FILE, NSET=B.FAR\nU\n*EL FILE, ELSET=B.BLOCK\nS\n',
                             '*NODE FILE, NSET=BFAR\nU\n*EL FILE, ELSET=BB\nS\n')}
    failures = []
    for case, (in_part, in_step, flat_step) in cases.items():
        got = run(binary, outdir, case, PART.format(nodes=part_nodes, in_part=in_part, in_step=in_step))
        want = run(binary, outdir, case + '_flat', FLAT.format(nodes=flat_nodes, in_step=flat_step))
        failures += compare(case, got, want)
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
