#!/usr/bin/env python3
"""Closed-form checks of the decks of the CalculiX/Abaqus cards
(tests/decks/ccx_requests, ccx_requests_plane, ccx_springs, beam_library):
each deck is solved with --csv and its results are compared with the closed
forms stated in its header. Discrete answers are exact, so the tolerance is
round-off: 1e-12 relative.

usage: closed_forms.py SUPERJOIN OUTDIR
"""
import csv
import math
import os
import subprocess
import sys

DECKS = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'decks')
TOL = 1.0e-12
WORST = {}
FAIL = []


def solve(binary, outdir, name):
    out = os.path.join(outdir, name)
    os.makedirs(out, exist_ok=True)
    proc = subprocess.run([binary, '-q', name + '.deck', '-o', os.path.join(out, name + '.lst'), '--csv', out],
                          cwd=DECKS, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        print(f'FAIL: {name}: exit {proc.returncode}\n{proc.stderr}')
        sys.exit(1)
    return out


def rows(out, file):
    with open(os.path.join(out, file)) as f:
        return list(csv.DictReader(f))


def disp(out):
    return {(r['step'], int(r['node'])): [float(r[k]) for k in ('u1', 'u2', 'u3', 'ur1', 'ur2', 'ur3')]
            for r in rows(out, 'displacements.csv')}


def check(deck, what, got, want):
    err = abs(got - want) / abs(want)
    WORST[deck] = max(WORST.get(deck, 0.0), err)
    ok = err <= TOL
    print(f"  {'ok  ' if ok else 'FAIL'} {deck}: {what}: {got:.16e} closed form {want:.16e} relerr {err:.1e}")
    if not ok:
        FAIL.append(what)


def rect_j(c, d):
    c, d = max(c, d), min(c, d)
    s = sum(math.tanh(n * math.pi * c / (2 * d)) / n**5 for n in range(1, 200001, 2))
    return c * d**3 / 3 * (1 - 192 / math.pi**5 * (d / c) * s)


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    binary, outdir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])

    out = solve(binary, outdir, 'beam_library')
    d = disp(out)
    e, length = 2.1e11, 2.0
    g = e / 2.6
    check('beam_library', 'RECT tip Y (Iz = b a^3/12)', d[('TIP_Y', 3)][1], 1000 * length**3 / (3 * e * 0.08 * 0.05**3 / 12))
    check('beam_library', 'RECT tip Z (Iy = a b^3/12)', d[('TIP_Z', 3)][2], 1000 * length**3 / (3 * e * 0.05 * 0.08**3 / 12))
    check('beam_library', 'RECT twist (Saint-Venant J)', d[('TORQUE', 3)][3], 100 * length / (g * rect_j(0.08, 0.05)))
    i_pipe = math.pi * (0.05**4 - 0.045**4) / 4
    check('beam_library', 'PIPE tip Y', d[('TIP_Y', 13)][1], 1000 * length**3 / (3 * e * i_pipe))
    check('beam_library', 'PIPE twist (J = 2I)', d[('TORQUE', 13)][3], 100 * length / (g * 2 * i_pipe))
    check('beam_library', 'GENERAL tip Y (I22)', d[('TIP_Y', 23)][1], 1000 * length**3 / (3 * e * 1e-6))
    check('beam_library', 'B23 RECT tip (I = I11)', d[('TIP_Y', 33)][1], 1000 * length**3 / (3 * e * 0.05 * 0.08**3 / 12))

    out = solve(binary, outdir, 'ccx_springs')
    d = disp(out)
    force = {r['contact']: float(r['force']) for r in rows(out, 'contact_forces.csv')}
    react = {(int(r['node']), int(r['dof'])): float(r['force']) for r in rows(out, 'reactions.csv')}
    check('ccx_springs', 'SPRING1 u2', d[('1', 2)][0], 10 / 1500)
    check('ccx_springs', 'SPRING1 reaction', react[(2, 1)], -10 / 3)
    check('ccx_springs', 'SPRING2 u14', d[('1', 14)][0], 0.025)
    check('ccx_springs', 'SPRING2 force', force['SPRING_JOINT'], 10.0)
    check('ccx_springs', 'SPRINGA u', d[('1', 21)][0], 0.068)
    check('ccx_springs', 'SPRINGA v', d[('1', 21)][1], 0.024)
    check('ccx_springs', 'SPRINGA 1 force (compression)', force['SPRINGA_STAYA_103'], -6.0)
    check('ccx_springs', 'SPRINGA 2 force (tension)', force['SPRINGA_STAYB_104'], 8.0)

    out = solve(binary, outdir, 'ccx_requests')
    d = disp(out)
    check('ccx_requests', 'LOADX u1 of node 2', d[('LOADX', 2)][0], 8e-6 * math.sqrt(2))
    check('ccx_requests', 'LOADZ u3 of node 2', d[('LOADZ', 2)][2], 2 * 8e-6 * math.sqrt(2))

    out = solve(binary, outdir, 'ccx_requests_plane')
    p = rows(out, 'plate_results.csv')[0]
    check('ccx_requests_plane', 'nx (element frame: global y) = syy t', float(p['nx']), 0.5)
    check('ccx_requests_plane', 'ny (element frame: global -x) = sxx t', float(p['ny']), 1.0)

    for deck, err in WORST.items():
        print(f'{deck}: max relative error {err:.1e}')
    if FAIL:
        print(f'FAIL: {len(FAIL)} checks')
        sys.exit(1)


if __name__ == '__main__':
    main()
