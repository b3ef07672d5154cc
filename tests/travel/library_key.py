#!/usr/bin/env python3
"""The condensation library's input key (issue 26, --library DIR).

A part loaded from the library is not assembled: its key hashes the inputs
of its condensation (src/substructure/library_key.f90). Three condensed parts:
A, a C3D8 block of orthotropic material in turned axes (*ORIENTATION); B, an
isotropic C3D8 block joined to A along a face; C, a CPS4 panel joined to B
along an edge. After a base run has filled the library, each input class is
flipped alone (coordinate, E, nu, thickness, orientation angle, element
option, a support inside a part, the boundary DOF set, the solver): the parts
it touches are condensed anew (a new key: "condensed and stored"), the others
loaded, and the results equal a run without the library to round-off. The
base deck again loads every part, with the base run's results to the byte.
The safety net: an entry whose sample element stiffnesses differ is not used
(stale, condensed anew); under --library-verify an entry whose assembled
stiffness hash differs is not used, and a sound one is loaded.

usage: library_key.py SUPERJOIN WORKDIR
"""
import hashlib
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import equiv  # noqa: E402

RTOL = 1e-10
N = 3          # elements along each edge of a block
FAILED = []
BASE = dict(coord=0.0, e=2.0e11, nu=0.3, t=0.05, angle=30.0, etype="C3D8", support=False, dofs=3, u0=0.0)


def check(ok, what):
    print(("ok: " if ok else "FAIL: ") + what)
    if not ok:
        FAILED.append(what)


def block(name, x0, etype, material, orient, p):
    """A cube [x0, x0+1]^3 of N^3 elements; FACE0 (x = x0) and FACE1 (x = x0+1)
    node sets in the same order, EDGE1 the nodes of FACE1 at z = 0."""
    out = [f"*SUBSTRUCTURE, NAME={name}", "*NODE"]
    nid = lambda i, j, k: 1 + i + (N + 1) * (j + (N + 1) * k)  # noqa: E731
    for k in range(N + 1):
        for j in range(N + 1):
            for i in range(N + 1):
                x, y, z = x0 + i / N, j / N, k / N
                if name == "B" and (i, j, k) == (1, 1, 1):
                    x += p["coord"]
                out.append(f"{nid(i, j, k)}, {x!r}, {y!r}, {z!r}")
    out.append(f"*ELEMENT, TYPE={etype}, ELSET=SOLID")
    e = 0
    for k in range(N):
        for j in range(N):
            for i in range(N):
                e += 1
                c = [nid(i, j, k), nid(i + 1, j, k), nid(i + 1, j + 1, k), nid(i, j + 1, k),
                     nid(i, j, k + 1), nid(i + 1, j, k + 1), nid(i + 1, j + 1, k + 1), nid(i, j + 1, k + 1)]
                out.append(f"{e}, " + ", ".join(map(str, c)))
    for side, i in (("FACE0", 0), ("FACE1", N)):
        out += [f"*NSET, NSET={side}", ", ".join(str(nid(i, j, k)) for k in range(N + 1) for j in range(N + 1))]
    out += ["*NSET, NSET=EDGE1", ", ".join(str(nid(N, j, 0)) for j in range(N + 1))]
    out += ["*NSET, NSET=MIDDLE", str(nid(1, 1, 1))]
    out.append(f"*SOLID SECTION, ELSET=SOLID, MATERIAL={material}" + (f", ORIENTATION={orient}" if orient else ""))
    out.append("*END SUBSTRUCTURE")
    return out


def panel(p):
    """A CPS4 panel [2, 3] x [0, 1] at z = 0; LEFT (x = 2) in the order of B's EDGE1."""
    out = ["*SUBSTRUCTURE, NAME=C", "*NODE"]
    nid = lambda i, j: 1 + i + (N + 1) * j  # noqa: E731
    for j in range(N + 1):
        for i in range(N + 1):
            out.append(f"{nid(i, j)}, {2 + i / N!r}, {j / N!r}, 0.0")
    out.append("*ELEMENT, TYPE=CPS4, ELSET=SKIN")
    e = 0
    for j in range(N):
        for i in range(N):
            e += 1
            out.append(f"{e}, {nid(i, j)}, {nid(i + 1, j)}, {nid(i + 1, j + 1)}, {nid(i, j + 1)}")
    out += ["*NSET, NSET=LEFT", ", ".join(str(nid(0, j)) for j in range(N + 1))]
    out += ["*NSET, NSET=RIGHT", ", ".join(str(nid(N, j)) for j in range(N + 1))]
    out += ["*SOLID SECTION, ELSET=SKIN, MATERIAL=ISO", repr(p["t"]), "*END SUBSTRUCTURE"]
    return out


def deck(p):
    a = math.radians(p["angle"])
    out = ["*HEADING", "tests/travel/library_key.py: blocks A, B and panel C",
           "*MATERIAL, NAME=ISO", "*ELASTIC", f"{p['e']!r}, {p['nu']!r}",
           "*MATERIAL, NAME=ORT", "*ELASTIC, TYPE=ORTHO",
           "3.0e11, 1.0e11, 2.0e11, 0.9e11, 0.8e11, 1.5e11, 0.6e11, 0.5e11", "0.4e11",
           "*ORIENTATION, NAME=AXES", f"{math.cos(a)!r}, {math.sin(a)!r}, 0.0, {-math.sin(a)!r}, {math.cos(a)!r}, 0.0"]
    out += block("A", 0.0, p["etype"], "ORT", "AXES", p)
    out += block("B", 1.0, "C3D8", "ISO", None, p)
    out += panel(p)
    out += ["*CONTACT, NAME=AB, MASTER=A, SLAVE=B"] + [f"FACE1, FACE0, {d}, {d}, RIGID" for d in range(1, p["dofs"] + 1)]
    out += ["*CONTACT, NAME=BC, MASTER=B, SLAVE=C", "EDGE1, LEFT, 1, 1, RIGID", "EDGE1, LEFT, 2, 2, 1e10"]
    out += ["*BOUNDARY", "A.FACE0, 1, 3"]
    if p["dofs"] < 3:
        out += ["B.FACE1, 3, 3"]
    if p["support"]:
        out += ["B.MIDDLE, 3, 3" + (f", {p['u0']!r}" if p["u0"] else "")]
    out += ["*STEP, NAME=PULL", "*CLOAD", "C.RIGHT, 1, 1000.0", "C.RIGHT, 2, 300.0", "B.FACE1, 3, -50.0",
            "*END STEP"]
    return "\n".join(out) + "\n"


def solve(binary, text, name, work, library=None, extra=()):
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as fh:
        fh.write(text)
    lst = os.path.join(work, name + ".lst")
    csvdir = os.path.join(work, name + ".csv")
    cmd = [binary, "-q", "--condense", "yes", path, "-o", lst, "--csv", csvdir, *extra]
    if library:
        cmd += ["--library", library]
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        print(f"FAIL: {name} exited with {r.returncode}: {r.stderr.strip()[:400]}")
        sys.exit(1)
    with open(lst) as fh:
        return fh.read().splitlines(), csvdir


def notes(lines, text):
    return sum(1 for line in lines if "library:" in line and text in line)


def stored(lines):
    return sorted(line.split("substructure ")[1].split()[0] for line in lines
                  if "library:" in line and "condensed and stored" in line)


def body(lines):
    return [line for line in lines if "library:" not in line]


def same_csv(a, b):
    fa, fb = sorted(os.listdir(a)), sorted(os.listdir(b))
    return fa == fb and all(open(os.path.join(a, f), "rb").read() == open(os.path.join(b, f), "rb").read()
                            for f in fa)


def agrees(a_csv, b_csv):
    worst = 0.0
    for f in sorted(os.listdir(b_csv)):
        w, msg = equiv.compare_file(os.path.join(a_csv, f), os.path.join(b_csv, f), RTOL, 1e-14)
        if msg:
            return False, f"{f}: {msg}"
        worst = max(worst, w)
    return True, f"{worst:.1e}"


def restamp(data):
    return data[:-64] + hashlib.sha256(bytes(data[:-64])).hexdigest().encode()


def tamper(path, offset):
    """One hexadecimal digit of the 64 at offset changed, the checksum made right."""
    data = bytearray(open(path, "rb").read())
    data[offset] = ord("0") if data[offset] != ord("0") else ord("1")
    with open(path, "wb") as fh:
        fh.write(restamp(data))


def main():
    binary, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    lib = os.path.join(work, "lib")
    base, base_csv = solve(binary, deck(BASE), "base", work, lib)
    check(stored(base) == ["A", "B", "C"], "base run: A, B and C condensed and stored")

    flips = [("a coordinate of B", dict(coord=1e-3), (), ["B"]),
             ("E", dict(e=2.1e11), (), ["B", "C"]),
             ("nu", dict(nu=0.29), (), ["B", "C"]),
             ("the thickness of C", dict(t=0.06), (), ["C"]),
             ("the orientation angle of A", dict(angle=31.0), (), ["A"]),
             ("the element option of A (C3D8I)", dict(etype="C3D8I"), (), ["A"]),
             ("a support inside B", dict(support=True), (), ["B"]),
             ("the boundary DOF set (contact AB without DOF 3)", dict(dofs=2), (), ["A", "B"]),
             ("the solver", {}, ("--solver", "lapack"), ["A", "B", "C"])]
    for i, (what, change, extra, parts) in enumerate(flips):
        p = dict(BASE, **change)
        lines, csv = solve(binary, deck(p), f"flip{i}", work, lib, extra)
        check(stored(lines) == parts and notes(lines, "loaded from library") == 3 - len(parts),
              f"{what}: {', '.join(parts)} condensed anew (new key), the others loaded (got {stored(lines)})")
        _, plain_csv = solve(binary, deck(p), f"flip{i}_plain", work, None, extra)
        ok, worst = agrees(csv, plain_csv)
        check(ok, f"{what}: results equal a run without the library ({worst})")

    again, again_csv = solve(binary, deck(BASE), "again", work, lib)
    check(notes(again, "loaded from library") == 3 and not stored(again), "untouched deck: every part loaded")
    check(body(again) == body(base) and same_csv(again_csv, base_csv), "untouched deck: the base results to the byte")
    _, plain_csv = solve(binary, deck(BASE), "plain", work)
    ok, worst = agrees(again_csv, plain_csv)
    check(ok, f"untouched deck: results equal a run without the library ({worst})")

    # A prescribed displacement inside B: the health check's k u0 assembles k after a hit.
    p = dict(BASE, support=True, u0=1e-6)
    first, first_csv = solve(binary, deck(p), "u0_first", work, lib)
    second, second_csv = solve(binary, deck(p), "u0_second", work, lib)
    check(notes(first, "loaded from library") == 3 and notes(second, "loaded from library") == 3,
          "a prescribed displacement inside B: every part loaded (B's key is the support's: u0 is a load)")
    check(body(first) == body(second) and same_csv(first_csv, second_csv),
          "a prescribed displacement inside B: the second run's results to the byte")
    _, plain_csv = solve(binary, deck(p), "u0_plain", work)
    ok, worst = agrees(second_csv, plain_csv)
    check(ok, f"a prescribed displacement inside B: results equal a run without the library ({worst})")

    # The safety net. Entry layout: magic 8, version 8, key 64, counts 40, MAXRATIO 8,
    # sample hash 64 (offset 128), stiffness hash 64 (offset 192).
    key = [line.split("key ")[1].rstrip(")") for line in base if "library: substructure B condensed" in line][0]
    entry = os.path.join(lib, key + ".sjc")
    v, v_csv = solve(binary, deck(BASE), "verify", work, lib, ("--library-verify",))
    check(notes(v, "loaded from library") == 3 and same_csv(v_csv, base_csv),
          "--library-verify: sound entries loaded, the same results")
    tamper(entry, 128)
    s, s_csv = solve(binary, deck(BASE), "samples", work, lib)
    check(notes(s, "sample element stiffnesses differ: stale") == 1 and stored(s) == ["B"]
          and same_csv(s_csv, base_csv), "sample hash differs: B's entry not used, B condensed anew, same results")
    tamper(entry, 192)
    u, _ = solve(binary, deck(BASE), "unverified", work, lib)
    check(notes(u, "loaded from library") == 3, "stiffness hash differs, without --library-verify: loaded")
    w, w_csv = solve(binary, deck(BASE), "verified", work, lib, ("--library-verify",))
    check(notes(w, "assembled stiffness differs") == 1 and stored(w) == ["B"] and same_csv(w_csv, base_csv),
          "stiffness hash differs, --library-verify: B's entry not used, B condensed anew, same results")
    print(f"{len(FAILED)} failed")
    return 1 if FAILED else 0


if __name__ == "__main__":
    sys.exit(main())
