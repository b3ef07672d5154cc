#!/usr/bin/env python3
"""Instances of one S4 part whose drilling edge masks differ (issue 13,
src/elements/drill_mask.f90, src/substructure/cache.f90).

The part is the MacNeal-Harder trapezoidal cantilever (6 x 1 S4, in-plane tip
shear, root clamped). Instance I1 also fixes UY along its bottom edge, so its
bottom edges are straight (restrained-edge rule); instance I2 does not, so its
bottom edges bend with theta_z. The two instances must not share a
condensation: I2's tip deflection must equal that of the same strip modelled
as a plain substructure (to 1e-9) and the MacNeal-Harder ratio of
doc/verification.md (0.8814); I2's element resultants must equal the plain
substructure's too (to 1e-8 of the largest: the instances placed alike share
one result operator per element only when their masks agree,
src/analysis/recover.f90). Exit status 1 on failure.

usage: drill_instances.py SUPERJOIN WORKDIR
"""
import csv
import os
import subprocess
import sys

E, NU, T = 1.0e7, 0.3, 0.1
D = [0.0, 0.2, -0.2, 0.2, -0.2, 0.2, 0.0]
REF, RATIO, TOL_RATIO, TOL_SAME = 0.1081, 0.8814, 1.0e-3, 1.0e-9


def strip_body():
    lines = ["*NODE"]
    for i in range(7):
        lines.append(f"{i + 1}, {i - D[i] / 2}, 0.0, 0.0")
        lines.append(f"{i + 11}, {i + D[i] / 2}, 0.2, 0.0")
    lines.append("*ELEMENT, TYPE=S4, ELSET=ALL")
    for i in range(1, 7):
        lines.append(f"{i}, {i}, {i + 1}, {i + 11}, {i + 10}")
    lines += ["*NSET, NSET=ROOT", "1, 11", "*NSET, NSET=TIP", "7, 17",
              "*NSET, NSET=BOT", "2, 3, 4, 5, 6, 7",
              "*SHELL SECTION, ELSET=ALL, MATERIAL=M", f"{T}"]
    return lines


def deck(instances):
    lines = ["*HEADING", "drilling edge masks of two instances of one part",
             "*MATERIAL, NAME=M", "*ELASTIC", f"{E}, {NU}"]
    if instances:
        lines += ["*PART, NAME=STRIP"] + strip_body() + ["*END PART", "*ASSEMBLY, NAME=A",
                  "*INSTANCE, NAME=I1, PART=STRIP", "*END INSTANCE",
                  "*INSTANCE, NAME=I2, PART=STRIP", "0.0, 5.0, 0.0", "*END INSTANCE", "*END ASSEMBLY"]
    else:
        for name in ("I1", "I2"):
            lines += [f"*SUBSTRUCTURE, NAME={name}"] + strip_body() + ["*END SUBSTRUCTURE"]
    lines += ["*BOUNDARY", "I1.ROOT, 1, 6", "I2.ROOT, 1, 6", "I1.BOT, 2, 2",
              "*STEP", "*STATIC", "*CLOAD", "I1.TIP, 1, 0.5", "I2.TIP, 2, 0.5", "*END STEP"]
    return "\n".join(lines) + "\n"


def tip(exe, work, name, text):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, name + "_csv")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, name + ".lst"), path],
                       capture_output=True, text=True)
    if r.returncode != 0:
        raise SystemExit(f"{name}: exit {r.returncode}: {r.stderr.strip()[:300]}")
    with open(os.path.join(out, "plate_results.csv")) as f:
        res = [[float(v) for v in row[3:]] for row in csv.reader(f) if row[1] == "I2"]
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            if row["substructure"] == "I2" and int(row["node"]) == 17:
                return float(row["u2"]), res
    raise SystemExit(f"{name}: I2 node 17 not in the results")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    inst, inst_res = tip(exe, work, "instances", deck(True))
    plain, plain_res = tip(exe, work, "plain", deck(False))
    ok = True
    big = max(abs(v) for row in plain_res for v in row)
    worst = max((abs(a - b) for ra, rb in zip(inst_res, plain_res) for a, b in zip(ra, rb)), default=big)
    print(f"I2 resultants: largest difference {worst / big:.2e} of the largest ({len(inst_res)} elements)")
    if len(inst_res) != len(plain_res) or len(plain_res) == 0 or worst > 1.0e-8 * big:
        print("FAIL: the instance's element resultants do not match the plain substructure's")
        ok = False
    print(f"I2 tip: instances {inst:.12e}  plain substructures {plain:.12e}  ratio {inst / REF:.4f}")
    if abs(inst - plain) > TOL_SAME * abs(plain):
        print("FAIL: the instance of the part does not match the plain substructure")
        ok = False
    if abs(inst / REF - RATIO) > TOL_RATIO:
        print(f"FAIL: ratio {inst / REF:.4f} is not the drilling membrane's {RATIO}")
        ok = False
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
