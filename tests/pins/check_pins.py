#!/usr/bin/env python3
"""Solve a deck and check what its comment lines pin down in the listing and CSV.

usage: check_pins.py SUPERJOIN DECK WORKDIR [OPTION...]

OPTIONs are passed to superjoin (e.g. --condense yes, --formulation penalty).
The deck's comment lines state the expected values:

  ** let: NAME = EXPRESSION
  ** expect: TABLE KEY=VALUE... COLUMN == EXPRESSION rtol=R | atol=A
      a CSV value, as tests/examples/check_example.py reads it (the run writes
      CSV files only when the deck has such lines: without them, the run
      computes only the element results the output requests name)
  ** row: STEP | REQUEST | VAR | LABELS | V1, V2, ...
      one row of the listing's REQUESTED OUTPUT: in step STEP (name or
      number), under the request whose header starts with REQUEST (e.g.
      `*EL PRINT, ELSET=B.BRACE`), in the block of variable VAR (U, RF, S, SF,
      ...), the row whose leading words are LABELS (substructure, node or
      element id, type, end) with the values V1... (expressions; 7 printed
      digits: relative 2e-6 of the block's largest value). The rows of
      every block that a `** row:` line names must be exactly those stated,
      in that order: a row of another substructure or id fails.
  ** line: STEP | REQUEST | LABEL == EXPRESSION rtol=R
      the first number after LABEL on a line of that request's output
  ** listing: TEXT
      the listing has a line equal to TEXT (leading and trailing blanks
      ignored)
  ** listing-if: OPTIONS | TEXT
      the same, checked only in the run with exactly these OPTIONs
  ** refinement: STEP | KEPT of TRIED
      the step's NUMERICAL HEALTH says "(KEPT refinement steps kept of TRIED
      tried)"; with KEPT = 0 its relative residual is printed as the residual
      before refinement (the kept iterate's)
  ** no-listing: TEXT
      no line of the listing contains TEXT
"""
import csv
import math
import os
import re
import subprocess
import sys

LET = re.compile(r"^\*\* let:\s*([A-Za-z_]\w*)\s*=\s*(.+?)\s*$")
EXPECT = re.compile(r"^\*\* expect:\s*(\w+)((?:\s+\w+=\S+)+)\s+(\w+)\s*==\s*(.+?)\s+(rtol|atol)=(\S+)\s*$")
LINE = re.compile(r"^(.*?)\s*==\s*(.+?)\s+rtol=(\S+)\s*$")
STEP_HEAD = re.compile(r"^REQUESTED OUTPUT .* of step (\d+)\s*$")
STEP_NAME = re.compile(r"^STEP\s+(\d+)\s+(\S+)")
VARS = ("U", "RF", "CF", "S", "E", "SF", "NT", "ENER")
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")


def parse_requests(lines):
    """{(step number, request header, var): [row tokens]} and {(step, header): [lines]}."""
    blocks, texts = {}, {}
    step = header = var = None
    for line in lines:
        m = STEP_HEAD.match(line)
        if m:
            step, header, var = int(m.group(1)), None, None
            continue
        if step is None:
            continue
        if line.strip() and not line.startswith(" "):
            step = None   # the next section of the listing
            continue
        if line.startswith("  *"):
            header = line.strip()
            var = None
            texts[(step, header)] = []
            continue
        if header is None or not line.strip():
            continue
        texts[(step, header)].append(line)
        words = line.split()
        if words[0] in VARS and len(words) > 1 and not NUMBER.match(words[1]):
            var = words[0]
            blocks.setdefault((step, header, var), [])
            continue
        if var is None or words[0] == "substructure":
            continue
        blocks[(step, header, var)].append(words)
    return blocks, texts


def health_block(lines, step):
    """The NUMERICAL HEALTH lines of step number `step`."""
    current, inside, block = None, False, []
    for line in lines:
        m = STEP_NAME.match(line)
        if m:
            current = int(m.group(1))
        if line.startswith("NUMERICAL HEALTH"):
            inside = current == step
            continue
        if inside:
            if not line.strip():
                break
            block.append(line)
    return block


def step_numbers(lines):
    names = {}
    for line in lines:
        m = STEP_NAME.match(line)
        if m:
            names[m.group(2).upper()] = int(m.group(1))
    return names


def main(argv):
    if len(argv) < 4:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    exe, deck, work, opts = argv[1], argv[2], argv[3], argv[4:]
    name = os.path.splitext(os.path.basename(deck))[0]
    os.makedirs(work, exist_ok=True)
    lst = os.path.join(work, name + ".lst")
    csvdir = os.path.join(work, name + ".csv")
    with open(deck) as f:
        deck_lines = f.read().splitlines()
    cmd = [exe, "-q", os.path.basename(deck), "-o", lst] + opts
    if any(line.startswith("** expect:") for line in deck_lines):
        cmd += ["--csv", csvdir]
    r = subprocess.run(cmd, cwd=os.path.dirname(os.path.abspath(deck)), stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        print(f"FAIL: {deck}: superjoin {' '.join(opts)} exited with {r.returncode}\n{r.stderr}")
        return 1
    with open(lst) as f:
        listing = f.read().splitlines()
    if "END OF LISTING" not in listing:
        print(f"FAIL: {lst} is incomplete")
        return 1
    blocks, texts = parse_requests(listing)
    steps = step_numbers(listing)
    env = {k: getattr(math, k) for k in dir(math) if not k.startswith("_")}
    env["__builtins__"] = {}
    checks = fails = 0
    wanted_rows = {}

    def step_of(s):
        s = s.strip()
        return int(s) if s.isdigit() else steps.get(s.upper(), -1)

    def report(ok, text):
        nonlocal checks, fails
        checks += 1
        if not ok:
            fails += 1
        print(("ok: " if ok else "FAIL: ") + text)

    for lineno, line in enumerate(deck_lines, 1):
        where = f"{name}:{lineno}"
        m = LET.match(line)
        if m:
            env[m.group(1)] = eval(m.group(2), env)
        elif line.startswith("** expect:"):
            m = EXPECT.match(line)
            if not m:
                report(False, f"{where}: cannot read the expect line")
                continue
            table, filters, column, expr, kind, tol = m.groups()
            want = float(eval(expr, env))
            keys = dict(kv.split("=", 1) for kv in filters.split())
            with open(os.path.join(csvdir, table + ".csv"), newline="") as f:
                rows = [row for row in csv.DictReader(f)
                        if all(row[k].upper() == v.upper() for k, v in keys.items())]
            if len(rows) != 1:
                report(False, f"{where}: {len(rows)} rows of {table}.csv match {keys}")
                continue
            got = float(rows[0][column])
            bound = float(tol) * (abs(want) if kind == "rtol" else 1.0)
            report(abs(got - want) <= bound, f"{where}: {table} {filters.strip()} {column} = {got:.16e}, "
                   f"closed form {want:.16e}")
        elif line.startswith("** row:"):
            parts = [p.strip() for p in line[len("** row:"):].split("|")]
            if len(parts) != 5:
                report(False, f"{where}: cannot read the row line")
                continue
            key = (step_of(parts[0]), parts[1], parts[2])
            values = [float(eval(e, env)) for e in parts[4].split(",")]
            wanted_rows.setdefault(key, []).append((where, parts[3].split(), values))
        elif line.startswith("** line:"):
            parts = [p.strip() for p in line[len("** line:"):].split("|")]
            m = LINE.match(parts[2]) if len(parts) == 3 else None
            if not m:
                report(False, f"{where}: cannot read the line line")
                continue
            label, expr, tol = m.groups()
            want = float(eval(expr, env))
            got = None
            for (s, h), body in texts.items():
                if s != step_of(parts[0]) or not h.startswith(parts[1]):
                    continue
                for text in body:
                    if text.strip().startswith(label):
                        nums = [w for w in text.strip()[len(label):].split() if NUMBER.match(w)]
                        if nums:
                            got = float(nums[0])
                            break
                if got is not None:
                    break
            if got is None:
                report(False, f"{where}: no line '{label}' under {parts[1]} in step {parts[0]}")
                continue
            report(abs(got - want) <= float(tol) * abs(want), f"{where}: {label} = {got:.7e}, closed form {want:.7e}")
        elif line.startswith("** listing:"):
            text = line[len("** listing:"):].strip()
            report(any(l.strip() == text for l in listing), f"{where}: listing line '{text}'")
        elif line.startswith("** listing-if:"):
            cond, _, text = line[len("** listing-if:"):].partition("|")
            if cond.split() == opts:
                text = text.strip()
                report(any(l.strip() == text for l in listing), f"{where}: listing line '{text}'")
        elif line.startswith("** refinement:"):
            parts = [p.strip() for p in line[len("** refinement:"):].split("|")]
            kept, _, tried = parts[1].partition(" of ")
            health = health_block(listing, step_of(parts[0]))
            res = [l.split()[2] for l in health if l.strip().startswith("relative residual")]
            before = [l for l in health if l.strip().startswith("residual before refinement")]
            text = f"({kept.strip()} refinement steps kept of {tried.strip()} tried)"
            ok = len(before) == 1 and before[0].rstrip().endswith(text) and len(res) == 1
            if ok and kept.strip() == "0":
                ok = before[0].split()[3] == res[0]
            report(ok, f"{where}: step {parts[0]}: {' '.join(before).strip() or 'no refinement line'}, "
                   f"relative residual {res}")
        elif line.startswith("** no-listing:"):
            text = line[len("** no-listing:"):].strip()
            report(not any(text in l for l in listing), f"{where}: no listing line with '{text}'")

    for (step, header, var), want in wanted_rows.items():
        found = [v for k, v in blocks.items() if k[0] == step and k[1].startswith(header) and k[2] == var]
        if len(found) != 1:
            report(False, f"{want[0][0]}: {len(found)} blocks {var} under '{header}' in step {step}")
            continue
        got = found[0]
        labels_got = [row[:len(row) - len(want[0][2])] for row in got]
        labels_want = [w[1] for w in want]
        if labels_got != labels_want:
            report(False, f"{want[0][0]}: rows of {var} under '{header}' in step {step}: "
                   f"{[' '.join(l) for l in labels_got]}, stated {[' '.join(l) for l in labels_want]}")
            continue
        scale = max([abs(x) for w in want for x in w[2]] + [0.0])
        for (where, labels, values), row in zip(want, got):
            printed = [float(x) for x in row[len(labels):]]
            ok = len(printed) == len(values) and all(abs(a - b) <= 2e-6 * scale for a, b in zip(printed, values))
            report(ok, f"{where}: {var} {' '.join(labels)}: {printed}, closed form {values}")

    if checks == 0:
        print(f"FAIL: {name}: the deck states nothing to check")
        return 1
    print(f"{name}{' ' + ' '.join(opts) if opts else ''}: {checks - fails} of {checks} checks hold")
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
