#!/usr/bin/env python3
"""Numerical stress tests: sweep one variable of a structure (joint stiffness g,
stiffness contrast, slenderness, a near-hinge) over both formulations and every
solver backend, and compare with the exact answer.

For every run it records the exit status, the relative error of the probe
node's displacements against the exact answer (max over translations and
rotations, each relative to the largest exact component of its kind), and the
health block of the listing (relative residual before/after refinement,
refinement steps, EPSILON, MAXRATIO, condition estimate, warnings).

Verdict per run:
  accurate  exit 0 and error <= ACCURATE (1e-8)
  warned    exit 0 or 5 (judged inaccurate), error above it, and the listing has a WARNING
  refused   exit 3 with a message naming the location, on a mechanism (right)
  breakdown exit 3 on a structure that has an answer (PENALTY past 1/eps: the
            factorization breaks down or MAXRATIO is fatal; wrong for TRANSFORM)
  SILENT    exit 0, error above ACCURATE and no warning: a silent wrong answer
  compliant exit 0, no warning, on a case whose exact answer is only known in
            the RIGID limit (the stiffened panel below extra['judged_from']):
            rel_error is then the joint's own effect, not judged
  WRONG-REFUSAL  a mechanism that was "solved" without a warning
usage: sweep.py [--case NAME] [--values v1,v2..] [--solvers ...] [--formulations ...]
                [--bin SUPERJOIN] [--work DIR] [--csv FILE]
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))
ACCURATE = 1.0e-8
EXTRA_ARGS = []   # options for every run under test (--args), not for the references
FIELDS = ['case', 'value', 'formulation', 'solver', 'status', 'rel_error', 'residual', 'residual0',
          'refinements', 'epsilon', 'maxratio', 'cond', 'verdict', 'warning', 'message']
HEALTH = {
    'residual': re.compile(r'^\s*relative residual\s+(\S+)'),
    'residual0': re.compile(r'^\s*residual before refinement\s+(\S+)\s+\((\d+) refinement steps kept of (\d+)'),
    'epsilon': re.compile(r'^\s*EPSILON \(energy error\)\s+(\S+)'),
    'maxratio': re.compile(r'^\s*MAXRATIO\s+(\S+)'),
    'cond': re.compile(r'^\s*condition estimate \(1-norm\)\s+(\S+)'),
}


def parse_listing(path):
    """Worst value over the steps of each health figure, and the warnings."""
    out = {'refinements': '0/0', 'warning': ''}
    with open(path) as f:
        for line in f:
            for key, rx in HEALTH.items():
                m = rx.match(line)
                if m:
                    v = float(m.group(1))
                    out[key] = max(out.get(key, v), v, key=abs) if key != 'residual0' else v
                    if key == 'residual0':
                        out['refinements'] = '%s/%s' % (m.group(2), m.group(3))
            if line.strip().startswith('WARNING:') and not out['warning']:
                out['warning'] = line.strip()[len('WARNING:'):].strip()
    out.setdefault('residual0', out.get('residual'))
    return out


def parse_displacements(path, probe):
    with open(path) as f:
        for row in csv.DictReader(f):
            if row['substructure'].upper() == probe[0].upper() and int(row['node']) == probe[1]:
                return [float(row[k]) for k in ('u1', 'u2', 'u3', 'ur1', 'ur2', 'ur3')]
    raise KeyError('probe %s.%d not in %s' % (probe[0], probe[1], path))


def rel_error(u, ex):
    err = 0.0
    for block in (slice(0, 3), slice(3, 6)):
        ref = max(abs(x) for x in ex[block])
        if ref == 0.0:
            continue
        err = max(err, max(abs(a - b) for a, b in zip(u[block], ex[block])) / ref)
    return err


_REFERENCE = {}


def reference(binary, case, work, tag):
    """Probe displacements of a case's reference deck (dense LAPACK, solved once per deck)."""
    key = (binary, case.extra['reference_deck'])
    if key not in _REFERENCE:
        tag = '%s_reference%d' % (tag, len(_REFERENCE))
        deck = os.path.join(work, tag + '.deck')
        with open(deck, 'w') as f:
            f.write(case.extra['reference_deck'])
        csvdir = os.path.join(work, tag + '_csv')
        p = subprocess.run([binary, '-q', deck, '-o', os.path.join(work, tag + '.lst'), '--csv', csvdir,
                            '--solver', 'lapack'], capture_output=True, text=True)
        if p.returncode != 0:
            sys.exit('sweep.py: reference deck of %s failed: %s' % (tag, p.stderr.strip()))
        _REFERENCE[key] = parse_displacements(os.path.join(csvdir, 'displacements.csv'), case.probe)
    return _REFERENCE[key]


def run_one(binary, case_name, value, formulation, solver, work):
    make, _ = cases.CASES[case_name]
    case = make(value)
    judged = True
    if 'reference_deck' in case.extra and case.exact is not None:
        case.exact = reference(binary, case, work, case_name)
        judged = value == cases.RIGID or float(value) == 0.0 or float(value) >= case.extra['judged_from']
    with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), 'templates', case.template + '.deck.in')) as f:
        deck_text = f.read().format(**case.subst)
    tag = '%s_%s_%s_%s' % (case_name, re.sub(r'[^A-Za-z0-9.+-]', '_', value), formulation, solver)
    deck = os.path.join(work, tag + '.deck')
    lst = os.path.join(work, tag + '.lst')
    csvdir = os.path.join(work, tag + '_csv')
    with open(deck, 'w') as f:
        f.write(deck_text)
    if os.path.exists(lst):
        os.remove(lst)
    p = subprocess.run([binary, '-q', deck, '-o', lst, '--csv', csvdir] + EXTRA_ARGS + ['--solver', solver,
                        '--formulation', formulation], capture_output=True, text=True)
    row = dict(case=case_name, value=value, formulation=formulation, solver=solver, status=p.returncode,
               rel_error='', residual='', residual0='', refinements='', epsilon='', maxratio='', cond='',
               warning='', message=' '.join(p.stderr.replace(work + os.sep, '').split())[:300])
    if p.returncode in (0, 5):
        # 5: solved and listed, but judged inaccurate (a WARNING in the listing)
        h = parse_listing(lst)
        row.update({k: h.get(k, '') for k in ('residual', 'residual0', 'refinements', 'epsilon', 'maxratio',
                                                'cond', 'warning')})
        u = parse_displacements(os.path.join(csvdir, 'displacements.csv'), case.probe)
        if case.exact is None:
            row['verdict'] = 'WRONG-REFUSAL' if not h['warning'] else 'warned'
            row['rel_error'] = 'inf'
        else:
            err = rel_error(u, case.exact)
            if not all(math.isfinite(x) for x in u):
                err = math.inf
            row['rel_error'] = '%.3e' % err
            if not judged:
                row['verdict'] = 'warned' if h['warning'] else 'compliant'
            elif err <= ACCURATE:
                row['verdict'] = 'accurate'
            elif h['warning']:
                row['verdict'] = 'warned'
            else:
                row['verdict'] = 'SILENT'
    elif p.returncode == 3:
        row['verdict'] = 'refused' if case.exact is None else 'breakdown'
    else:
        row['verdict'] = 'FAILED(%d)' % p.returncode
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--case', default='cantilever', choices=sorted(cases.CASES))
    ap.add_argument('--values', help='comma-separated values of the swept variable (default: the case\'s)')
    ap.add_argument('--solvers', default='cholmod,umfpack,lapack')
    ap.add_argument('--formulations', default='transform,penalty')
    ap.add_argument('--bin', default=os.environ.get('SUPERJOIN', os.path.join(ROOT, 'build', 'superjoin')))
    ap.add_argument('--args', default='', help='extra options for every run, e.g. "--condense yes"')
    ap.add_argument('--work', default=os.path.join(ROOT, 'build', 'stability'))
    ap.add_argument('--csv', help='output CSV (default: stdout only)')
    ap.add_argument('--quiet', action='store_true', help='no table on stdout')
    args = ap.parse_args()
    EXTRA_ARGS.extend(args.args.split())
    values = args.values.split(',') if args.values else cases.CASES[args.case][1]
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for form in args.formulations.split(','):
        for solver in args.solvers.split(','):
            for v in values:
                r = run_one(args.bin, args.case, v, form, solver, args.work)
                rows.append(r)
                if not args.quiet:
                    print('%-10s %-7s %-9s %-7s st=%d err=%-9s res=%-9s eps=%-9s maxratio=%-9s %s %s' % (
                        r['case'], r['value'], form, solver, r['status'], r['rel_error'], r['residual'],
                        r['epsilon'], r['maxratio'], r['verdict'], (r['warning'] or r['message'])[:90]))
    if args.csv:
        with open(args.csv, 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=FIELDS)
            w.writeheader()
            w.writerows(rows)
    # Failures: a silent wrong answer anywhere, a crash or deck error, and for the
    # joint sweeps anything but round-off from TRANSFORM at a finite or RIGID g.
    bad = [r for r in rows if r['verdict'] in ('SILENT', 'WRONG-REFUSAL') or r['verdict'].startswith('FAILED')
           or (r['formulation'] == 'transform' and args.case in ('cantilever', 'frame3d', 'eccentric', 'panel')
               and r['value'] not in ('0', '1e-6') and r['verdict'] not in ('accurate', 'compliant'))]
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
