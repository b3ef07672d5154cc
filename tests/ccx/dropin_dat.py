#!/usr/bin/env python3
"""superjoin as a drop-in for CalculiX: run every deck of tests/ccx that has a
non-empty .dat.ref as ccx would be run (`superjoin -i JOB` in a scratch
directory), and compare JOB.dat with JOB.dat.ref number by number.

usage: dropin_dat.py SUPERJOIN OUTDIR

Blocks are matched by their title, set and time ("displacements (vx,vy,vz)
for set NALL and time 0.1000000E+01"; CalculiX 2.11's "forset" read as "for
set"), rows by node or by element and integration point. A block's
difference is max |superjoin - CalculiX| over its rows divided by the
largest magnitude in the reference block. Every block of .dat.ref must be in
.dat with the same rows (beams excepted: superjoin prints no stresses for
them) and within the deck's tolerance below; the table printed is the one
of doc/calculix-dropin.md.

The energies of ener_truss.inp and ener_c3d8.inp (decks written for this test,
references from ccx 2.20) are also checked against closed forms
(energy_closed_forms), and the rows of a node set GENERATEd up to the
largest node id 2**31 - 1 (generate_near_limit).

With ccx installed it also runs achtel2, beam10p, beam20p and beamd with
*EL FILE S, E added through superjoin -i and ccx and compares the .frd
STRESS and TOSTRAIN blocks (solids' nodal values extrapolated from their
points): within 5e-5 of the largest value (5 printed digits).

Tolerances and why (doc/calculix-dropin.md, "The .dat against .dat.ref"):
- 1e-6 (7 printed digits): solids (the same elements at the same points), trusses (CalculiX's C3D20R of a truss carries the
  uniaxial tensor), the plane patch tests, nodal systems.
- planestress2: 5e-4 (CalculiX's brick has szz, sxz, syz from the thickness
  steps between its bricks; in-plane within 5e-6).
- planestress3: 0.25 (CPS4 is superjoin's QM6, CalculiX's C3D8 is fully
  integrated: different elements on a coarse mesh).
- beams (B31, B32R: beamlin, b31, rot1, rot2, simplebeam*): 0.07 on
  displacements (CalculiX expands a beam into bricks; superjoin's beam is
  the closed form, tests/ccx/compare_ccx.py), 1e-6 on forces (statically
  determinate); stresses: none printed by superjoin for beams.
- shells (S8R: shell1lin, rot4): 0.2 on displacements, 0.3 on forces, 0.35
  on stresses (CalculiX's one-brick-thick C3D20R expansion of a 2x2 mesh is
  16 % stiff in bending, compare_ccx.py; its brick has szz).
- axial (CAX8R, CENTRIF): 1e-2 (CalculiX's 2 deg wedge of C3D20R on two elements
  0.45 long; against the spinning thin disk's closed form superjoin is the
  nearer: u at the bore -1.5 % against ccx's -2.5 %, doc/calculix-dropin.md).
- c3d15: forces 5 times the reference's largest: the pressures on opposite
  faces balance, so both programs' reactions are round-off (ccx 1.4e-14,
  superjoin 2.5e-14); the check says both are.
- disk2 (C3D20R, CENTRIF, cyclic *EQUATIONs on nodes with a cylindrical
  *TRANSFORM, their DOFs in the nodal system): 2e-5 on displacements, 1e-4
  on stresses (measured 1.3e-5 and 8.2e-5: the load's quadrature on curved
  C3D20R, as segment1/segment2 in doc/verification.md).
- orient_print (ours, .dat.ref by ccx 2.20): S, E of oriented solids in their
  material axes unless GLOBAL=YES, the rows ending with the orientation's name
  (checked as text).
- pret1: a mechanism (CalculiX solves through its singular stiffness):
  exit status 3, the mechanism on stderr, no "Job finished".
- spring1: refused (*STEP, NLGEOM): exit status 1, the reason on stderr, no
  "Job finished" on stdout and an empty .dat: a front-end sees a failure.
"""
import math
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
EXACT = 1.0e-6
BEAMS = ('beamlin', 'b31', 'rot1', 'rot2', 'simplebeam', 'simplebeampipe1', 'simplebeampipe2',
         'simplebeampipe4')
# deck -> {block kind: tolerance}; kinds: displacements, forces, stresses, strains, temperatures
TOLERANCE = {'planestress2': {'stresses': 5.0e-4}, 'planestress3': {'displacements': 0.25},
             'shell1lin': {'displacements': 0.2, 'forces': 0.3, 'stresses': 0.35},
             'rot4': {'displacements': 0.2, 'forces': 0.3, 'stresses': 0.35},
             'axial': {'displacements': 1.0e-2, 'stresses': 1.0e-2},
             'c3d15': {'forces': 5.0}, 'disk2': {'displacements': 2.0e-5, 'stresses': 1.0e-4},
             # ELSE of a B31 and an S4 cantilever (written for this test): CalculiX's C3D20R and
             # C3D8I expansions; superjoin's B31 gives Timoshenko's closed form (energy_closed_forms)
             # ENER (kind density): the B31's mean density at CalculiX's 8 points, the S4's at its points
             'ener_b31': {'displacements': 1.0e-2, 'internal': 1.0e-2, 'total': 1.0e-2, 'density': 1.0e-2},
             'ener_s4': {'displacements': 1.0e-2, 'internal': 1.0e-2, 'total': 1.0e-2, 'density': 0.1},
             # u_r = -nu eps r exactly in superjoin; CalculiX's straight-sided 2 deg wedge: times cos 1 deg
             'ener_cax8r': {'displacements': 2.0e-4}}
for _b in BEAMS:
    TOLERANCE[_b] = {'displacements': 0.07}
# CalculiX solved these with its iterative solvers (*STATIC, SOLVER=ITERATIVE CHOLESKY /
# ITERATIVE SCALING): their .dat.ref carry its iteration error, superjoin solves directly.
# beampic is beampset's model (same mesh, supports and load; beampset solved directly):
# superjoin's beampic.dat must equal beampset.dat.ref to 7 digits, and the two .dat.ref
# differ by 1.7e-3 (displacements) and 1.8e-3 (stresses) of the table.
ITERATIVE = {'beampic': ('beampset', 2.0e-3), 'beampis': (None, 2.0e-6)}
for _job, (_, _tol) in ITERATIVE.items():
    TOLERANCE[_job] = {'displacements': _tol, 'stresses': _tol}
REFUSED = {'spring1': 'NLGEOM'}
# decks CalculiX solves through a singular stiffness (SPOOLES on a free rigid motion and a
# zero-energy mode): superjoin reports the mechanism, exit status 3, an empty .dat
# (pret1: only x held, a frame one C3D20R thick; doc/verification.md, "Bolt pretension")
MECHANISM = ('pret1',)
# solid decks whose .frd STRESS and TOSTRAIN (with *EL FILE S, E added) are checked against ccx's, when
# ccx is installed: 5 printed digits, 5e-5 of the largest value (as tests/solids/verify_solids.py)
FRD_SOLIDS = ('achtel2', 'beam10p', 'beam20p', 'beamd')
FRD_TOL = 5.0e-5
TITLE = re.compile(r'\s*(\D.*?)\s+for\s*set\s+(\S+)\s+and time\s+(\S+)')


def parse_dat(path):
    """{(title, set, time[, n]): {row key: [values]}} of a CalculiX .dat file
    (n = 2, 3, ... for a later block of the same title, set and time: steps
    of *STATIC, TIME RESET end at the same total time)."""
    blocks, cur, title = {}, None, ''
    with open(path) as f:
        for line in f:
            words = line.split()
            if not words:
                continue
            m = TITLE.match(line)
            if m:
                title = m.group(1)
                key = (title, m.group(2), float(m.group(3)))
                n = 1
                while key + ((n,) if n > 1 else ()) in blocks:
                    n += 1
                cur = blocks.setdefault(key + ((n,) if n > 1 else ()), {})
                continue
            if not re.match(r'[-+0-9.]', words[0]):
                cur = None           # ccx 2.11's knot listing of expanded beams (KNOT2, tra, rot, exp)
                continue
            if cur is None:
                continue
            if words[-1] == 'L':
                words = words[:-1]
            if '(elem, integ.pnt.' in title and not re.match(r'[-+0-9.]', words[-1]):
                words = words[:-1]   # an oriented element's row ends with its orientation's name
            if title.startswith('total'):
                cur['total'] = [float(w) for w in words]
            elif '(elem, integ.pnt.' in title:
                cur[(int(words[0]), int(words[1]))] = [float(w) for w in words[2:]]
            else:
                cur[int(words[0])] = [float(w) for w in words[1:]]
    return blocks


def orientation_names(path):
    """The text after the six values of every element row that has one (ccx 2.20: the first 20
    characters of the orientation of an oriented solid printed in its material axes), in order."""
    out = []
    with open(path) as f:
        for line in f:
            words = line.split()
            if len(words) == 9 and re.match(r'[0-9]', words[0]) and not re.match(r'[-+0-9.]', words[-1]):
                out.append((words[0], words[1], line.rstrip('\n')[98:]))
    return out


def run(binary, outdir, job):
    work = os.path.join(outdir, job)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    shutil.copy(os.path.join(HERE, job + '.inp'), work)
    proc = subprocess.run([binary, '-i ', job], cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True)
    proc.stderr = DEBUG_NOISE.sub('', proc.stderr)
    return proc, os.path.join(work, job + '.dat')


def compare(job, got, want):
    """Print a row per reference block; return the failures."""
    failures = []
    for key, rows in want.items():
        kind = 'density' if 'energy density' in key[0] else key[0].split()[0]
        label = f'{job:16s} {kind:13s} {key[1]:7s} t={key[2]:g}' + (f' ({key[3]})' if len(key) > 3 else '')
        if key not in got:
            failures.append(f'{label}: block missing')
            print(f'  FAIL {label}: block missing')
            continue
        mine = got[key]
        if job in BEAMS and kind == 'stresses':
            print(f'  ok   {label}: not printed for beams ({len(rows)} CalculiX brick points)')
            continue
        if set(mine) != set(rows):
            failures.append(f'{label}: rows differ')
            print(f'  FAIL {label}: rows {sorted(mine)[:5]}.. against {sorted(rows)[:5]}..')
            continue
        scale = max([abs(v) for r in rows.values() for v in r] + [1e-300])
        diff = max([abs(a - b) for k in rows for a, b in zip(mine[k], rows[k])] + [0.0])
        tol = TOLERANCE.get(job, {}).get(kind, EXACT)
        ok = diff <= tol * scale
        print(f"  {'ok  ' if ok else 'FAIL'} {label}: {len(rows):3d} rows, |diff|/scale {diff / scale:.1e}"
              f" (tolerance {tol:.2g})")
        if not ok:
            failures.append(label)
    return failures


def energy_closed_forms(outdir):
    """The .dat energies of ener_truss and ener_c3d8 (ENER, ELSE) against closed forms;
    return the failures. Truss: N^2 L / (2 E A) per bar (N = -1000, 1000 sqrt 2; EA =
    2.1e7), density sigma^2 / (2 E); C3D8 cantilever: the total equals 1/2 P w over the
    tip loads (Clapeyron), and the sum of ENER x weight x det J (unit cubes: 1/8 of
    the element's points) equals ELSE."""
    failures = []
    dat = parse_dat(os.path.join(outdir, 'ener_truss', 'ener_truss.dat'))
    blocks = {k[0].split(' (')[0]: v for k, v in dat.items()}
    ea, bars = 2.1e7, [(-1000.0, 1000.0), (1000.0 * 2 ** 0.5, 1000.0 * 2 ** 0.5)]
    want = [n * n * length / (2 * ea) for n, length in bars]
    got = [blocks['internal energy'][e][0] for e in (1, 2)]
    dens = [blocks['internal energy density'][(e, 1)][0] for e in (1, 2)]
    want_dens = [(n / 100.0) ** 2 / (2 * 210000.0) for n, _ in bars]
    diff = max(abs(a - b) / b for a, b in zip(got + dens, want + want_dens))
    ok = diff <= 1e-6
    print(f"  {'ok  ' if ok else 'FAIL'} ener_truss       ELSE, ENER against N^2 L/(2EA), sigma^2/(2E): "
          f"|diff|/value {diff:.1e} (ELSE {got[0]:.6e}, {got[1]:.6e})")
    if not ok:
        failures.append('ener_truss closed form')
    dat = parse_dat(os.path.join(outdir, 'ener_c3d8', 'ener_c3d8.dat'))
    blocks = {k[0].split(' (')[0]: v for k, v in dat.items()}
    work = 0.5 * sum(-25.0 * blocks['displacements'][n][2] for n in (5, 10, 15, 20))
    total = blocks['total internal energy']['total'][0]
    dens = blocks['internal energy density']
    els = blocks['internal energy']
    integ = max(abs(sum(v[0] for k, v in dens.items() if k[0] == e) / 8.0 - els[e][0]) for e in els)
    ok = abs(total - work) <= 1e-6 * work and integ <= 1e-6 * max(v[0] for v in els.values())
    print(f"  {'ok  ' if ok else 'FAIL'} ener_c3d8        total {total:.6e} = 1/2 P w {work:.6e} "
          f"(Euler-Bernoulli 1/2 P^2 L^3/(3EI) = {0.5 * 100.0 ** 2 * 64 / (3 * 210000.0 / 12):.6e}: "
          f"C3D8 locks in bending); ENER integrated = ELSE within {integ:.1e}")
    if not ok:
        failures.append('ener_c3d8 closed form')
    # CAX8R ring r = 1..3, h = 1, uz = 0.001: ENER = E eps^2 / 2, ELSE total = ENER pi (9 - 1) / 180 (the wedge)
    dat = parse_dat(os.path.join(outdir, 'ener_cax8r', 'ener_cax8r.dat'))
    blocks = {k[0].split(' (')[0]: v for k, v in dat.items()}
    dens, total = 0.5 * 210000.0 * 1e-6, blocks['total internal energy']['total'][0]
    diff = max([abs(v[0] - dens) / dens for v in blocks['internal energy density'].values()]
               + [abs(total - dens * math.pi * 8 / 180) / total])
    ok = diff <= 1e-6
    print(f"  {'ok  ' if ok else 'FAIL'} ener_cax8r       ENER = E eps^2/2, ELSE = ENER V / 180 (CalculiX's 2 deg wedge): "
          f"|diff|/value {diff:.1e}")
    if not ok:
        failures.append('ener_cax8r closed form')
    # B31 cantilever L = 1000, 10 x 20 rectangle (I = 6666.67 about the load), P = 100: Timoshenko
    # 1/2 P^2 (L^3/(3EI) + L/(k G A)), k = 0.85 (superjoin's rectangle); S4 strip: 1/2 P w (Clapeyron)
    for job, closed in (('ener_b31', 0.5 * 100.0 ** 2 * (1e9 / (3 * 210000.0 * 20.0 ** 3 * 10 / 12)
                                                         + 1000.0 / (0.85 * 210000.0 / 2.6 * 200.0))),
                        ('ener_s4', None)):
        dat = parse_dat(os.path.join(outdir, job, job + '.dat'))
        blocks = {k[0].split(' (')[0]: v for k, v in dat.items()}
        total = blocks['total internal energy']['total'][0]
        if closed is None:
            closed = 0.5 * sum(-50.0 * blocks['displacements'][n][2] for n in (9, 18))
        # ENER at the 8 points of CalculiX's brick of each element (volume 125 x 10 x 20 = 25000, equal
        # weights): their mean times the volume is ELSE (B31: by construction, its mean density)
        dens, els = blocks['internal energy density'], blocks['internal energy']
        # relative to the largest element's energy, as the table comparisons: the tip element holds
        # 6e-3 of it, and its ELSE (1/2 u.k.u with the drilling penalty's stiffness) moves by 3e-6 of
        # itself between the Release and the Debug build
        scale = max(v[0] for v in els.values())
        integ = max(abs(sum(v[0] for k, v in dens.items() if k[0] == e) / 8.0 * 25000.0 - els[e][0]) / scale
                    for e in els)
        ok = abs(total - closed) <= 1e-6 * closed and integ <= 1e-6
        print(f"  {'ok  ' if ok else 'FAIL'} {job:16s} total {total:.6e} against {closed:.6e} "
              f"({'Timoshenko' if job == 'ener_b31' else '1/2 P w'}); ENER integrated = ELSE within {integ:.1e}")
        if not ok:
            failures.append(job + ' closed form')
    # CPS4 and S4 strips 2 x 1 x 0.1 in uniform tension sigma = 1000: ENER = sigma^2/(2E) at every point,
    # ELSE = ENER x 0.1 per element, total = 1/2 P u over the loaded nodes
    dat = parse_dat(os.path.join(outdir, 'ener_plane', 'ener_plane.dat'))
    blocks = {k[0].split(' (')[0]: v for k, v in dat.items()}
    dens = 1000.0 ** 2 / (2 * 210000.0)
    work = 0.5 * sum(50.0 * blocks['displacements'][n][0] for n in (3, 6, 13, 16))
    diff = max([abs(v[0] - dens) / dens for v in blocks['internal energy density'].values()]
               + [abs(v[0] - 0.1 * dens) / (0.1 * dens) for v in blocks['internal energy'].values()]
               + [abs(blocks['total internal energy']['total'][0] - work) / work])
    ok = diff <= 1e-6 and len(blocks['internal energy density']) == 32
    print(f"  {'ok  ' if ok else 'FAIL'} ener_plane       ENER = sigma^2/(2E) at the 8 points of each CPS4 and S4, "
          f"ELSE = ENER V, total = 1/2 P u: |diff|/value {diff:.1e}")
    if not ok:
        failures.append('ener_plane closed form')
    return failures


def cards_without_output(binary, outdir):
    """*CONTACT PRINT / *CONTACT FILE (ener_c3d8.inp has both) are accepted with a
    listing note; *EL PRINT S6 (planestrain.inp with its E, S replaced) stops with
    status 1 and says that S6 is an element type (ccx 2.20: label not applicable)."""
    failures = []
    with open(os.path.join(outdir, 'ener_c3d8', 'ener_c3d8.lst')) as f:
        lst = f.read()
    ok = all(f'*CONTACT {w} at ener_c3d8.inp:' in lst for w in ('PRINT', 'FILE'))
    print(f"  {'ok  ' if ok else 'FAIL'} ener_c3d8        *CONTACT PRINT, *CONTACT FILE accepted, noted in the listing")
    if not ok:
        failures.append('*CONTACT PRINT note')
    work = os.path.join(outdir, 'el_print_s6')
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(HERE, 'planestrain.inp')) as f:
        deck = re.sub(r'(?m)^E,S$', 'S6', f.read())
    with open(os.path.join(work, 's6.inp'), 'w') as f:
        f.write(deck)
    proc = subprocess.run([binary, '-i', 's6'], cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    ok = proc.returncode == 1 and "S6 is CalculiX's shell element type, not an output variable" in proc.stderr
    print(f"  {'ok  ' if ok else 'FAIL'} el_print_s6      *EL PRINT S6 refused: status {proc.returncode}, "
          f"{proc.stderr.strip()[:60]}...")
    if not ok:
        failures.append('*EL PRINT S6 not refused clearly')
    return failures


GENERATE_NEAR_LIMIT = """*NODE
1, 0.0, 0.0, 0.0
2147483647, 2.0, 0.0, 0.0
*ELEMENT, TYPE=T3D2, ELSET=BAR
1, 1, 2147483647
*MATERIAL, NAME=STEEL
*ELASTIC
2.0e11, 0.3
*SOLID SECTION, ELSET=BAR, MATERIAL=STEEL
1.0e-4
*NSET, NSET=ENDS, GENERATE
1, 2147483647, 1073741823
*BOUNDARY
1, 1, 3
2147483647, 2, 3
*STEP
*STATIC
*CLOAD
2147483647, 1, 1000.0
*NODE PRINT, NSET=ENDS
U
*END STEP
"""


def generate_near_limit(binary, outdir):
    """A GENERATE range ending at the largest node id, 2**31 - 1, with a step
    of 2**30 - 1: the .dat rows of its three ids (the undefined middle one
    with zeros, as ccx 2.20 prints a set's gaps) and no more. Stepping past
    the last id overflowed int32 (UBSan, 2026-11-29); the rows are counted
    now. The bar's end moves F L / (E A) = 1000 * 2 / (2e11 * 1e-4) = 1e-4."""
    work = os.path.join(outdir, 'generate_limit')
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    with open(os.path.join(work, 'limit.inp'), 'w') as f:
        f.write(GENERATE_NEAR_LIMIT)
    try:
        proc = subprocess.run([binary, '-i', 'limit'], cwd=work, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, timeout=60)
        status = proc.returncode
    except subprocess.TimeoutExpired:
        status = 'timeout (60 s)'
    rows = []
    if status == 0:
        with open(os.path.join(work, 'limit.dat')) as f:
            rows = [line.split() for line in f if re.match(r'^ *\d+ ', line)]
    ids = [int(r[0]) for r in rows]
    u = float(rows[-1][1]) if rows else 0.0
    ok = (status == 0 and ids == [1, 2**30, 2**31 - 1] and all(float(v) == 0.0 for v in rows[1][1:])
          and abs(u - 1.0e-4) <= 1e-10)
    print(f"  {'ok  ' if ok else 'FAIL'} generate_limit   GENERATE 1, 2**31-1, 2**30-1: status {status}, "
          f"rows {ids}, u1 {u:.6e} (1e-4)")
    return [] if ok else ['GENERATE range ending at 2**31-1']


def frd_blocks(path):
    """{name: {node: [values]}} of the result blocks of an ASCII .frd."""
    out, cur = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith(' -4'):
                cur = out.setdefault(line.split()[1], {})
            elif line.startswith(' -3'):
                cur = None
            elif cur is not None and line.startswith(' -1'):
                n = (len(line.rstrip()) - 13) // 12
                cur[int(line[3:13])] = [float(line[13 + 12 * i:25 + 12 * i]) for i in range(n)]
    return out


def frd_solids(binary, outdir):
    """superjoin's and ccx's .frd STRESS and TOSTRAIN of the solid decks; return the failures."""
    if shutil.which('ccx') is None:
        print('  ccx not installed: .frd of solids not cross-checked')
        return []
    failures = []
    for job in FRD_SOLIDS:
        with open(os.path.join(HERE, job + '.inp')) as f:
            text = re.sub(r'(?im)^\*END STEP', '*EL FILE\nS, E\n*END STEP', f.read())
        got = {}
        for who in ('superjoin', 'ccx'):
            work = os.path.join(outdir, 'frd_' + who, job)
            shutil.rmtree(work, ignore_errors=True)
            os.makedirs(work)
            with open(os.path.join(work, job + '.inp'), 'w') as f:
                f.write(text)
            subprocess.run([binary if who == 'superjoin' else 'ccx', '-i', job], cwd=work,
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            frd = os.path.join(work, job + '.frd')
            got[who] = frd_blocks(frd) if os.path.exists(frd) else {}
        for name in ('STRESS', 'TOSTRAIN'):
            ref, mine = got['ccx'].get(name, {}), got['superjoin'].get(name, {})
            if not ref or set(ref) != set(mine):
                print(f'  FAIL {job:16s} .frd {name}: nodes differ or block missing')
                failures.append(f'{job} .frd {name}')
                continue
            scale = max([abs(v) for r in ref.values() for v in r] + [1e-300])
            diff = max(abs(a - b) for k in ref for a, b in zip(mine[k], ref[k]))
            ok = diff <= FRD_TOL * scale
            print(f"  {'ok  ' if ok else 'FAIL'} {job:16s} .frd {name:8s} {len(ref):3d} nodes, |diff|/scale "
                  f"{diff / scale:.1e} (tolerance {FRD_TOL:.2g})")
            if not ok:
                failures.append(f'{job} .frd {name}')
    return failures


def main():
    binary, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    failures = []
    jobs = sorted(f[:-8] for f in os.listdir(HERE) if f.endswith('.dat.ref')
                  and os.path.getsize(os.path.join(HERE, f)) > 0)
    for job in jobs:
        proc, dat = run(binary, outdir, job)
        if job in REFUSED:
            ok = (proc.returncode == 1 and REFUSED[job] in proc.stderr and 'Job finished' not in proc.stdout
                  and os.path.getsize(dat) == 0)
            print(f"  {'ok  ' if ok else 'FAIL'} {job:16s} refused: status {proc.returncode}, "
                  f"{proc.stderr.strip().splitlines()[0] if proc.stderr.strip() else 'no message'}")
            if not ok:
                failures.append(job + ' not refused clearly')
            continue
        if job in MECHANISM:
            ok = proc.returncode == 3 and 'mechanism' in proc.stderr and 'Job finished' not in proc.stdout
            print(f"  {'ok  ' if ok else 'FAIL'} {job:16s} mechanism: status {proc.returncode}")
            if not ok:
                failures.append(job + ' not reported as a mechanism')
            continue
        if proc.returncode != 0 or proc.stderr or 'Job finished' not in proc.stdout:
            print(f'  FAIL {job}: status {proc.returncode}, stderr {proc.stderr!r}')
            failures.append(job)
            continue
        failures += compare(job, parse_dat(dat), parse_dat(os.path.join(HERE, job + '.dat.ref')))
        names, want = orientation_names(dat), orientation_names(os.path.join(HERE, job + '.dat.ref'))
        if names or want:
            ok = names == want
            print(f"  {'ok  ' if ok else 'FAIL'} {job:16s} orientation names ending {len(want)} rows")
            if not ok:
                failures.append(job + ' orientation names')
        direct = ITERATIVE.get(job, (None, 0))[0]
        if direct:
            failures += compare(job + ' vs ' + direct, parse_dat(dat),
                                parse_dat(os.path.join(HERE, direct + '.dat.ref')))
    failures += energy_closed_forms(outdir)
    failures += cards_without_output(binary, outdir)
    failures += generate_near_limit(binary, outdir)
    failures += frd_solids(binary, outdir)
    print(f'{len(jobs)} decks, {len(failures)} failures')
    for f in failures:
        print('  ' + f)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
