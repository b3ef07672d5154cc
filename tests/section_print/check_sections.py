#!/usr/bin/env python3
"""*SECTION PRINT (SOF, SOM, SOAREA) against ccx 2.20 and against closed forms.

usage: check_sections.py SUPERJOIN OUTDIR

Decks (ours, written by a generator for this test; the .dat.ref are the .dat
files that ccx 2.20, Debian 12's calculix-ccx, `ccx -i JOB`, writes for them):
- cantilever20r: a C3D20R cantilever 10 x 1 x 2 (5 x 1 x 2 elements), clamped
  at x = 0, P = 1000 in z spread over the nodes of the end x = 10; sections
  LEFT (faces S4 of the elements ending at x = 4) and RIGHT (faces S6 of the
  elements starting there).
- cantilever20: the same cantilever of C3D20 elements.
- bar8: a C3D8 bar 10 x 1 x 2 (10 x 2 x 4 elements) clamped at x = 0, a
  pressure -P/A on the end face (tension P = 1000); the same two sections.

1. `superjoin -i JOB`: every "statistics for surface set" block of JOB.dat.ref
   is in JOB.dat with the same title, each row within 1e-4 of the row's
   largest reference value (at least 1e-3 of the block's: round-off rows) (ccx's nodal stresses, which it integrates, are
   4e-5 below superjoin's on these meshes while the stresses at the
   integration points agree to 7 digits: doc/calculix-dropin.md).
   `superjoin cantilever20r` (ccx's form without -i, as PrePoMax runs it)
   writes the same .dat.
2. The listing and --csv (section_forces.csv), closed forms:
   - cantilever20r: the force on LEFT (what the right part does to the left)
     is (0, 0, P), its moment about the centre of gravity (4, 0.5, 1) is
     (0, -P (L - x), 0) = (0, -6000, 0), within 1e-6 of P (C3D20R: exact);
     RIGHT is the opposite (action and reaction).
   - cantilever20: the same cantilever of C3D20: the stress integral is
     1352.3 and -6066.4 (ccx 2.20: 1352.4, -6066.6): the smoothed stresses
     of a coarse C3D20 mesh carry the shear badly; not checked.
   - every deck: the resultant of the nodal forces (fx_nodal .. mz_nodal,
     K u of the faces' elements at the section's nodes) is the closed form
     within 1e-9 of P (exact equilibrium).
   - bar8: LEFT carries (P, 0, 0) within 5e-4 (the smoothed stress of a
     clamped C3D8 bar is uniform only up to the discretisation), area 2,
     centre of gravity (4, 0.5, 1), mean normal (1, 0, 0); RIGHT opposite.
3. Deck errors (unknown surface, unknown variable, no NAME=, a surface of
   shell faces) stop the run with status 1 and say so.
"""
import csv
import os
import re
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
P, L, XC = 1000.0, 10.0, 4.0
ROW = re.compile(r'^\s+(-?\d\.\d{6}E[+-]\d\d)((\s+-?\d\.\d{6}E[+-]\d\d)*)\s*$')


def blocks(path):
    """{title: [rows of floats]} of the statistics blocks of a .dat file."""
    out, title = {}, None
    with open(path) as f:
        for line in f:
            if line.startswith(' statistics for surface set'):
                title = ' '.join(line.split())
                out[title] = []
            elif title and ROW.match(line):
                out[title].append([float(v) for v in line.split()])
            elif line.strip() and not line.startswith('   '):
                title = None
    return out


def close(a, b, tol, scale):
    return abs(a - b) <= tol * scale


def refusals(exe, outdir):
    """Deck errors of *SECTION PRINT: each a status 1 and its message."""
    with open(os.path.join(HERE, 'bar8.inp')) as f:
        deck = f.read()
    cases = [('SURFACE=LEFT, NAME=SL', 'SURFACE=NOPE, NAME=SL', 'unknown surface NOPE'),
             ('SOF, SOM, SOAREA', 'SOF, SOE', "unknown output variable 'SOE' for *SECTION PRINT"),
             ('SURFACE=LEFT, NAME=SL', 'SURFACE=LEFT', 'NAME'),
             ('*SURFACE, NAME=LEFT, TYPE=ELEMENT\n4, S4', '*SURFACE, NAME=LEFT, TYPE=ELEMENT\n4, SPOS',
              'faces of shells or plane elements')]
    failures = []
    for k, (old, new, message) in enumerate(cases):
        if old not in deck:
            failures.append('refusal %d: %r not in bar8.inp' % (k, old))
            continue
        path = os.path.join(outdir, 'refused%d.inp' % k)
        with open(path, 'w') as f:
            f.write(deck.replace(old, new, 1))
        r = subprocess.run([exe, '-q', '--check', path], capture_output=True, text=True)
        print('refusal %d: status %d, %s' % (k, r.returncode, r.stderr.strip().splitlines()[:1]))
        if r.returncode != 1 or message not in r.stderr:
            failures.append('refusal %d: status %d, stderr %r (expected %r)' % (k, r.returncode, r.stderr, message))
    return failures


def main():
    exe, outdir = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(outdir, exist_ok=True)
    failures = []
    for job in ('cantilever20r', 'cantilever20', 'bar8'):
        shutil.copy(os.path.join(HERE, job + '.inp'), outdir)
        r = subprocess.run([exe, '-q', '-i', job], cwd=outdir, capture_output=True, text=True)
        if r.returncode != 0:
            failures.append(job + ': superjoin -i failed: ' + r.stderr)
            continue
        ref, got = blocks(os.path.join(HERE, job + '.dat.ref')), blocks(os.path.join(outdir, job + '.dat'))
        if list(ref) != list(got):
            failures.append('%s: blocks %s, expected %s' % (job, list(got), list(ref)))
            continue
        for title in ref:
            if len(ref[title]) != len(got[title]):
                failures.append('%s: %s: %d rows, expected %d' % (job, title, len(got[title]), len(ref[title])))
                continue
            top = max(abs(v) for row in ref[title] for v in row)
            for rr, gr in zip(ref[title], got[title]):
                scale = max(max(abs(v) for v in rr), 1e-3 * top)
                worst = max(abs(a - b) for a, b in zip(rr, gr)) / scale
                print('%-14s %-45s row %s: %.1e' % (job, title[:45], ' '.join('%.4g' % v for v in rr), worst))
                if worst > 1e-4:
                    failures.append('%s: %s: %s, expected %s' % (job, title, gr, rr))
        if job == 'cantilever20r':      # ccx's form without -i, as PrePoMax runs it: the same .dat
            plain = os.path.join(outdir, 'plain')
            os.makedirs(plain, exist_ok=True)
            shutil.copy(os.path.join(HERE, job + '.inp'), plain)
            r = subprocess.run([exe, '-q', job], cwd=plain, capture_output=True, text=True)
            with open(os.path.join(outdir, job + '.dat')) as a, open(os.path.join(plain, job + '.dat')) as b:
                if r.returncode != 0 or a.read() != b.read():
                    failures.append('superjoin %s (no -i): status %d, %s' % (job, r.returncode, r.stderr))
        csvdir = os.path.join(outdir, job + '_csv')
        r = subprocess.run([exe, '-q', job + '.inp', '-o', job + '.lst', '--csv', csvdir], cwd=outdir,
                           capture_output=True, text=True)
        if r.returncode != 0:
            failures.append(job + ': superjoin failed: ' + r.stderr)
            continue
        with open(os.path.join(outdir, job + '.lst')) as f:
            if 'section SL (surface LEFT, ' not in f.read():
                failures.append(job + ': no SECTION PRINT table in the listing')
        with open(os.path.join(csvdir, 'section_forces.csv')) as f:
            rows = {row['section']: {k: float(v) for k, v in row.items() if k not in ('section', 'surface')}
                    for row in csv.DictReader(f)}
        tol = {'cantilever20r': 1e-6, 'cantilever20': None, 'bar8': 5e-4}[job]
        for name, sign in (('SL', 1.0), ('SR', -1.0)):
            s = rows[name]
            f = [s['fx'], s['fy'], s['fz']]
            cg = [s['cx'], s['cy'], s['cz']]
            m = [s['mx'], s['my'], s['mz']]
            mc = [m[0] - (cg[1] * f[2] - cg[2] * f[1]), m[1] - (cg[2] * f[0] - cg[0] * f[2]),
                  m[2] - (cg[0] * f[1] - cg[1] * f[0])]
            if job.startswith('cantilever'):
                want_f, want_m = [0.0, 0.0, sign * P], [0.0, -sign * P * (L - XC), 0.0]
            else:
                want_f, want_m = [sign * P, 0.0, 0.0], [0.0, 0.0, 0.0]
            fn = [s['fx_nodal'], s['fy_nodal'], s['fz_nodal']]
            mn = [s['mx_nodal'], s['my_nodal'], s['mz_nodal']]
            mnc = [mn[0] - (cg[1] * fn[2] - cg[2] * fn[1]), mn[1] - (cg[2] * fn[0] - cg[0] * fn[2]),
                   mn[2] - (cg[0] * fn[1] - cg[1] * fn[0])]
            print('%-14s %s: F = %s, M about c = %s, area %.6g, c = %s' % (job, name, f, mc, s['area'], cg))
            print('%-14s %s: nodal forces: F = %s, M about c = %s' % (job, name, fn, mnc))
            ok = (tol is None or all(close(a, b, tol, P) for a, b in zip(f, want_f)) and
                  all(close(a, b, tol, P * (L - XC)) for a, b in zip(mc, want_m))) and \
                all(close(a, b, 1e-9, P) for a, b in zip(fn, want_f)) and \
                all(close(a, b, 1e-9, P * (L - XC)) for a, b in zip(mnc, want_m)) and \
                close(s['area'], 2.0, 1e-12, 1.0) and \
                all(close(a, b, 1e-12, 1.0) for a, b in zip(cg, [XC, 0.5, 1.0])) and \
                close(s['nx'], sign, 1e-12, 1.0)
            if not ok:
                failures.append('%s %s: F %s, nodal %s (want %s), M about c %s, nodal %s (want %s)' %
                                (job, name, f, fn, want_f, mc, mnc, want_m))
    failures += refusals(exe, outdir)
    for msg in failures:
        print('FAIL ' + msg)
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
