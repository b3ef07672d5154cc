#!/usr/bin/env python3
"""CENTRIF on B32 beams: the section forces of the .frd (SECTFORC, *EL FILE SF)
against closed forms, the middle nodes included (their halves carry the load).

usage: check_b32_centrif.py SUPERJOIN OUTDIR

Two B32 (nodes every 0.5, L = 2, RECT 10 x 20, rho A omega^2 = 0.005 x 200 x 100
= 100), *DLOAD CENTRIF (r from the undeformed axis):
- 'transverse': the beam along x at y = -10 spins about the x axis: a uniform
  q = 100 x 10 = 1000 along -y; simply supported: V2 = q (L/2 - x),
  M1 = q x (L - x)/2 (the columns of sectforc_b32q in frd_cgx.py), M = q L^2/8
  = 500 at x = 1 and 62.5 x 3 = 375 at the middle nodes x = 0.5, 1.5;
- 'radial': the beam along x from the axis z (through the origin), held at x = 0,
  free at x = 2: q = 100 x along x, the normal force N = 100 (L^2 - x^2)/2 (SZZ):
  200, 187.5, 150, 87.5, 0.
Before, B32 refused CENTRIF; the middle nodes' values come from the equilibrium
of each half under its end node's forces and the load on it (3 Gauss points).
A heated B32 (the gradient across its section, clamped at both ends: M = E I
alpha g along it, no load on the halves) checks that TEMP needs nothing there.
"""
import os
import re
import subprocess
import sys

RHO_A_W2 = 100.0
DECK = """*NODE, NSET=NALL
{nodes}
*ELEMENT, TYPE=B32, ELSET=EALL
1, 1, 2, 3
2, 3, 4, 5
*MATERIAL, NAME=STEEL
*ELASTIC
210000., 0.3
*DENSITY
0.005
*BEAM SECTION, ELSET=EALL, MATERIAL=STEEL, SECTION=RECT
10., 20.
0., 0., 1.
*BOUNDARY
{bcs}
*STEP
*STATIC
*DLOAD
EALL, CENTRIF, 100., 0., 0., 0., {axis}
*NODE FILE
U
*EL FILE
SF
*END STEP
"""


def read_sectforc(path):
    """{node: [6 values]} of the SECTFORC block of a .frd."""
    rows, on = {}, False
    for line in open(path):
        if line.startswith(' -4') and 'SECTFORC' in line:
            on = True
            continue
        if on and line.startswith(' -3'):
            break
        if on and line.startswith(' -1'):
            n = int(line[3:13])
            rows[n] = [float(line[13 + 12*k:25 + 12*k]) for k in range(6)]
    return rows


def run(binary, outdir, job, text):
    work = os.path.join(outdir, job)
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, job + '.inp'), 'w') as f:
        f.write(text)
    proc = subprocess.run([binary, '-i', job], cwd=work, capture_output=True, text=True)
    if proc.returncode != 0:
        print(f'  FAIL {job}: status {proc.returncode}: {proc.stderr.strip()}')
        return None
    return read_sectforc(os.path.join(work, job + '.frd'))


def compare(job, got, want, scale):
    if got is None:
        return [job]
    ok = set(got) == set(want)
    diff = max(abs(got[n][c] - want[n][c]) for n in want for c in range(6)) / scale if ok else float('inf')
    ok = ok and diff <= 1e-5      # 5 printed digits
    print(f"  {'ok  ' if ok else 'FAIL'} {job}: SECTFORC at nodes {sorted(got)} against the closed form, "
          f"|diff|/max {diff:.1e}")
    if not ok:
        for n in sorted(want):
            print(f'       node {n}: got {got.get(n)}, want {want[n]}')
    return [] if ok else [job]


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    xs = [0.5*k for k in range(5)]
    failures = []
    q = RHO_A_W2*10.0
    deck = DECK.format(nodes='\n'.join(f'{k + 1}, {x}, -10., 0.' for k, x in enumerate(xs)),
                       bcs='1, 1, 4\n5, 2, 3', axis='1., 0., 0.')
    want = {k + 1: [0.0, q*(1.0 - x), 0.0, 0.0, q*x*(2.0 - x)/2, 0.0] for k, x in enumerate(xs)}
    failures += compare('transverse', run(binary, outdir, 'transverse', deck), want, q*4/8)
    deck = DECK.format(nodes='\n'.join(f'{k + 1}, {x}, 0., 0.' for k, x in enumerate(xs)),
                       bcs='1, 1, 6', axis='0., 0., 1.')
    want = {k + 1: [0.0, 0.0, RHO_A_W2*(4.0 - x*x)/2, 0.0, 0.0, 0.0] for k, x in enumerate(xs)}
    failures += compare('radial', run(binary, outdir, 'radial', deck), want, RHO_A_W2*2)
    # TEMP: a gradient g = 10 along local y (RECT's first side, 10) of a beam clamped at both ends,
    # no heating: the moment E Iz alpha g = 210000 x (20 x 10^3/12) x 1.2e-5 x 10 = 42000 all along
    deck = DECK.format(nodes='\n'.join(f'{k + 1}, {x}, 0., 0.' for k, x in enumerate(xs)),
                       bcs='1, 1, 6\n5, 1, 6', axis='0., 0., 1.')
    deck = deck.replace('*DLOAD\nEALL, CENTRIF, 100., 0., 0., 0., 0., 0., 1.\n', '*TEMPERATURE\nNALL, 0., 0., 10.\n')
    deck = deck.replace('*DENSITY\n0.005\n', '*EXPANSION\n1.2e-5\n').replace(
        '*BOUNDARY', '*INITIAL CONDITIONS, TYPE=TEMPERATURE\nNALL, 0.\n*BOUNDARY')
    assert 'CENTRIF' not in deck and '*EXPANSION' in deck
    moment = 210000.0*(20.0*10.0**3/12)*1.2e-5*10.0
    want = {k + 1: [0.0, 0.0, 0.0, 0.0, 0.0, moment] for k in range(5)}
    failures += compare('gradient', run(binary, outdir, 'gradient', deck), want, moment)
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
