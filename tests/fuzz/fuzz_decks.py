#!/usr/bin/env python3
"""Mutation fuzzer for superjoin decks.

Starting from the verification decks, every mutant applies one to three
mutations (delete, duplicate or swap lines, truncate, flip bytes, extreme or
malformed values, empty fields, overlong lines, undefined names, duplicate ids,
include cycles, self-contacts) and is solved by the binary. Each mutant must end
with exit status 0, 1, 3 or 5 (inaccurate, listing written) within the time bound, status 1 must come with a
'file:line: error:' message, and the output must show no Fortran runtime error,
signal or sanitizer report. A failing mutant is kept in the work directory.

usage: fuzz_decks.py SUPERJOIN SEED_DIR WORK_DIR [--count N] [--seed S] [--timeout T]
"""
import argparse
import glob
import os
import random
import re
import shutil
import subprocess
import sys

VALUES = ['1e308', '-1e308', '1e-300', '-1', '0', '-0', 'nan', 'NaN', 'inf', '-Infinity',
          '1e999', '2147483647', '2147483648', '99999999999999999999', '1.5', '1.2.3',
          'abc', '', ' ', 'RIGID', 'rigid', '1d5', '.', '+', '\u00e9\u00e8', '\u20ac1',
          'x' * 300, '1,2,3,4,5,6,7,8', '0x10', '1e', 'e5']
CRASH_PATTERNS = re.compile(r'runtime error|backtrace|segmentation|sigsegv|sigabrt|'
                            r'addresssanitizer|leaksanitizer|undefinedbehaviorsanitizer|'
                            r'floating point exception|error termination', re.I)
MESSAGE = re.compile(r'^[^\s:][^:]*:\d+: error: ', re.M)


def mutate(lines, rng, name):
    """Apply one random mutation to a list of lines (in place); return extra files."""
    extra = {}
    if not lines:
        lines.append('')
    i = rng.randrange(len(lines))
    op = rng.randrange(13)
    if op == 0:
        del lines[i]
    elif op == 1:
        lines.insert(i, lines[rng.randrange(len(lines))])
    elif op == 2:
        j = rng.randrange(len(lines))
        lines[i], lines[j] = lines[j], lines[i]
    elif op == 3:
        del lines[i:]
    elif op == 4:
        text = lines[i]
        if text:
            p = rng.randrange(len(text))
            lines[i] = text[:p] + chr(rng.randrange(1, 256)) + text[p + 1:]
    elif op == 5:
        fields = lines[i].split(',')
        fields[rng.randrange(len(fields))] = rng.choice(VALUES)
        lines[i] = ','.join(fields)
    elif op == 6:
        fields = lines[i].split(',')
        fields[rng.randrange(len(fields))] = ''
        lines[i] = ','.join(fields)
    elif op == 7:
        lines[i] = lines[i] + ',' + '9' * rng.choice([10, 1000, 100000])
    elif op == 8:
        lines[i] = re.sub(r'NAME=\w+', 'NAME=' + rng.choice(['UNDEFINED', 'X', 'A.B', '']), lines[i])
        lines[i] = re.sub(r'(MASTER|SLAVE|MATERIAL|ELSET|ORIENTATION)=\w+',
                          r'\1=' + rng.choice(['NOWHERE', 'MAIN', 'I']), lines[i])
    elif op == 9:
        # duplicate an id line: a data line starting with a number
        data = [k for k, t in enumerate(lines) if re.match(r'\s*\d+\s*,', t)]
        if data:
            k = rng.choice(data)
            lines.insert(k + 1, lines[k])
    elif op == 10:
        inc = name + '.inc'
        extra[inc] = '*INCLUDE, INPUT=' + inc + '\n'
        lines.insert(i, '*INCLUDE, INPUT=' + inc)
    elif op == 11:
        # self-contact or contact to the same node
        m = re.match(r'\s*(\w+)\s*,\s*(\w+)\s*,(.*)', lines[i])
        if m:
            lines[i] = '%s, %s,%s' % (m.group(1), m.group(1), m.group(3))
        else:
            lines.insert(i, '*CONTACT, NAME=SELF, MASTER=I, SLAVE=I')
            lines.insert(i + 1, ' 1, 1, 1, 6, RIGID')
    else:
        lines.insert(i, rng.choice(['*STEP', '*END STEP', '*SUBSTRUCTURE, NAME=Z',
                                    '*END SUBSTRUCTURE', '*NODE', '*CLOAD', '*SUPPORT',
                                    '*ELEMENT, TYPE=B33', '**', '*', '*HEADING']))
    return extra



def partial_listing(path):
    """A listing of a run that exits 3 must mark its failed steps NOT SOLVED."""
    with open(path, errors="replace") as f:
        return any(line.startswith("NOT SOLVED") for line in f)

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('binary')
    ap.add_argument('seed_dir')
    ap.add_argument('work_dir')
    ap.add_argument('--count', type=int, default=2000)
    ap.add_argument('--seed', type=int, default=20261121)
    ap.add_argument('--timeout', type=float, default=20.0)
    args = ap.parse_args()
    args.binary = os.path.abspath(args.binary)

    seeds = sorted(glob.glob(os.path.join(args.seed_dir, '*.deck')))
    if not seeds:
        print('no seed decks in ' + args.seed_dir)
        return 2
    corpus = [open(p, encoding='utf-8').read().split('\n') for p in seeds]
    shutil.rmtree(args.work_dir, ignore_errors=True)
    os.makedirs(args.work_dir)
    rng = random.Random(args.seed)
    failures = 0
    statuses = {}
    for k in range(args.count):
        lines = list(rng.choice(corpus))
        name = 'm%06d' % k
        extra = {}
        for _ in range(rng.randint(1, 3)):
            extra.update(mutate(lines, rng, name))
        deck = os.path.join(args.work_dir, name + '.deck')
        with open(deck, 'w', encoding='utf-8', errors='surrogateescape') as f:
            f.write('\n'.join(lines))
        for fname, text in extra.items():
            with open(os.path.join(args.work_dir, fname), 'w') as f:
                f.write(text)
        lst = os.path.join(args.work_dir, name + '.lst')
        try:
            r = subprocess.run([args.binary, '-q', name + '.deck', '-o', name + '.lst'],
                               cwd=args.work_dir, capture_output=True, timeout=args.timeout)
            status, err = r.returncode, r.stderr.decode('utf-8', 'replace') + r.stdout.decode('utf-8', 'replace')
        except subprocess.TimeoutExpired:
            status, err = 'timeout', ''
        statuses[status] = statuses.get(status, 0) + 1
        reason = None
        if status == 'timeout':
            reason = 'no answer within %g s' % args.timeout
        elif status not in (0, 1, 3, 5):
            reason = 'exit status %s' % status
        elif CRASH_PATTERNS.search(err):
            reason = 'crash output'
        elif status == 1 and not MESSAGE.search(err):
            reason = 'status 1 without a file:line: error: message'
        elif status not in (0, 3, 5) and os.path.exists(lst):
            reason = 'failed run left a listing'
        elif status == 3 and os.path.exists(lst) and not partial_listing(lst):
            # exit 3 keeps a listing only for a study whose solved steps are
            # written and whose failed ones are marked NOT SOLVED
            reason = 'mechanism run left a listing without a NOT SOLVED step'
        if reason:
            failures += 1
            print('FAIL %s: %s\n%s' % (deck, reason, err[:500]))
        else:
            for f in [deck, lst] + [os.path.join(args.work_dir, e) for e in extra]:
                if os.path.exists(f):
                    os.remove(f)
    summary = ', '.join('%s: %d' % (s, n) for s, n in sorted(statuses.items(), key=lambda t: str(t[0])))
    print('fuzz: %d mutants (seed %d), exit statuses %s' % (args.count, args.seed, summary))
    print('%d passed, %d failed' % (args.count - failures, failures))
    return 1 if failures else 0


if __name__ == '__main__':
    sys.exit(main())
