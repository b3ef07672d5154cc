#!/usr/bin/env python3
"""Plate with a circular hole (Kirsch) on the gmsh mesh of decks/plate_hole.

  plate_hole.py --write-bc            regenerate decks/plate_hole/kirsch_bc.inp
  plate_hole.py SUPERJOIN WORKDIR     solve decks/plate_hole/plate_hole.deck and check it

The exact plane-stress displacements of an infinite plate with a hole of radius
a under remote tension S along x (Kirsch) are prescribed on the outer edges
Line2, Line3 and the symmetry conditions on Line1 (y = 0) and Line4 (x = 0);
the hole is free. The finite element answer must then approach the Kirsch
field inside: displacements of the hole nodes and the stresses at element
centroids (rotated into each element's frame) are compared with it.
"""
import csv
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DECKDIR = os.path.join(HERE, "..", "..", "decks", "plate_hole")
E, NU, S, RADIUS, T = 210000.0, 0.3, 100.0, 1.0, 1.0


def kirsch_u(x, y):
    """Displacements (ux, uy) of the Kirsch solution, plane stress."""
    r, th = math.hypot(x, y), math.atan2(y, x)
    mu = E / (2 * (1 + NU))
    kap = (3 - NU) / (1 + NU)
    a = RADIUS
    c = S / (4 * mu)
    ur = c * (r * ((kap - 1) / 2 + math.cos(2 * th)) + a * a / r * (1 + (1 + kap) * math.cos(2 * th))
              - a ** 4 / r ** 3 * math.cos(2 * th))
    ut = c * ((1 - kap) * a * a / r - r - a ** 4 / r ** 3) * math.sin(2 * th)
    return ur * math.cos(th) - ut * math.sin(th), ur * math.sin(th) + ut * math.cos(th)


def kirsch_stress(x, y):
    """(sx, sy, sxy) of the Kirsch solution."""
    r, th = math.hypot(x, y), math.atan2(y, x)
    q = (RADIUS / r) ** 2
    c2, s2 = math.cos(2 * th), math.sin(2 * th)
    srr = S / 2 * (1 - q) + S / 2 * (1 - 4 * q + 3 * q * q) * c2
    stt = S / 2 * (1 + q) - S / 2 * (1 + 3 * q * q) * c2
    srt = -S / 2 * (1 + 2 * q - 3 * q * q) * s2
    c, s = math.cos(th), math.sin(th)
    return (srr * c * c + stt * s * s - 2 * srt * s * c,
            srr * s * s + stt * c * c + 2 * srt * s * c,
            (srr - stt) * s * c + srt * (c * c - s * s))


def read_mesh(path):
    """Nodes {id: (x, y)}, elements {id: [nodes]}, node sets {name: [ids]} of a gmsh .inp."""
    nodes, elems, nsets = {}, {}, {}
    mode, name = None, None
    with open(path) as f:
        for line in f:
            s = line.strip()
            if not s or s.startswith("**"):
                continue
            if s.startswith("*"):
                key = s.upper()
                mode = None
                if key.startswith("*NODE"):
                    mode = "node"
                elif key.startswith("*ELEMENT"):
                    mode = "elem"
                elif key.startswith("*NSET"):
                    mode, name = "nset", s.split("=")[1].strip()
                    nsets[name] = []
                continue
            vals = [v for v in s.split(",") if v.strip()]
            if mode == "node":
                nodes[int(vals[0])] = (float(vals[1]), float(vals[2]))
            elif mode == "elem":
                elems[int(vals[0])] = [int(v) for v in vals[1:]]
            elif mode == "nset":
                nsets[name] += [int(v) for v in vals]
    return nodes, elems, nsets


def write_bc():
    nodes, _, nsets = read_mesh(os.path.join(DECKDIR, "hole.inp"))
    out = ["** Kirsch displacements on the outer edges of hole.inp (plane stress, E = 210000,",
           "** nu = 0.3, remote stress 100 along x, hole radius 1), written by",
           "** tests/shells/plate_hole.py --write-bc; the test checks it is up to date.",
           "*BOUNDARY"]
    for nid in sorted(set(nsets["Line2"]) | set(nsets["Line3"])):
        ux, uy = kirsch_u(*nodes[nid])
        if nodes[nid][0] != 0.0:      # x = 0 and y = 0 are held by the symmetry lines
            out.append(f" P.{nid}, 1, 1, {ux:.17g}")
        if nodes[nid][1] != 0.0:
            out.append(f" P.{nid}, 2, 2, {uy:.17g}")
    return "\n".join(out) + "\n"


def main():
    bc_path = os.path.join(DECKDIR, "kirsch_bc.inp")
    if sys.argv[1:] == ["--write-bc"]:
        with open(bc_path, "w") as f:
            f.write(write_bc())
        return 0
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    fails = []
    with open(bc_path) as f:
        if f.read() != write_bc():
            fails.append("decks/plate_hole/kirsch_bc.inp is not what --write-bc writes")
    deck = os.path.join(DECKDIR, "plate_hole.deck")
    out = os.path.join(work, "csv")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, "plate_hole.lst"), deck],
                       capture_output=True, text=True)
    if r.returncode != 0:
        print(f"FAIL: superjoin exit {r.returncode}: {r.stderr}")
        return 1
    nodes, elems, nsets = read_mesh(os.path.join(DECKDIR, "hole.inp"))
    disp = {}
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            disp[int(row["node"])] = (float(row["u1"]), float(row["u2"]))
    scale = S * RADIUS / E * 3.0
    worst_u = max(math.hypot(disp[n][0] - kirsch_u(*nodes[n])[0], disp[n][1] - kirsch_u(*nodes[n])[1])
                  for n in nsets["Line5"]) / scale
    u_top = disp[[n for n in nsets["Line5"] if abs(nodes[n][0]) < 1e-9][0]]
    print(f"hole nodes: largest displacement error / (3 S a / E) = {worst_u:.2e}")
    print(f"top of the hole: uy = {u_top[1]:.6e}, Kirsch {-S * RADIUS / E:.6e}")
    worst_s, at = 0.0, None
    peak = 0.0
    with open(os.path.join(out, "plate_results.csv")) as f:
        for row in csv.DictReader(f):
            ns = elems[int(row["element"])]
            cx = sum(nodes[n][0] for n in ns) / len(ns)
            cy = sum(nodes[n][1] for n in ns) / len(ns)
            dx = nodes[ns[1]][0] - nodes[ns[0]][0]
            dy = nodes[ns[1]][1] - nodes[ns[0]][1]
            ln = math.hypot(dx, dy)
            c, s = dx / ln, dy / ln
            sx, sy, sxy = kirsch_stress(cx, cy)
            ex = [sx * c * c + sy * s * s + 2 * sxy * s * c,
                  sx * s * s + sy * c * c - 2 * sxy * s * c,
                  (sy - sx) * s * c + sxy * (c * c - s * s)]
            got = [float(row["nx"]) / T, float(row["ny"]) / T, float(row["nxy"]) / T]
            err = max(abs(g - e) for g, e in zip(got, ex)) / (3 * S)
            peak = max(peak, max(abs(v) for v in got))
            if err > worst_s:
                worst_s, at = err, int(row["element"])
    print(f"centroid stresses: largest error / (3 S) = {worst_s:.2e} (element {at}); peak |stress| {peak:.2f}")
    if worst_u > 5e-3:
        fails.append(f"hole displacements off by {worst_u:.2e} of 3Sa/E (limit 5e-3)")
    if worst_s > 0.05:
        fails.append(f"centroid stresses off by {worst_s:.2e} of 3S (limit 0.05)")
    for m in fails:
        print("FAIL: " + m)
    return 1 if fails else 0


if __name__ == "__main__":
    sys.exit(main())
