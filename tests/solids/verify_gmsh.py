#!/usr/bin/env python3
"""Meshes from gmsh run as written (issue 23): tests/solids/gmsh/box1.inp (C3D4)
and box2.inp (C3D10) are gmsh 4.8.4's (Debian 12) .inp of a 10 x 1 x 1 bar (box1.geo,
box2.geo), unchanged but for what every gmsh user removes: the face elements
(CPS3/CPS6) gmsh writes for each physical surface, which neither ccx nor
superjoin accept without a section. The surfaces' *ELSETs still list those
faces: ccx passes over undefined ids, and so does superjoin under CalculiX's
reading (a `superjoin -i` run), with a listing note.

The bar is stretched by u = 0.01 at x = 10 (job.inp): uniform strain 1e-3,
which linear and quadratic tetrahedra reproduce exactly, so at every
integration point sxx = E * 1e-3 = 210 and the other components are 0
(round-off: 1e-9 of 210), the end reaction is -210 (area 1), and the lateral
contraction at the loaded end is -nu * 1e-3 * y (z) at each node (1e-8 of the
0.01 stretch: the .dat prints 7 digits).

usage: verify_gmsh.py SUPERJOIN OUTDIR
"""
import os
import shutil
import subprocess
import sys

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), 'gmsh')
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'ccx'))
import dropin_dat  # noqa: E402

E, NU, STRAIN = 210000.0, 0.3, 1.0e-3
TOL = 1.0e-9


def strip_faces(text):
    """The gmsh .inp without its *ELEMENT cards of face elements (CPS3, CPS6)."""
    out, skip = [], False
    for line in text.splitlines(keepends=True):
        if line.startswith('*') and not line.startswith('**'):
            skip = line.replace(' ', '').upper().startswith('*ELEMENT,TYPE=CPS')
        if not skip:
            out.append(line)
    return ''.join(out)


def nodes_of(text):
    """{id: (x, y, z)} of the *NODE card."""
    xyz, on = {}, False
    for line in text.splitlines():
        if line.startswith('*'):
            on = line.upper().startswith('*NODE') and not line.upper().startswith('*NODE ')
            continue
        if on and line.strip():
            w = [float(v) for v in line.split(',')]
            xyz[int(w[0])] = w[1:4]
    return xyz


def check(binary, outdir, mesh):
    work = os.path.join(outdir, mesh)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    text = open(os.path.join(HERE, mesh + '.inp')).read()
    open(os.path.join(work, 'mesh.inp'), 'w').write(strip_faces(text))
    shutil.copy(os.path.join(HERE, 'job.inp'), work)
    proc = subprocess.run([binary, '-i', 'job'], cwd=work, capture_output=True, text=True)
    proc.stderr = dropin_dat.DEBUG_NOISE.sub('', proc.stderr)
    if proc.returncode != 0 or proc.stderr:
        print(f'  FAIL {mesh}: status {proc.returncode}, stderr {proc.stderr!r}')
        return [mesh]
    notes = [ln for ln in open(os.path.join(work, 'job.lst')) if 'left out, as CalculiX does' in ln]
    blocks = dropin_dat.parse_dat(os.path.join(work, 'job.dat'))
    xyz = nodes_of(text)
    s = max(max(abs(v[0] - E * STRAIN), *map(abs, v[1:])) for k, b in blocks.items()
            if k[0].startswith('stresses') for v in b.values())
    npts = sum(len(b) for k, b in blocks.items() if k[0].startswith('stresses'))
    tip = next(b for k, b in blocks.items() if k[0].startswith('displacements'))
    u = max(max(abs(v[0] - 0.01), abs(v[1] + NU * STRAIN * xyz[n][1]), abs(v[2] + NU * STRAIN * xyz[n][2]))
            for n, v in tip.items())
    rf = next(b for k, b in blocks.items() if k[0].startswith('total force'))['total'][0]
    failures = []
    for what, err, scale, tol in (('stresses', s, E * STRAIN, TOL), ('tip displacements', u, 0.01, 1.0e-8),
                                  ('end reaction', abs(rf + E * STRAIN), E * STRAIN, TOL)):
        ok = err <= tol * scale
        print(f"  {'ok  ' if ok else 'FAIL'} {mesh}: {what}: max error {err / scale:.1e} of {scale:g}")
        if not ok:
            failures.append(f'{mesh} {what}')
    ok = npts > 0 and notes and all('set FIX' in n or 'set TIP' in n for n in notes)
    print(f"  {'ok  ' if ok else 'FAIL'} {mesh}: {npts} integration points, {len(tip)} loaded-end nodes, "
          f"{len(notes)} listing notes on the surfaces' element sets")
    return failures + ([] if ok else [f'{mesh} notes'])


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    failures = check(binary, outdir, 'box1') + check(binary, outdir, 'box2')
    print(f'{len(failures)} failures')
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
