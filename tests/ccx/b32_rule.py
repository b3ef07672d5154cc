#!/usr/bin/env python3
"""Why CalculiX's B32R can be superjoin's B32: a three-node Timoshenko beam
(quadratic w and theta, one bending plane) with two Gauss points (the reduced
rule, superjoin's B32) and with three (full), a cantilever with a tip load,
PIPE r = 0.11, t = 0.01, E = 1e7, nu = 0.3, k = 0.5. Prints the tip
deflection over P L^3/(3 EI) + P L/(k G A) as a markdown table; exit 1
unless the two-point element is exact (1e-8) and the full rule locks (one
slender element below 0.8).

usage: b32_rule.py
"""
import math
import sys


def solve(a, b):
    n = len(b); a = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c])); a[c], a[p] = a[p], a[c]
        for r in range(c+1, n):
            f = a[r][c]/a[c][c]
            for k in range(c, n+1): a[r][k] -= f*a[c][k]
    x = [0.0]*n
    for r in reversed(range(n)):
        x[r] = (a[r][n] - sum(a[r][k]*x[k] for k in range(r+1, n)))/a[r][r]
    return x


def tip(nel, L, EI, kGA, ngp, P=1.0):
    g = {2: ([-1/math.sqrt(3), 1/math.sqrt(3)], [1, 1]), 3: ([-math.sqrt(.6), 0, math.sqrt(.6)], [5/9, 8/9, 5/9])}[ngp]
    nn = 2*nel+1; K = [[0.0]*(2*nn) for _ in range(2*nn)]; le = L/nel
    for e in range(nel):
        idx = [2*(2*e+a)+c for a in range(3) for c in range(2)]
        for xi, w in zip(*g):
            N = [xi*(xi-1)/2, 1-xi*xi, xi*(xi+1)/2]; dN = [(xi-.5)*2/le, -2*xi*2/le, (xi+.5)*2/le]
            Bb = [0.0]*6; Bs = [0.0]*6
            for a in range(3):
                Bb[2*a+1] = dN[a]; Bs[2*a] = dN[a]; Bs[2*a+1] = -N[a]
            for i in range(6):
                for j in range(6):
                    K[idx[i]][idx[j]] += w*le/2*(EI*Bb[i]*Bb[j] + kGA*Bs[i]*Bs[j])
    f = [0.0]*(2*nn); f[-2] = P
    free = list(range(2, 2*nn))
    u = solve([[K[i][j] for j in free] for i in free], [f[i] for i in free])
    return u[-2]


def main():
    e, nu = 1e7, 0.3
    g = e/2/(1 + nu)
    ro, ri = 0.11, 0.10
    area, inertia, k = math.pi*(ro**2 - ri**2), math.pi/4*(ro**4 - ri**4), 0.5
    bad = []
    print('| L / D | elements | 2 Gauss points (superjoin\'s B32) | 3 Gauss points (full) |')
    print('|---|---|---|---|')
    for length in (1.0, 10.0, 100.0):
        exact = length**3/(3*e*inertia) + length/(k*g*area)
        for nel in (1, 10):
            r2 = tip(nel, length, e*inertia, k*g*area, 2)/exact
            r3 = tip(nel, length, e*inertia, k*g*area, 3)/exact
            print(f'| {length/(2*ro):.1f} | {nel} | {r2:.10f} | {r3:.6f} |')
            if abs(r2 - 1) > 1e-8:
                bad.append(f'two points, L/D {length/(2*ro):.1f}, {nel} elements: {r2}')
            if nel == 1 and length == 100.0 and r3 > 0.8:
                bad.append(f'full rule does not lock: {r3}')
    for b in bad:
        print('FAIL:', b)
    sys.exit(1 if bad else 0)


if __name__ == '__main__':
    main()
