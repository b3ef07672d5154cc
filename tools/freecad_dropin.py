"""FreeCAD end to end with superjoin as its CalculiX binary (by hand; three of the
examples are the ctest ccx.freecad_dropin, tests/ccx/freecad_dropin.py).

usage (Debian 12: apt-get install freecad-python3):
  SUPERJOIN=build/superjoin WORK=/tmp/fc_dropin freecadcmd tools/freecad_dropin.py
  optional: EXAMPLES=ccx_cantilever_ele_quad4,ccx_cantilever_ele_seg2 (default: the list below)

For each of FreeCAD's bundled examples (femexamples, solver "ccxtools") the
script does what the FEM workbench does: FemToolsCcx checks the binary (its
no-argument run must print CalculiX), writes the deck, runs
`binary "-i " Mesh` in the working directory, reads Mesh.frd back into a
result object. It does so with superjoin and, when installed, with ccx, and
prints one line per run: the exit status, FreeCAD's result objects, the
largest displacement and von Mises stress FreeCAD computed from the .frd.
The measured table and what fails: doc/calculix-dropin.md, "FreeCAD".
"""
import os
import shutil
from importlib import import_module

import FreeCAD

EXAMPLES = ['ccx_cantilever_ele_quad4', 'ccx_cantilever_ele_quad8', 'ccx_cantilever_ele_tria3',
            'ccx_cantilever_ele_tria6', 'ccx_cantilever_ele_seg2', 'ccx_cantilever_ele_seg3',
            'ccx_cantilever_beam_rect', 'ccx_cantilever_beam_circle', 'ccx_cantilever_beam_pipe',
            'truss_3d_cs_circle_ele_seg2', 'truss_3d_cs_circle_ele_seg3', 'ccx_cantilever_faceload',
            'ccx_cantilever_ele_hexa20']


def run_one(example, binary, work):
    """Exit status, result names, max displacement, max von Mises (or the error)."""
    from femtools import ccxtools
    prefs = FreeCAD.ParamGet('User parameter:BaseApp/Preferences/Mod/Fem/Ccx')
    prefs.SetBool('UseStandardCcxLocation', False)
    prefs.SetString('ccxBinaryPath', binary)
    doc = import_module('femexamples.' + example).setup(solvertype='ccxtools')
    doc.recompute()
    solver = [o for o in doc.Analysis.Group if o.isDerivedFrom('Fem::FemSolverObjectPython')][0]
    fea = ccxtools.FemToolsCcx(doc.Analysis, solver)
    fea.update_objects()
    fea.setup_working_dir(work)
    fea.setup_ccx(ccx_binary=binary)
    fea.write_inp_file()
    rc = fea.ccx_run()
    line = f'status {rc}'
    if rc == 0:
        try:
            fea.load_results()
        except Exception as e:          # FreeCAD's reader refused the file
            line += f', results not loaded: {e!r}'
        res = [o for o in doc.Analysis.Group if o.isDerivedFrom('Fem::FemResultObjectPython')]
        for r in res:
            line += f', {r.Name}: max |u| {max(r.DisplacementLengths):.6e}, max von Mises {max(r.vonMises):.6e}'
    else:
        line += ', ' + (fea.ccx_stderr.strip().splitlines() or ['(no stderr)'])[0][:160]
    FreeCAD.closeDocument(doc.Name)
    return line


def main():
    superjoin = os.path.abspath(os.environ['SUPERJOIN'])
    work = os.path.abspath(os.environ.get('WORK', '/tmp/fc_dropin'))
    examples = os.environ.get('EXAMPLES', ','.join(EXAMPLES)).split(',')
    binaries = [('superjoin', superjoin)]
    if shutil.which('ccx'):
        binaries.append(('ccx', shutil.which('ccx')))
    report = []
    for example in examples:
        for name, binary in binaries:
            where = os.path.join(work, f'{example}_{name}')
            os.makedirs(where, exist_ok=True)
            try:
                line = run_one(example, binary, where)
            except Exception as e:
                line = f'failed: {e!r}'
            report.append(f'{example:32s} {name:9s} {line}')
    print('\n'.join(['', 'FreeCAD with superjoin as CalculiX:'] + report))


main()
