#!/usr/bin/env python3
"""Generate decks that probe the limits of the superjoin deck reader.

usage: gen_limits.py KIND OUT [options]

KIND
  chain     a bar of N T2D2 elements (N+1 nodes) along x from 0 to L, fixed at
            x = 0, axial load P at x = L, every node held in y (one *BOUNDARY
            line per node). Node and element ids are distinct random ids near
            2**31-1, every card's lines in shuffled order. About 3 N lines.
            --elements N (default 700000), --seed S. Exact solution (linear
            elements are exact here): u1(x) = P x / (E A), axial force P in
            every element; check_chain.py checks every node and element.
  sparse    two-element cantilever whose node ids are 1, 2**30 and 2**31-1:
            any allocation by the largest id costs gigabytes.
  id2p31    a deck that references node 2**31 in an *ELEMENT line (must be refused
            with file:line).
  include   a chain of --depth D nested *INCLUDE files (OUT, OUT.1.inc, ...).
  longline  a valid deck with one comment-free *HEADING line of --bytes B
            characters (default 10 MB) after the keyword.
  longdata  a *NODE data line of --bytes B characters (a node id padded with
            blanks before its comma): must be read or refused, never crash.
  equation  a C3D8 cube (substructure S, its base held) whose top node 8 moves
            in x as the mean of the --terms nodes of a bar of T3D2 elements
            (substructure T, pulled at its end): one *EQUATION of terms + 1
            terms, so the cube's element touches that many reduced columns.
"""
import argparse
import random
import sys

MAX_ID = 2**31 - 1
E = 2.1e11
NU = 0.3
AREA = 1.0e-2
INERTIA = 1.0e-4
LENGTH = 100.0
LOAD = 1000.0


def header(out, title):
    out.write("*HEADING\n" + title + "\n")
    out.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r, %r\n" % (E, NU))


def distinct_ids(rng, count):
    """count distinct ids in (MAX_ID - 4 count, MAX_ID], in random order."""
    span = 4 * count
    ids = rng.sample(range(MAX_ID - span + 1, MAX_ID + 1), count)
    return ids


def chain(path, n, seed):
    rng = random.Random(seed)
    node_ids = distinct_ids(rng, n + 1)       # node_ids[k] is at x = k L / n
    elem_ids = distinct_ids(rng, n)
    h = LENGTH / n
    with open(path, "w", buffering=1 << 20) as out:
        header(out, "limits: bar of %d T2D2 elements, shuffled ids near 2**31-1" % n)
        out.write("*NODE\n")
        order = list(range(n + 1))
        rng.shuffle(order)
        out.writelines("%d, %.17g, 0.0\n" % (node_ids[k], k * h) for k in order)
        out.write("*ELEMENT, TYPE=T2D2, ELSET=CHAIN\n")
        order = list(range(n))
        rng.shuffle(order)
        out.writelines("%d, %d, %d\n" % (elem_ids[k], node_ids[k], node_ids[k + 1]) for k in order)
        out.write("*SOLID SECTION, ELSET=CHAIN, MATERIAL=STEEL\n%r\n" % AREA)
        out.write("*BOUNDARY\n%d, 1, 1\n" % node_ids[0])
        order = list(range(n + 1))
        rng.shuffle(order)
        out.writelines("%d, 2, 2\n" % node_ids[k] for k in order)
        out.write("*STEP, NAME=TIP\n*CLOAD\n%d, 1, %r\n*END STEP\n" % (node_ids[n], LOAD))


def sparse(path):
    ids = [1, 2**30, MAX_ID]
    with open(path, "w") as out:
        header(out, "limits: node ids 1, 2**30 and 2**31-1")
        out.write("*NODE\n")
        for k, i in enumerate(ids):
            out.write("%d, %r, 0.0\n" % (i, k * 1.0))
        out.write("*ELEMENT, TYPE=B23, ELSET=B\n%d, %d, %d\n%d, %d, %d\n"
                  % (MAX_ID, ids[0], ids[1], 7, ids[1], ids[2]))
        out.write("*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r\n" % (AREA, INERTIA))
        out.write("*BOUNDARY\n1, 1, 2\n1, 6, 6\n")
        out.write("*STEP\n*CLOAD\n%d, 2, %r\n*END STEP\n" % (MAX_ID, -LOAD))


def id2p31(path):
    with open(path, "w") as out:
        header(out, "limits: an element that references node 2**31")
        out.write("*NODE\n1, 0.0, 0.0\n2, 1.0, 0.0\n")
        out.write("*ELEMENT, TYPE=B23, ELSET=B\n1, 1, %d\n" % (MAX_ID + 1))
        out.write("*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r\n" % (AREA, INERTIA))


def include(path, depth):
    """OUT includes OUT.1.inc, which includes OUT.2.inc, ... down to `depth` levels."""
    base = path.rsplit("/", 1)[-1]
    names = [path] + ["%s.%d.inc" % (path, k) for k in range(1, depth + 1)]
    for k, name in enumerate(names):
        with open(name, "w") as out:
            if k == 0:
                header(out, "limits: *INCLUDE nested %d levels deep" % depth)
            out.write("** level %d\n" % k)
            if k < depth:
                out.write("*INCLUDE, INPUT=%s.%d.inc\n" % (base, k + 1))
            else:
                out.write("*NODE\n1, 0.0, 0.0\n2, 1.0, 0.0\n")
                out.write("*ELEMENT, TYPE=B23, ELSET=B\n1, 1, 2\n")
                out.write("*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r\n" % (AREA, INERTIA))
                out.write("*BOUNDARY\n1, 1, 2\n1, 6, 6\n")


def small_model(out):
    out.write("*NODE\n1, 0.0, 0.0\n2, 1.0, 0.0\n")
    out.write("*ELEMENT, TYPE=B23, ELSET=B\n1, 1, 2\n")
    out.write("*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r\n" % (AREA, INERTIA))
    out.write("*BOUNDARY\n1, 1, 2\n1, 6, 6\n*STEP\n*CLOAD\n2, 2, -1.0\n*END STEP\n")


def longline(path, nbytes):
    with open(path, "w") as out:
        out.write("*HEADING\n")
        out.write("x" * nbytes + "\n")
        out.write("*MATERIAL, NAME=STEEL\n*ELASTIC\n%r, %r\n" % (E, NU))
        small_model(out)


def longdata(path, nbytes):
    with open(path, "w") as out:
        header(out, "limits: a node data line of %d bytes" % nbytes)
        out.write("*NODE\n1" + " " * nbytes + ", 0.0, 0.0\n2, 1.0, 0.0\n")
        out.write("*ELEMENT, TYPE=B23, ELSET=B\n1, 1, 2\n")
        out.write("*BEAM SECTION, ELSET=B, MATERIAL=STEEL\n%r, %r\n" % (AREA, INERTIA))
        out.write("*BOUNDARY\n1, 1, 2\n1, 6, 6\n*STEP\n*CLOAD\n2, 2, -1.0\n*END STEP\n")


def equation(path, terms):
    with open(path, "w") as out:
        header(out, "limits: a solid's node tied to the mean of %d nodes by one *EQUATION" % terms)
        out.write("*SUBSTRUCTURE, NAME=S\n*NODE\n")
        for i, (x, y, z) in enumerate([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0),
                                       (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]):
            out.write("%d, %d, %d, %d\n" % (i + 1, x, y, z))
        out.write("*ELEMENT, TYPE=C3D8, ELSET=B\n1, 1, 2, 3, 4, 5, 6, 7, 8\n")
        out.write("*SOLID SECTION, ELSET=B, MATERIAL=STEEL\n\n*END SUBSTRUCTURE\n")
        out.write("*SUBSTRUCTURE, NAME=T\n*NODE\n")
        for k in range(terms + 1):
            out.write("%d, %r, 5.0, 0.0\n" % (k + 1, 0.01 * k))
        out.write("*ELEMENT, TYPE=T3D2, ELSET=R\n")
        for k in range(terms):
            out.write("%d, %d, %d\n" % (k + 1, k + 1, k + 2))
        out.write("*SOLID SECTION, ELSET=R, MATERIAL=STEEL\n%r\n*END SUBSTRUCTURE\n" % AREA)
        terms_text = ["S.8, 1, 1.0"] + ["T.%d, 1, %r" % (k + 2, -1.0 / terms) for k in range(terms)]
        out.write("*EQUATION\n%d\n" % (terms + 1))
        for i in range(0, len(terms_text), 4):
            out.write(", ".join(terms_text[i:i + 4]) + "\n")
        out.write("*BOUNDARY\n")
        for n in range(1, 5):
            out.write("S.%d, 1, 3\n" % n)
        out.write("T.1, 1, 3\n")
        for k in range(2, terms + 2):
            out.write("T.%d, 2, 3\n" % k)
        out.write("*STEP, NAME=P\n*CLOAD\nS.8, 2, %r\nT.%d, 1, %r\n*END STEP\n" % (LOAD, terms + 1, LOAD / 100))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("kind", choices=["chain", "sparse", "id2p31", "include", "longline", "longdata", "equation"])
    p.add_argument("out")
    p.add_argument("--elements", type=int, default=700000)
    p.add_argument("--seed", type=int, default=20261122)
    p.add_argument("--depth", type=int, default=17)
    p.add_argument("--bytes", type=int, default=10 * 1024 * 1024)
    p.add_argument("--terms", type=int, default=6000)
    a = p.parse_args()
    if a.kind == "chain":
        chain(a.out, a.elements, a.seed)
    elif a.kind == "sparse":
        sparse(a.out)
    elif a.kind == "id2p31":
        id2p31(a.out)
    elif a.kind == "include":
        include(a.out, a.depth)
    elif a.kind == "longline":
        longline(a.out, a.bytes)
    elif a.kind == "equation":
        equation(a.out, a.terms)
    else:
        longdata(a.out, a.bytes)
    return 0


if __name__ == "__main__":
    sys.exit(main())
