#!/usr/bin/env python3
"""Run CalculiX's rigid-body test deck beamprb.inp unchanged and compare
superjoin's displacements with CalculiX's beamprb.frd.ref.

usage: compare_rigid.py SUPERJOIN OUTDIR

beamprb.inp: a C3D20R cantilever 1 x 1 x 8 along z (E = 210000, nu = 0.3),
clamped at z = 0 (*BOUNDARY FIX 1..3); the four corner nodes 5-8 of its end
face form `*RIGID BODY, NSET=N1, REF NODE=262, ROT NODE=263` (CalculiX: the
translations of the ROT NODE are the rotations of the body), and the load
`263, 2, 1.` is a moment M = 1 about y on the body. It is linear (no NLGEOM);
its .dat.ref is empty (no print request), the displacements are in the .frd
(*NODE FILE U, 6 significant digits: 1e-5 of the table).

Checks:
1. every node of the .frd: superjoin's u equals CalculiX's within 1e-5 of the
   table (measured 2.6e-6, the .frd's rounding);
2. the rigid body: each of the nodes 5-8 moves as u_262 + theta x (x - x_262)
   with theta = u_263 (round-off);
3. closed form: the tip deflection of a cantilever under an end moment,
   M L^2 / (2 E I) = 1.8286e-3 (I = 1/12), within 1 % of the face's mean
   deflection (measured 0.6 %: the clamp's restrained Poisson contraction and
   the load through four corner nodes only). The body's rotation theta_y is
   printed against M L / (E I): the four corners turn more than the beam's
   section (they carry the moment alone, a local effect), CalculiX's the same.
"""
import csv
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from compare_ccx import frd_disp  # noqa: E402

FAILURES = []


def check(ok, what):
    print(f"  {'ok  ' if ok else 'FAIL'} {what}")
    if not ok:
        FAILURES.append(what)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    binary, outdir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(outdir, exist_ok=True)
    csvdir = os.path.join(outdir, 'beamprb_csv')
    proc = subprocess.run([binary, '-q', 'beamprb.inp', '-o', os.path.join(outdir, 'beamprb.lst'), '--csv', csvdir],
                          cwd=HERE, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        print(f'FAIL: superjoin exited with {proc.returncode} on beamprb.inp:\n{proc.stderr}')
        sys.exit(1)
    got = {}
    with open(os.path.join(csvdir, 'displacements.csv')) as f:
        for row in csv.DictReader(f):
            got[int(row['node'])] = [float(row[c]) for c in ('u1', 'u2', 'u3')]
    ref = frd_disp(os.path.join(HERE, 'beamprb.frd.ref'))
    print('beamprb.inp (*RIGID BODY, REF NODE, ROT NODE; C3D20R): *NODE FILE U against beamprb.frd.ref')
    scale = max(max(abs(v) for v in u) for u in ref.values())
    err = max(max(abs(a - b) for a, b in zip(got[n], ref[n])) for n in ref)
    check(err <= 1e-5 * scale, f'{len(ref)} nodes: max |u - u_ccx| / table {err / scale:.1e} (1e-5)')
    xyz = {}
    with open(os.path.join(HERE, 'beamprb.inp')) as f:
        inside = False
        for line in f:
            if line.upper().startswith('*NODE') and 'FILE' not in line.upper():
                inside = True
                continue
            if line.startswith('*'):
                inside = False
            if inside and line.strip():
                v = line.split(',')
                xyz[int(v[0])] = [float(t) for t in v[1:4]]
    th = got[263]
    worst = 0.0
    for n in (5, 6, 7, 8):
        r = [xyz[n][i] - xyz[262][i] for i in range(3)]
        rigid = [got[262][0] + th[1] * r[2] - th[2] * r[1], got[262][1] + th[2] * r[0] - th[0] * r[2],
                 got[262][2] + th[0] * r[1] - th[1] * r[0]]
        worst = max(worst, max(abs(a - b) for a, b in zip(got[n], rigid)))
    check(worst <= 1e-12 * scale, f'nodes 5-8 move rigidly with REF NODE 262 and the rotation u(263) '
          f'({worst / scale:.1e} of the table)')
    e, inertia, length = 210000.0, 1.0 / 12.0, 8.0
    want = length ** 2 / (2 * e * inertia)
    mean = sum(got[n][0] for n in (5, 6, 7, 8)) / 4
    check(abs(mean / want - 1) < 0.01, f'tip deflection {mean:.5e} / M L^2/(2EI) {want:.5e} = {mean / want:.4f}')
    print(f'  note: body rotation {th[1]:.5e} / M L/(EI) {length / (e * inertia):.5e} = '
          f'{th[1] * e * inertia / length:.4f} (the four corners carry the moment)')
    if FAILURES:
        print(f'FAIL: {len(FAILURES)} comparisons')
        sys.exit(1)
    print('all comparisons within their stated tolerances')


if __name__ == '__main__':
    main()
