#!/usr/bin/env python3
"""Write tests/decks/mpc_meanrot.deck: *MPC MEANROT (CalculiX's mean rotation
MPC, linearised) applying moments to C3D20R solids through a torque on the
extra node's DOF 1 (*CLOAD), checked against closed forms.

usage: meanrot_deck.py [OUTPUT]   (default: tests/decks/mpc_meanrot.deck)

- a tube a = 0.5, b = 1, L = 4 along z (2 x 16 x 4 elements, mid-side nodes
  on the arcs), its root z = 0 held, its tip face's 80 nodes in a MEANROT
  about z (extra node 9001 at (0, 0, 1)) with the torque T = 100: the tube's
  torsion is warping-free, so the mean rotation of the tip (the extra node's
  u1) is T L/(G J), J = pi (b^4 - a^4)/2, within the mesh's error (0.3 %);
- a cantilever 1 x 1 x 10 (2 x 2 x 10 elements) at x in [5, 6], its root
  held, its tip face in a MEANROT about y (node 9002 at (0, 1, 0)) with the
  moment M = 10: the tip's mean rotation M L/(E I), I = 1/12 (1 %: the held
  root's Poisson restraint, the tip's end effect).
E = 210000, nu = 0.3.
"""
import math
import os
import sys

E, NU = 210000.0, 0.3
A_IN, B_OUT, L_TUBE, T = 0.5, 1.0, 4.0, 100.0
L_BEAM, M = 10.0, 10.0


def hexmesh(n, pos, first, periodic=False):
    """C3D20R mesh of n = (n1, n2, n3) cells mapped by pos(u, v, w) (u, v, w in
    half-cell units); periodic: the second direction closes on itself.
    Returns ({id: xyz}, {lattice point: id}, [element node lists])."""
    ids, nodes = {}, {}

    def nid(i, j, k):
        if periodic:
            j %= 2 * n[1]
        key = (i, j, k)
        if key not in ids:
            ids[key] = first + len(ids)
            nodes[ids[key]] = pos(i, j, k)
        return ids[key]

    corners = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
    mids = [(1, 0, 0), (2, 1, 0), (1, 2, 0), (0, 1, 0), (1, 0, 2), (2, 1, 2), (1, 2, 2), (0, 1, 2),
            (0, 0, 1), (2, 0, 1), (2, 2, 1), (0, 2, 1)]
    elems = []
    for k in range(n[2]):
        for j in range(n[1]):
            for i in range(n[0]):
                elems.append([nid(2 * i + a, 2 * j + b, 2 * k + c) for a, b, c in corners + mids])
    return nodes, ids, elems


def fmt(v):
    return f"{v:.15g}"


def block(nodes, elems, first_elem, elset):
    out = [f" {n}, {fmt(x[0])}, {fmt(x[1])}, {fmt(x[2])}" for n, x in sorted(nodes.items())]
    els = [f"*ELEMENT, TYPE=C3D20R, ELSET={elset}"]
    for k, el in enumerate(elems):
        v = [first_elem + k] + el
        els.append(" " + ", ".join(str(x) for x in v[:16]) + ",")
        els.append(" " + ", ".join(str(x) for x in v[16:]))
    return out, els


def main():
    out_path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "..", "decks", "mpc_meanrot.deck")
    nt = (2, 16, 4)
    tube_nodes, tube_ids, tube_elems = hexmesh(
        nt, lambda i, j, k: (
            (A_IN + (B_OUT - A_IN) * i / (2 * nt[0])) * math.cos(math.pi * j / nt[1]),
            (A_IN + (B_OUT - A_IN) * i / (2 * nt[0])) * math.sin(math.pi * j / nt[1]),
            L_TUBE * k / (2 * nt[2])), 1, periodic=True)
    nb = (2, 2, 10)
    beam_nodes, beam_ids, beam_elems = hexmesh(
        nb, lambda i, j, k: (5.0 + i / (2 * nb[0]), j / (2 * nb[1]), L_BEAM * k / (2 * nb[2])), 5001)
    tube_root = sorted(v for (i, j, k), v in tube_ids.items() if k == 0)
    tube_tip = sorted(v for (i, j, k), v in tube_ids.items() if k == 2 * nt[2])
    beam_root = sorted(v for (i, j, k), v in beam_ids.items() if k == 0)
    # the nodes off the bending axis (x = 5.5): CalculiX's mean counts a node on the axis with the angle 0
    beam_tip = sorted(v for (i, j, k), v in beam_ids.items() if k == 2 * nb[2] and i != nb[0])
    g = E / (2 * (1 + NU))
    j_polar = math.pi * (B_OUT ** 4 - A_IN ** 4) / 2
    tn, te = block(tube_nodes, tube_elems, 1, "TUBE")
    bn, be = block(beam_nodes, beam_elems, 1001, "BEAM")
    mid_tube = tube_ids[(2 * nt[0], 0, nt[2])]            # r = 1, theta = 0, z = L/2
    mid_beam = beam_ids[(nb[0], nb[1], nb[2])]            # the centroid line, z = L/2
    lines = ["*HEADING",
             "The mean rotation MPC (*MPC MEANROT, CalculiX's, linearised): a torque on a tube and a bending moment on a",
             "cantilever, both C3D20R, applied by *CLOAD on DOF 1 of the MPC's extra node (written by",
             "tests/solids/meanrot_deck.py; closed forms T L/(G J) and M L/(E I) for the tips' mean rotations).",
             f"** let: E = {fmt(E)}", f"** let: NU = {fmt(NU)}", "** let: G = E/(2*(1 + NU))",
             f"** let: J = pi*({fmt(B_OUT)}**4 - {fmt(A_IN)}**4)/2",
             "** the tube at mid-length, r = 1: u_theta = T z r/(G J), Saint-Venant's torsion (0.3 %)",
             f"** expect: displacements node={mid_tube} u2 == {fmt(T)}*{fmt(L_TUBE / 2)}/(G*J) rtol=5e-3",
             "** its tip's mean rotation: T L/(G J) and the loaded face's end effect (the MPC gives every node",
             "** the same share of the torque: the bore's nodes turn 13 % more), +3.1 %",
             f"** expect: displacements node=9001 u1 == {fmt(T)}*{fmt(L_TUBE)}/(G*J) rtol=4e-2",
             "** the cantilever's centre line at mid-span: M z^2/(2 E I); its tip's mean rotation M L/(E I) (+1.4 %)",
             f"** expect: displacements node={mid_beam} u1 == {fmt(M)}*{fmt((L_BEAM / 2) ** 2)}/(2*E/12.0) rtol=2e-2",
             f"** expect: displacements node=9002 u1 == {fmt(M)}*{fmt(L_BEAM)}/(E/12.0) rtol=2e-2",
             "*NODE, NSET=NALL"] + tn + bn + [" 9001, 0.0, 0.0, 1.0", " 9002, 0.0, 1.0, 0.0"]
    lines += te + be
    lines += ["*NSET, NSET=ROOT"] + [", ".join(str(v) for v in (tube_root + beam_root)[c:c + 16])
                                      for c in range(0, len(tube_root + beam_root), 16)]
    lines += ["*NSET, NSET=EXTRA", " 9001, 9002", "*ELSET, ELSET=ROOTS", " 1, 1001"]
    lines += ["*MATERIAL, NAME=STEEL", "*ELASTIC", f" {fmt(E)}, {fmt(NU)}",
              "*SOLID SECTION, ELSET=TUBE, MATERIAL=STEEL", "*SOLID SECTION, ELSET=BEAM, MATERIAL=STEEL",
              "*BOUNDARY", " ROOT, 1, 3", "*MPC"]
    for tip, extra in ((tube_tip, 9001), (beam_tip, 9002)):
        terms = [str(v) for v in tip for _ in range(3)] + [str(extra)]
        head = "MEANROT, " + ", ".join(terms[:15])
        lines.append(head + ("," if len(terms) > 15 else ""))
        rest = terms[15:]
        for c in range(0, len(rest), 16):
            lines.append(" " + ", ".join(rest[c:c + 16]) + ("," if c + 16 < len(rest) else ""))
    lines += ["*STEP", "*STATIC", "*CLOAD", f" 9001, 1, {fmt(T)}", f" 9002, 1, {fmt(M)}",
              "*NODE PRINT, NSET=EXTRA", " U, RF", "*EL PRINT, ELSET=ROOTS", " ENER", "*EL FILE, ELSET=ROOTS", " ENER", "*END STEP"]
    with open(out_path, "w") as f:
        f.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
