#!/usr/bin/env python3
"""Solve an example deck and check the closed-form values it states.

usage: check_example.py SUPERJOIN DECK WORKDIR

The deck must solve (exit status 0, a complete listing, the CSV files). Its
comment lines may define constants and expected values:

  ** let: NAME = EXPRESSION
  ** expect: TABLE KEY=VALUE... COLUMN == EXPRESSION rtol=R | atol=A

TABLE is a CSV file of `--csv` without .csv (displacements, reactions,
contact_forces, element_forces, plate_results); the KEY=VALUE filters must
select exactly one row (names compare case-insensitively), and COLUMN of that
row must equal EXPRESSION (Python syntax, math functions and the `let`
constants) within the relative tolerance R or the absolute tolerance A.
"""
import csv
import math
import os
import re
import subprocess
import sys

LET = re.compile(r"^\*\* let:\s*([A-Za-z_]\w*)\s*=\s*(.+?)\s*$")
EXPECT = re.compile(r"^\*\* expect:\s*(\w+)((?:\s+\w+=\S+)+)\s+(\w+)\s*==\s*(.+?)\s+(rtol|atol)=(\S+)\s*$")


def main(argv):
    if len(argv) != 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, deck, work = argv[1:]
    name = os.path.splitext(os.path.basename(deck))[0]
    os.makedirs(work, exist_ok=True)
    lst = os.path.join(work, name + ".lst")
    csvdir = os.path.join(work, name + ".csv")
    r = subprocess.run([exe, "-q", deck, "-o", lst, "--csv", csvdir], stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: {deck}: superjoin exited with {r.returncode}\n{r.stderr}")
        return 1
    with open(lst) as f:
        if "END OF LISTING" not in f.read():
            print(f"FAIL: {lst} is incomplete")
            return 1
    env = {k: getattr(math, k) for k in dir(math) if not k.startswith("_")}
    checks = fails = 0
    with open(deck) as f:
        lines = f.read().splitlines()
    for lineno, line in enumerate(lines, 1):
        m = LET.match(line)
        if m:
            env[m.group(1)] = eval(m.group(2), {"__builtins__": {}}, env)
            continue
        if not line.startswith("** expect:"):
            continue
        m = EXPECT.match(line)
        if not m:
            print(f"FAIL: {deck}:{lineno}: cannot read the expect line")
            fails += 1
            continue
        table, filters, column, expr, kind, tol = m.groups()
        want = float(eval(expr, {"__builtins__": {}}, env))
        keys = dict(kv.split("=", 1) for kv in filters.split())
        with open(os.path.join(csvdir, table + ".csv"), newline="") as f:
            rows = [row for row in csv.DictReader(f)
                    if all(row[k].upper() == v.upper() for k, v in keys.items())]
        checks += 1
        if len(rows) != 1:
            print(f"FAIL: {deck}:{lineno}: {len(rows)} rows of {table}.csv match {keys}")
            fails += 1
            continue
        got = float(rows[0][column])
        bound = float(tol) * (abs(want) if kind == "rtol" else 1.0)
        status = "ok" if abs(got - want) <= bound else "FAIL"
        if status == "FAIL":
            fails += 1
        rel = abs(got - want) / abs(want) if want else abs(got - want)
        print(f"{status}: {name}: {table} {filters.strip()} {column} = {got:.16e}, closed form {want:.16e}"
              f" ({'relative' if want else 'absolute'} difference {rel:.1e}, {kind} {tol})")
    if checks == 0:
        print(f"{name}: solved (the deck states no closed form)")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
