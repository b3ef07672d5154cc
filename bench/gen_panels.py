#!/usr/bin/env python3
"""A joint study: two S4 panels joined along a line by compliant contacts.

usage: gen_panels.py [--mesh M] [--plane] [--values V1,V2,...|--sweep N] [--single G] > panels.deck

Two square steel panels (1 m, 50 mm, M x M S4 elements each) side by side in
the XY plane, joined along their common edge node by node: translations RIGID,
rotations with stiffness g (a semi-rigid line joint). Panel A is clamped along
its far edge, panel B free at its far edge; both carry a pressure. With
--sweep N (default 20) one step per value of g, log-spaced from 1e4 to 1e11
N m/rad per node pair, written as *CHANGE CONTACT, SWEEP; with --values the
given values; with --single G one step with g = G in the *CONTACT card itself
(the independent run a step of the study must equal). Each panel has
6 (M+1)^2 DOFs; the joint 6 (M+1).

With --plane the panels are CPS4 plane-stress panels (2 (M+1)^2 DOFs each, 1 m
by 1 m, 50 mm thick) in the XY plane, joined along the edge by normal springs
(DOF 1, RIGID) and shear springs (DOF 2, the swept g, in N/m per node pair),
panel A clamped at its far edge and panel B pulled and sheared at its far edge
(the shell panels' drilling and bending DOFs make their stiffness matrix far
less well conditioned: relative residuals near 1e-6 at M = 130).
"""
import argparse

SIDE = 1.0
THICK = 0.05
E, NU = 2.1e11, 0.3
PRESSURE = 1.0e2


def panel(name, m, x0, etype="S4"):
    n1 = m + 1
    out = [f"*SUBSTRUCTURE, NAME={name}", "*NODE"]
    for j in range(n1):
        for i in range(n1):
            out.append(f"{j * n1 + i + 1}, {x0 + SIDE * i / m:.12g}, {SIDE * j / m:.12g}, 0")
    out.append(f"*ELEMENT, TYPE={etype}, ELSET=SKIN")
    for j in range(m):
        for i in range(m):
            a = j * n1 + i + 1
            out.append(f"{j * m + i + 1}, {a}, {a + 1}, {a + n1 + 1}, {a + n1}")
    out.append("*NSET, NSET=LEFT")
    out += chunk([j * n1 + 1 for j in range(n1)])
    out.append("*NSET, NSET=RIGHT")
    out += chunk([j * n1 + n1 for j in range(n1)])
    out.append(("*SHELL SECTION" if etype == "S4" else "*SOLID SECTION") + ", ELSET=SKIN, MATERIAL=STEEL")
    out.append(f"{THICK}")
    out.append("*END SUBSTRUCTURE")
    return out


def chunk(ids, per=16):
    return [", ".join(str(i) for i in ids[k:k + per]) for k in range(0, len(ids), per)]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--mesh", type=int, default=8)
    ap.add_argument("--sweep", type=int, default=20)
    ap.add_argument("--values")
    ap.add_argument("--single")
    ap.add_argument("--plane", action="store_true", help="CPS4 panels, in-plane joint")
    ap.add_argument("--requests", action="store_true",
                    help="print only what a joint study reads: the loaded edge's displacements "
                         "(*NODE PRINT) besides the contact forces")
    args = ap.parse_args()
    m = args.mesh
    if args.values:
        values = args.values.split(",")
    else:
        n = args.sweep
        lo = 6 if args.plane else 4
        values = [f"{10 ** (lo + 7 * k / max(n - 1, 1)):.6e}" for k in range(n)]
    out = ["*HEADING", f"Two {'CPS4' if args.plane else 'S4'} panels ({m}x{m} each) joined by a "
           f"semi-rigid line joint, bench/gen_panels.py --mesh {m}" + (" --plane" if args.plane else ""), "*MATERIAL, NAME=STEEL", "*ELASTIC", f"{E:.6g}, {NU}"]
    etype = "CPS4" if args.plane else "S4"
    out += panel("A", m, 0.0, etype)
    out += panel("B", m, SIDE, etype)
    g0 = args.single if args.single else "1.0e6"
    # the swept DOFs: rotations of the shells, the shear DOF of the plane panels
    swept = "2, 2" if args.plane else "4, 6"
    out.append("*CONTACT, NAME=JOINT, MASTER=A, SLAVE=B")
    out.append("RIGHT, LEFT, 1, 1, RIGID" if args.plane else "RIGHT, LEFT, 1, 3, RIGID")
    out.append(f"RIGHT, LEFT, {swept}, {g0}")
    out.append("*BOUNDARY")
    out.append("A.LEFT, 1, 2" if args.plane else "A.LEFT, 1, 6")
    out.append("*STEP, NAME=STUDY")
    if args.plane:
        out.append("*CLOAD")
        out.append(f"B.RIGHT, 1, {1.0e4 / (m + 1):.6g}")
        out.append(f"B.RIGHT, 2, {2.0e3 / (m + 1):.6g}")
    else:
        out.append("*DLOAD")
        out.append("A.SKIN, P, %g" % -PRESSURE)   # *DLOAD P pushes along the normal
        out.append("B.SKIN, P, %g" % -PRESSURE)
    if args.requests:
        out.append("*NODE PRINT, NSET=B.RIGHT")
        out.append("U")
    if not args.single:
        out.append("*CHANGE CONTACT, NAME=JOINT, SWEEP")
        out.append(f"RIGHT, LEFT, {swept}, " + ", ".join(values))
    out.append("*END STEP")
    print("\n".join(out))


if __name__ == "__main__":
    main()
