#!/usr/bin/env python3
"""A residual warning is printed in the block of the step it is about, and only there.

usage: step_residual_warning.py SUPERJOIN GEN_PANELS WORKDIR

Two S4 panels (bench/gen_panels.py --single G), A clamped, B joined to A's
edge rigidly in translation and by a rotational spring of G = 1e-3 (a near
hinge), and two load steps solved with one matrix: LOADA presses on A alone
(B hardly moves: residual at round-off), LOADB on B alone (B swings about the
near hinge: relative residual about 1e-3, above RESIDUAL_WARN = 1e-6).
- monolithic: "WARNING: relative residual R after refinement: results are
  inaccurate" in LOADB's block only, R its printed relative residual;
- condensed: "... of the whole system (condensed substructures recovered):
  results are inaccurate" in LOADB's block only, R its whole-system residual;
- both: exit status 5, the listing written, LOADA's residual below 1e-10.
The warnings are computed over the steps of one solve and attached through
a mask of the steps that exceed the limit (src/analysis/health.f90); a mask
that flags every step puts them in LOADA's block too.
- A condensed, B not (CONDENSE= on the cards, no --condense): B's swing is in
  the interface system itself, so LOADB's whole-system residual is its
  interface rows' (health's K_red q - f_red, which full_health takes over
  instead of forming the product again): both warnings in LOADB's block, the
  whole-system R at least half the interface R (interface rows left out of
  the whole system leave round-off there; a residual of another q would
  not be caught by this one-sided check).
"""
import os
import re
import subprocess
import sys

MESH = 6
G = "1e-3"
RESIDUAL_WARN = 1e-6
ROUND_OFF = 1e-10
STEPS = """*STEP, NAME=LOADA
*DLOAD
A.SKIN, P, -100
*END STEP
*STEP, NAME=LOADB
*DLOAD
B.SKIN, P, -100
*END STEP
"""
WARNINGS = {"no": r"relative residual (\S+) after refinement: results are inaccurate",
            "yes": r"relative residual (\S+) of the whole system \(condensed substructures recovered\): "
                   r"results are inaccurate"}


def step_blocks(listing):
    """{step name: its block of the listing}."""
    parts = re.split(r"^STEP \d+  (\S+)\n", listing, flags=re.M)
    return dict(zip(parts[1::2], parts[2::2]))


def interface_dominated(superjoin, deck, work):
    """A condensed, B not: LOADB's whole-system residual holds its interface residual."""
    lst = os.path.join(work, "two_steps_part.lst")
    r = subprocess.run([superjoin, "-q", deck, "-o", lst], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 5 or not os.path.exists(lst):
        return [f"A condensed only: exit {r.returncode}, want 5 with the listing written\n{r.stderr}"]
    with open(lst) as f:
        blocks = step_blocks(f.read())
    if "CONDENSE=YES" not in open(deck).read() or "LOADB" not in blocks:
        return [f"A condensed only: step blocks {sorted(blocks)}"]
    inner = re.findall(r"^  WARNING: " + WARNINGS["no"] + "$", blocks["LOADB"], re.M)
    whole = re.findall(r"^  WARNING: " + WARNINGS["yes"] + "$", blocks["LOADB"], re.M)
    print(f"A condensed only: LOADB's interface residual {inner}, whole-system residual {whole}")
    if len(inner) != 1 or len(whole) != 1:
        return [f"A condensed only: LOADB's block has {len(inner)} interface and {len(whole)} whole-system "
                "residual warnings, want 1 and 1"]
    if float(whole[0]) < 0.5 * float(inner[0]):
        return [f"A condensed only: whole-system residual {whole[0]} below half the interface residual {inner[0]}"]
    return []


def main():
    superjoin, gen, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    base = subprocess.run([sys.executable, gen, "--mesh", str(MESH), "--single", G],
                          stdout=subprocess.PIPE, text=True, check=True).stdout
    deck = os.path.join(work, "two_steps.deck")
    with open(deck, "w") as f:
        f.write(base[:base.index("*STEP")] + STEPS)
    failures = []
    part_deck = os.path.join(work, "two_steps_part.deck")
    with open(part_deck, "w") as f:
        f.write(base[:base.index("*STEP")].replace("*SUBSTRUCTURE, NAME=A\n", "*SUBSTRUCTURE, NAME=A, CONDENSE=YES\n")
                .replace("*SUBSTRUCTURE, NAME=B\n", "*SUBSTRUCTURE, NAME=B, CONDENSE=NO\n") + STEPS)
    failures += interface_dominated(superjoin, part_deck, work)
    for condense in ("no", "yes"):
        lst = os.path.join(work, f"two_steps_{condense}.lst")
        r = subprocess.run([superjoin, "-q", deck, "-o", lst, "--condense", condense],
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        what = f"--condense {condense}"
        if r.returncode != 5 or not os.path.exists(lst):
            failures.append(f"{what}: exit {r.returncode}, want 5 with the listing written\n{r.stderr}")
            continue
        with open(lst) as f:
            blocks = step_blocks(f.read())
        if sorted(blocks) != ["LOADA", "LOADB"]:
            failures.append(f"{what}: step blocks {sorted(blocks)}")
            continue
        residual = {}
        for name, block in blocks.items():
            m = re.search(r"^  relative residual +(\S+)$", block, re.M)
            residual[name] = float(m.group(1)) if m else None
        if residual["LOADA"] is None or residual["LOADA"] > ROUND_OFF:
            failures.append(f"{what}: LOADA's relative residual {residual['LOADA']}, want <= {ROUND_OFF}")
        if residual["LOADB"] is None or residual["LOADB"] <= RESIDUAL_WARN:
            failures.append(f"{what}: LOADB's relative residual {residual['LOADB']}, want > {RESIDUAL_WARN}")
        pattern = r"^  WARNING: " + WARNINGS[condense] + "$"
        in_a = re.findall(pattern, blocks["LOADA"], re.M)
        in_b = re.findall(pattern, blocks["LOADB"], re.M)
        if in_a:
            failures.append(f"{what}: LOADA's block has the residual warning of another step: {in_a}")
        if len(in_b) != 1:
            failures.append(f"{what}: LOADB's block has {len(in_b)} residual warnings, want 1")
        elif residual["LOADB"] is not None and float(in_b[0]) != residual["LOADB"]:
            failures.append(f"{what}: the warning says {in_b[0]}, LOADB's residual is {residual['LOADB']}")
        warned = re.findall(r"warning: " + WARNINGS[condense], r.stderr)
        if len(warned) != 1:
            failures.append(f"{what}: {len(warned)} residual warnings on stderr, want 1")
        print(f"{what}: residual LOADA {residual['LOADA']}, LOADB {residual['LOADB']}; warnings in LOADA "
              f"{len(in_a)}, in LOADB {len(in_b)}")
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
