#!/usr/bin/env python3
"""FreeCAD with superjoin as its CalculiX binary, a subset of
tools/freecad_dropin.py as a ctest (ccx.freecad_dropin; the full list of
examples stays a run by hand, doc/calculix-dropin.md, "FreeCAD").

usage: freecad_dropin.py SUPERJOIN OUTDIR   (exit 77: freecadcmd not installed, skipped)

Runs `freecadcmd tools/freecad_dropin.py` on three of FreeCAD's examples
(the FEM workbench's own steps: binary check, deck, `binary "-i " Mesh`,
Mesh.frd read back; about 5 s, 3.5 s of it FreeCAD starting):
- ccx_cantilever_faceload (C3D10, a face pressure) and
  ccx_cantilever_ele_hexa20 (C3D20): superjoin's run must load a result and,
  when ccx is installed, its largest displacement must be ccx's within 1e-6
  and its largest von Mises stress within 1e-4 (the same elements; measured
  2e-6 and 1.6e-5: FreeCAD computes von Mises from the 5-digit .frd);
- ccx_cantilever_ele_quad4 (S4): a result loaded, its largest displacement
  within 2 % of ccx's (superjoin's S4 against ccx's C3D8I expansion: 0.9 %).
"""
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
# example -> (tolerance on max |u|, on max von Mises or None)
CHECKS = {'ccx_cantilever_faceload': (1e-6, 1e-4), 'ccx_cantilever_ele_hexa20': (1e-6, 1e-4),
          'ccx_cantilever_ele_quad4': (0.02, None)}
LINE = re.compile(r'^(\S+)\s+(superjoin|ccx)\s+status (\d+)(.*)$')
VALUES = re.compile(r'CCX_Results: max \|u\| (\S+), max von Mises (\S+)$')


def main():
    exe, outdir = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    fc = shutil.which('freecadcmd')
    if not fc:
        print('freecadcmd not installed (Debian: freecad-python3): ccx.freecad_dropin skipped')
        return 77
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    env = dict(os.environ, SUPERJOIN=exe, WORK=outdir, EXAMPLES=','.join(CHECKS))
    r = subprocess.run([fc, os.path.join(ROOT, 'tools', 'freecad_dropin.py')], env=env, cwd=outdir,
                       capture_output=True, text=True, timeout=300)
    runs = {}
    for line in r.stdout.splitlines():
        m = LINE.match(line)
        if m:
            runs[(m.group(1), m.group(2))] = (int(m.group(3)), m.group(4))
            print(line)
    failures = []
    for example, (tol_u, tol_s) in CHECKS.items():
        got = runs.get((example, 'superjoin'))
        if got is None:
            failures.append(example + ': no superjoin run reported (freecadcmd status %d)' % r.returncode)
            continue
        v = VALUES.search(got[1])
        if got[0] != 0 or 'not loaded' in got[1] or not v:
            failures.append('%s: superjoin: status %d%s' % (example, got[0], got[1]))
            continue
        ref = runs.get((example, 'ccx'))
        w = VALUES.search(ref[1]) if ref and ref[0] == 0 else None
        if not w:
            print('%s: no ccx result to compare with' % example)
            continue
        u, s, u0, s0 = (float(x) for x in (v.group(1), v.group(2), w.group(1), w.group(2)))
        if abs(u - u0) > tol_u * abs(u0):
            failures.append('%s: max |u| %g, ccx %g (tolerance %g)' % (example, u, u0, tol_u))
        if tol_s is not None and abs(s - s0) > tol_s * abs(s0):
            failures.append('%s: max von Mises %g, ccx %g (tolerance %g)' % (example, s, s0, tol_s))
    for f in failures:
        print('FAIL ' + f)
    if not failures:
        print('FreeCAD read back superjoin\'s results of %d examples' % len(CHECKS))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
