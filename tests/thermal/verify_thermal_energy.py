#!/usr/bin/env python3
"""Strain energy (ENER) of plane and shell elements whose temperature varies
over them, against closed forms.

usage: verify_thermal_energy.py SUPERJOIN WORKDIR

A 2 x 1 plate (thickness 0.05, E = 2e11, nu = 0.3, alpha = 1.2e-5) meshed 4 x 2
with each plane element type, heated by the linear field T - T0 = 10 + 30 x + 20 y
given at the nodes (so every element's temperature varies over it). The energy is
that of the mechanical strains, 1/2 int (eps - eps_th)^T D (eps - eps_th) dV,
with a = alpha (T - T0):

- free (held against rigid motion only): a linear field is compatible, the
  plate expands without stress. Plane stress: W = 0. Plane strain: the
  expansion across the plane is held, sigma_z = -E a, W = 1/2 E t int a^2 dA.
  CPS4/CPE4 (their incompatible modes hold the quadratic displacement on
  rectangles) and the quadratic elements follow it exactly: |W| <= 1e-9 of the
  clamped value (plane stress), W to 1e-10 (plane strain).
- clamped (every node held): plane stress W = E t/(1 - nu) int a^2 dA, plane
  strain W = 3/2 E t/(1 - 2 nu) int a^2 dA; the quadratic elements' rules are
  exact for the quadratic integrand: 1e-10. CPS3: its constant strain takes
  the mean of its three nodes (as its load does), W = sum A t E abar^2/(1 - nu):
  1e-10. CPS4/CPE4: the incompatible modes are not held by the nodes and relax
  part of the field, so 0 < W < the closed form (checked: the energy is the
  minimum over those modes of a function whose value without them is the
  closed form, 2 x 2 Gauss being exact here).

Shells S4, S4R, S3, S3R (the same plate, 4 x 2 nodes' spacing, *TEMPERATURE
with the gradient through the thickness as third field, g):
- clamped (all six DOFs), T - T0 = 5 uniform and g = 100 + 50 x - 40 y: the
  membrane stores E t a^2 A/(1 - nu), the plate E t^3/(12 (1 - nu)) int k^2 dA,
  k = alpha g (the curvatures are zero; each rule is exact for the quadratic
  integrand): 1e-10.
- free, T - T0 = 10 + 30 x + 20 y, g = 0: S4/S4R's membrane (incompatible
  modes) stays stress-free, |W| <= 1e-9 of the clamped membrane energy; S3/S3R
  take each triangle's mean (0 < W < the clamped energy).
  (A linear g is not compatible for a plate: dk/dy = d(kappa_xy)/dx fails, so
  a free plate stores energy; the four elements converge to the same 0.0890 as
  the mesh is refined, not checked here.)

ccx 2.20 on the same decks (`-i`, ELSE totals) prints 11657.66 for CPS8
clamped (exact 11657.14: its C3D20R expansion) and 4080.000 for CPE8 free
(exact 4080), and 128.87 for CPS4 free, where the exact answer is 0 (its C3D8
expansion has no incompatible modes and cannot follow the quadratic field).
"""
import csv
import os
import subprocess
import sys
from fractions import Fraction

E, NU, ALPHA, T = 2.0e11, 0.3, 1.2e-5, 0.05
L, H, NX, NY = 2.0, 1.0, 4, 2
C0, CX, CY = 10.0, 30.0, 20.0


def field(x, y):
    return C0 + CX * x + CY * y


def int_a2():
    """int a^2 dA over the plate, exactly (a = alpha (C0 + CX x + CY y))."""
    def ix(p):
        return Fraction(L) ** (p + 1) / (p + 1)

    def iy(p):
        return Fraction(H) ** (p + 1) / (p + 1)
    c0, cx, cy = Fraction(C0), Fraction(CX), Fraction(CY)
    i = (c0 * c0 * ix(0) * iy(0) + cx * cx * ix(2) * iy(0) + cy * cy * ix(0) * iy(2)
         + 2 * c0 * cx * ix(1) * iy(0) + 2 * c0 * cy * ix(0) * iy(1) + 2 * cx * cy * ix(1) * iy(1))
    return float(i) * ALPHA ** 2


def mesh(et):
    """Nodes (id -> x, y) and elements (node lists) of the 4 x 2 plate."""
    mx, my = 2 * NX + 1, 2 * NY + 1

    def nid(i, j):
        return j * mx + i + 1
    nodes = {nid(i, j): (L * i / (mx - 1), H * j / (my - 1)) for j in range(my) for i in range(mx)}
    elems = []
    for j in range(NY):
        for i in range(NX):
            a, b, c, d = nid(2 * i, 2 * j), nid(2 * i + 2, 2 * j), nid(2 * i + 2, 2 * j + 2), nid(2 * i, 2 * j + 2)
            mid = {'ab': nid(2 * i + 1, 2 * j), 'bc': nid(2 * i + 2, 2 * j + 1), 'cd': nid(2 * i + 1, 2 * j + 2),
                   'da': nid(2 * i, 2 * j + 1), 'ac': nid(2 * i + 1, 2 * j + 1)}
            if '8' in et:
                elems.append([a, b, c, d, mid['ab'], mid['bc'], mid['cd'], mid['da']])
            elif '6' in et:
                elems += [[a, b, c, mid['ab'], mid['bc'], mid['ac']], [a, c, d, mid['ac'], mid['cd'], mid['da']]]
            elif '3' in et:
                elems += [[a, b, c], [a, c, d]]
            else:
                elems.append([a, b, c, d])
    used = sorted({n for e in elems for n in e})
    return {n: nodes[n] for n in used}, elems, (nid(0, 0), nid(mx - 1, 0))


def deck_text(title, et, nodes, elems, section, boundary, temperatures):
    """A deck of the plate: its mesh, the material, `section` (the card), the
    `boundary` lines, the nodal `temperatures` lines (T0 = 20) and ENER."""
    lines = ['*HEADING', title, '*NODE, NSET=ALL']
    lines += [f'{n}, {x!r}, {y!r}, 0.' for n, (x, y) in nodes.items()]
    lines.append(f'*ELEMENT, TYPE={et}, ELSET=P')
    lines += [f'{k + 1}, ' + ', '.join(str(n) for n in e) for k, e in enumerate(elems)]
    lines += ['*MATERIAL, NAME=M', '*ELASTIC', f'{E}, {NU}', '*EXPANSION', f'{ALPHA}',
              f'*{section} SECTION, ELSET=P, MATERIAL=M', f'{T}', '*BOUNDARY'] + boundary
    lines += ['*INITIAL CONDITIONS, TYPE=TEMPERATURE', 'ALL, 20.0', '*STEP', '*STATIC', '*TEMPERATURE']
    lines += temperatures + ['*EL PRINT, ELSET=P', 'ENER', '*END STEP']
    return '\n'.join(lines) + '\n'


def deck(et, clamped):
    nodes, elems, (n1, n2) = mesh(et)
    text = deck_text(f'{et} plate, linear temperature, {"clamped" if clamped else "free"}', et, nodes, elems,
                     'SOLID', ['ALL, 1, 2'] if clamped else [f'{n1}, 1, 2', f'{n2}, 2'],
                     [f'{n}, {20.0 + field(x, y)!r}' for n, (x, y) in nodes.items()])
    return text, nodes, elems


def energy(exe, work, name, text):
    path = os.path.join(work, name + '.inp')
    with open(path, 'w') as f:
        f.write(text)
    out = os.path.join(work, name + '.csv')
    r = subprocess.run([exe, '-q', path, '-o', os.path.join(work, name + '.lst'), '--csv', out],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f'FAIL: {name}: exit {r.returncode}\n{r.stderr}')
    with open(os.path.join(out, 'energies.csv'), newline='') as f:
        return [float(row['energy']) for row in csv.DictReader(f) if row['kind'] == 'total'][0]


def cst_mean_energy(nodes, elems):
    """sum A t E abar^2/(1 - nu): CPS3's constant strain takes its nodes' mean."""
    w = 0.0
    for e in elems:
        (x1, y1), (x2, y2), (x3, y3) = (nodes[n] for n in e)
        area = 0.5 * abs((x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1))
        abar = ALPHA * sum(field(*nodes[n]) for n in e) / 3
        w += area * T * E * abar ** 2 / (1 - NU)
    return w


def shell_deck(et, clamped, tfun, gfun):
    """The plate as shells, corner nodes only (S4/S4R quadrilaterals, S3/S3R
    two triangles per cell)."""
    mx = NX + 1

    def nid(i, j):
        return j * mx + i + 1
    nodes = {nid(i, j): (L * i / NX, H * j / NY) for j in range(NY + 1) for i in range(mx)}
    elems = []
    for j in range(NY):
        for i in range(NX):
            a, b, c, d = nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1)
            elems += [[a, b, c], [a, c, d]] if '3' in et else [[a, b, c, d]]
    text = deck_text(f'{et} plate, {"clamped" if clamped else "free"}', et, nodes, elems, 'SHELL',
                     ['ALL, 1, 6'] if clamped else [f'{nid(0, 0)}, 1, 3', f'{nid(NX, 0)}, 2, 3', f'{nid(0, NY)}, 3'],
                     [f'{n}, {20.0 + tfun(x, y)!r}, {gfun(x, y)!r}' for n, (x, y) in nodes.items()])
    return text, nodes, elems


def int_g2(g0, gx, gy):
    """int (alpha (g0 + gx x + gy y))^2 dA over the plate, exactly."""
    global C0, CX, CY
    saved = C0, CX, CY
    C0, CX, CY = g0, gx, gy
    try:
        return int_a2()
    finally:
        C0, CX, CY = saved


def check_shells(exe, work, check):
    g0, gx, gy, t_uniform = 100.0, 50.0, -40.0, 5.0
    membrane_uniform = E * T * (ALPHA * t_uniform) ** 2 * L * H / (1 - NU)
    bending = E * T ** 3 / (12 * (1 - NU)) * int_g2(g0, gx, gy)
    stress_clamped = E * T / (1 - NU) * int_a2()
    for et in ('S4', 'S4R', 'S3', 'S3R'):
        text, _, _ = shell_deck(et, True, lambda x, y: t_uniform, lambda x, y: g0 + gx * x + gy * y)
        w, want = energy(exe, work, et + '_clamped', text), membrane_uniform + bending
        err = abs(w - want) / want
        check(et + '_clamped', err <= 1e-10, f'W = {w!r}, E t a^2 A/(1 - nu) + E t^3 int k^2/(12 (1 - nu)) = '
              f'{want!r} (error {err:.1e})')
        text, nodes, elems = shell_deck(et, False, field, lambda x, y: 0.0)
        w = energy(exe, work, et + '_free', text)
        if '3' in et:
            check(et + '_free', 0.0 < w < stress_clamped, f'W = {w!r}, between 0 and {stress_clamped!r} '
                  '(each triangle takes its mean)')
        else:
            err = abs(w) / stress_clamped
            check(et + '_free', err <= 1e-9, f'W = {w!r}, closed form 0 (error {err:.1e} of {stress_clamped:.6g})')


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    exe, work = argv[1], argv[2]
    os.makedirs(work, exist_ok=True)
    i2 = int_a2()
    stress_clamped = E * T / (1 - NU) * i2
    strain_free, strain_clamped = 0.5 * E * T * i2, 1.5 * E * T / (1 - 2 * NU) * i2
    failures = []

    def check(name, ok, text):
        print(f"{'ok  ' if ok else 'FAIL'} {name}: {text}")
        if not ok:
            failures.append(name)

    for et in ('CPS4', 'CPE4', 'CPS8', 'CPS8R', 'CPE8', 'CPE8R', 'CPS6', 'CPE6', 'CPS3'):
        strain = et.startswith('CPE')
        for clamped in (False, True):
            name = f'{et}_{"clamped" if clamped else "free"}'
            text, nodes, elems = deck(et, clamped)
            w = energy(exe, work, name, text)
            if et == 'CPS3':
                if clamped:
                    want = cst_mean_energy(nodes, elems)
                    check(name, abs(w - want) <= 1e-10 * want, f'W = {w!r}, sum A t E abar^2/(1 - nu) = {want!r}')
                else:   # the elements' means differ: not stress-free, but below the clamped energy
                    check(name, 0.0 < w < stress_clamped, f'W = {w!r}, between 0 and {stress_clamped!r}')
                continue
            if clamped and et.endswith('4'):
                want = strain_clamped if strain else stress_clamped
                check(name, 0.0 < w < want, f'W = {w!r}, between 0 and the closed form {want!r} '
                      '(the incompatible modes relax)')
                continue
            if clamped:
                want = strain_clamped if strain else stress_clamped
            else:
                want = strain_free if strain else 0.0
            scale = want if want else stress_clamped
            tol = 1e-10 if want else 1e-9
            err = abs(w - want) / scale
            check(name, err <= tol, f'W = {w!r}, closed form {want!r} (error {err:.1e} of {scale:.6g})')
    check_shells(exe, work, check)
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
