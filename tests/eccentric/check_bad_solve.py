#!/usr/bin/env python3
"""Decks whose errors show only once they are solved: constraint errors found
when the transform is built (a DOF that a node does not carry, a dependent DOF
already made dependent by a support or contact, a cycle, terms that cancel
through the substitutions; tests/eccentric/bad), studies of which no step can
be solved (tests/partial/bad). Solved (not --check), they must exit with the
status of their first line `** expect: STATUS MESSAGE`, print MESSAGE on
stderr and nothing that looks like a crash, write no listing, and print
exactly `** errors: N` error lines when the deck says so.

usage: check_bad_solve.py SUPERJOIN DECK_DIR WORK_DIR
"""
import glob
import os
import re
import subprocess
import sys

CRASH = re.compile(r'runtime error|backtrace|segmentation|sanitizer|error termination', re.I)


def main(argv):
    exe, deck_dir, work = os.path.abspath(argv[1]), argv[2], os.path.abspath(argv[3])
    os.makedirs(work, exist_ok=True)
    fails = 0
    decks = sorted(glob.glob(os.path.join(deck_dir, '*.deck')))
    for deck in decks:
        name = os.path.basename(deck)
        with open(deck) as f:
            lines = f.read().splitlines()
        m = re.match(r'^\*\* expect: (\d+) (.+)$', lines[0])
        if not m:
            print('FAIL: %s: first line must be ** expect: STATUS MESSAGE' % name)
            fails += 1
            continue
        status, message = int(m.group(1)), m.group(2)
        nerr = None
        for line in lines[1:]:
            e = re.match(r'^\*\* errors: (\d+)$', line)
            if e:
                nerr = int(e.group(1))
        lst = os.path.join(work, name + '.lst')
        if os.path.exists(lst):
            os.remove(lst)
        r = subprocess.run([exe, '-q', name, '-o', lst], cwd=os.path.dirname(os.path.abspath(deck)),
                           capture_output=True, text=True)
        problems = []
        if r.returncode != status:
            problems.append('exit %d, expected %d' % (r.returncode, status))
        if message not in r.stderr:
            problems.append('stderr lacks: ' + message)
        if nerr is not None and r.stderr.count(': error:') != nerr:
            problems.append('%d error lines, expected %d' % (r.stderr.count(': error:'), nerr))
        if os.path.exists(lst):
            problems.append('a listing was written')
        if CRASH.search(r.stderr + r.stdout):
            problems.append('crash output')
        if problems:
            fails += 1
            print('FAIL: %s: %s\n--- stderr:\n%s' % (name, '; '.join(problems), r.stderr))
        else:
            print('ok: %s: %s' % (name, r.stderr.strip().splitlines()[0]))
    if not decks:
        print('FAIL: no decks in ' + deck_dir)
        return 1
    return 1 if fails else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
