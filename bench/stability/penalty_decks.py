#!/usr/bin/env python3
"""Every bundled deck (decks/*.deck) under --formulation penalty with the
default LARGE: exit status, MAXRATIO, relative residual, and the largest
translation difference from TRANSFORM relative to the largest translation.

usage: penalty_decks.py [--bin SUPERJOIN] [--work DIR]
Prints a Markdown table (doc/verification.md); exits 1 if a deck does not
exit 0 under PENALTY.
"""
import argparse
import csv
import glob
import os
import re
import subprocess
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), '..', '..'))


def translations(path):
    with open(path) as f:
        rows = list(csv.reader(f))[1:]
    return {(r[0], r[1], r[2]): [float(x) for x in r[3:6]] for r in rows}


def health(lst, name):
    with open(lst) as f:
        for line in f:
            if line.strip().startswith(name):
                return float(re.split(r'\s{2,}', line.strip())[1].split()[0])
    return float('nan')


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--bin', default=os.path.join(ROOT, 'build', 'superjoin'))
    ap.add_argument('--work', default=os.path.join(ROOT, 'build', 'penalty_decks'))
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    bad = 0
    print('| deck | exit | MAXRATIO | relative residual | max translation difference / max translation |')
    print('|---|---|---|---|---|')
    for deck in sorted(glob.glob(os.path.join(ROOT, 'decks', '*.deck'))):
        name = os.path.splitext(os.path.basename(deck))[0]
        out = {}
        for form in ('transform', 'penalty'):
            lst = os.path.join(args.work, '%s_%s.lst' % (name, form))
            csvdir = os.path.join(args.work, '%s_%s_csv' % (name, form))
            p = subprocess.run([args.bin, '-q', '--formulation', form, deck, '-o', lst, '--csv', csvdir],
                               capture_output=True, text=True)
            out[form] = (p.returncode, lst, csvdir)
        status = out['penalty'][0]
        if status != 0 or out['transform'][0] != 0:
            bad += 1
            print('| `%s` | %d | | | |' % (name, status))
            continue
        t = translations(os.path.join(out['transform'][2], 'displacements.csv'))
        q = translations(os.path.join(out['penalty'][2], 'displacements.csv'))
        umax = max(abs(x) for v in t.values() for x in v)
        diff = max(abs(a - b) for k in t for a, b in zip(t[k], q[k]))
        print('| `%s` | %d | %.1e | %.1e | %.1e |' % (name, status, health(out['penalty'][1], 'MAXRATIO'),
                                                  health(out['penalty'][1], 'relative residual'),
                                                  diff / umax if umax > 0 else 0.0))
    return 1 if bad else 0


if __name__ == '__main__':
    sys.exit(main())
