#!/usr/bin/env python3
"""Couplings of solid faces (*COUPLING + *KINEMATIC / *DISTRIBUTING, *RIGID
BODY, *MPC BEAM) through the whole program: generates decks, solves them with
superjoin and checks closed forms.

usage: verify_coupling.py SUPERJOIN WORKDIR
Exit status 1 if any check fails.

Cases (a cantilever block L x b x h along x, clamped at x = 0, E = 210000,
nu = 0.3; its end face x = L is the element surface S4 of the last elements):
- KINEMATIC, C3D8 and C3D20R: a force (0, P, Q) and a moment (T, My, Mz) on a
  reference node off the face (x_r = (L + e, b/2, h/2)): the reactions equal
  the loads (round-off), every face node moves as u_r + theta_r x (x_i - x_r)
  (the face stays plane and rigid), and the C3D20R tip deflection under P
  is within 2 % of Timoshenko's P L^3 / 3EI + P L / (k G A) (k = 5/6) plus the
  arm's rotation (e theta_z) (the measured figure is printed);
- DISTRIBUTING on the same block (C3D20R, reference node at the face's
  centre): the reference node's displacement equals the area-weighted mean of
  the face's nodes (weights: the integral of N_a over the faces, -A/12 on the
  corners and A/3 on the mid-sides of 8-node faces; round-off), its rotation the
  weighted least-squares rotation, reactions equal the loads, and the face
  warps (its nodes leave the best-fit plane: the face is not held rigid);
- a C3D20R block and a B31 beam continuing it, joined through the coupling's
  reference node (the first beam node): the beam's tip deflection under a tip
  force equals the block's end deflection and rotation carried along the beam
  plus the beam's own cantilever deflection P l^3/3EI + P l/(k G A) (B31 with
  superjoin's shear factor), with the block's end values taken from the run
  (rigid face) -- and the whole within 2 % of Timoshenko for the combined
  length;
- *RIGID BODY, NSET=, REF NODE=, ROT NODE= (CalculiX: the ROT NODE's
  translations are the body's rotations) gives the same displacements as the
  KINEMATIC coupling with DOFs 1-6 on the same nodes (round-off);
- a coupled node held by a *BOUNDARY (a corner of the face fixed in y): solved
  without conflict, the face still rigid, the constraint eliminating another
  DOF (the reference node's);
- *MPC BEAM between two nodes: the distance's first variation is zero;
  *MPC PLANE (two nodes kept in the plane of three) and *MPC STRAIGHT (a node
  set: the middle node kept on the line of the two others): the first
  variations of (x_p - x_1).(a x b) and (x_p - x_1) x t are zero;
- CalculiX (if `ccx` is on PATH): the KINEMATIC and DISTRIBUTING C3D20R decks
  with a force and a moment on the reference node, run by `ccx -i`: the face
  nodes' displacements (*NODE PRINT U) agree within 1e-6 of the table (7
  printed digits); CalculiX prints 0 for the distributing reference node,
  superjoin its displacement.
"""
import csv
import math
import os
import shutil
import subprocess
import sys

failures = []
E, NU = 210000.0, 0.3
G = E / (2 * (1 + NU))


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        failures.append(what)


def fmt(v):
    return repr(float(v))


class Block:
    """A structured hex block [0, L] x [0, b] x [0, h], n = (nx, ny, nz) cells."""

    def __init__(self, etype, n, size):
        self.etype = etype
        self.quad = etype in ("C3D20", "C3D20R")
        self.n = n
        self.size = size
        step = 1 if self.quad else 2
        self.nodes = {}
        self.ids = {}
        for i in range(0, 2 * n[0] + 1, step):
            for j in range(0, 2 * n[1] + 1, step):
                for k in range(0, 2 * n[2] + 1, step):
                    if sum(v % 2 for v in (i, j, k)) > 1:
                        continue
                    nid = len(self.nodes) + 1
                    self.ids[(i, j, k)] = nid
                    self.nodes[nid] = tuple(size[a] * p / (2 * n[a]) for a, p in enumerate((i, j, k)))
        corners = [(0, 0, 0), (2, 0, 0), (2, 2, 0), (0, 2, 0), (0, 0, 2), (2, 0, 2), (2, 2, 2), (0, 2, 2)]
        edges = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4), (0, 4), (1, 5), (2, 6), (3, 7)]
        self.elems = []
        self.last = []
        for ex in range(n[0]):
            for ey in range(n[1]):
                for ez in range(n[2]):
                    base = (2 * ex, 2 * ey, 2 * ez)
                    pts = [tuple(b + c for b, c in zip(base, cr)) for cr in corners]
                    if self.quad:
                        pts += [tuple((p + q) // 2 for p, q in zip(pts[a], pts[b])) for a, b in edges]
                    self.elems.append([self.ids[p] for p in pts])
                    if ex == n[0] - 1:
                        self.last.append(len(self.elems))

    def at(self, x=None):
        """Nodes with x coordinate x."""
        return sorted(k for k, p in self.nodes.items() if abs(p[0] - x) < 1e-12)

    def deck(self, body, step, heading="coupling"):
        out = ["*HEADING", heading, "*MATERIAL, NAME=MAT", "*ELASTIC", f" {fmt(E)}, {fmt(NU)}", "*NODE"]
        out += [f" {k}, {fmt(p[0])}, {fmt(p[1])}, {fmt(p[2])}" for k, p in sorted(self.nodes.items())]
        out.append(f"*ELEMENT, TYPE={self.etype}, ELSET=SOLID")
        for k, el in enumerate(self.elems, 1):
            fields = [str(k)] + [str(v) for v in el]
            for c in range(0, len(fields), 16):
                tail = "," if c + 16 < len(fields) else ""
                out.append(" " + ", ".join(fields[c:c + 16]) + tail)
        out += ["*SOLID SECTION, ELSET=SOLID, MATERIAL=MAT", "*ELSET, ELSET=TIP"]
        out += [f" {k}" for k in self.last]
        out += ["*SURFACE, NAME=END, TYPE=ELEMENT", " TIP, S4", "*NSET, NSET=CLAMP"]
        out += [f" {k}" for k in self.at(0.0)]
        out += ["*NSET, NSET=FACE"] + [f" {k}" for k in self.at(self.size[0])]
        out += ["*BOUNDARY", " CLAMP, 1, 3"]
        out.append(body)
        out += ["*STEP", "*STATIC", step, "*END STEP"]
        return "\n".join(out) + "\n"

    def face_weights(self):
        """{node: weight} of the end face: the integral of N_a over each
        rectangular face, A/4 per corner of a 4-node face, -A/12 per corner
        and A/3 per mid-side node of an 8-node one."""
        w = {}
        L = self.size[0]
        a = (self.size[1] / self.n[1]) * (self.size[2] / self.n[2])
        for e in self.last:
            el = self.elems[e - 1]
            for k, v in enumerate(el):
                if abs(self.nodes[v][0] - L) > 1e-12:
                    continue
                share = (a / 3 if k >= 8 else -a / 12) if self.quad else a / 4
                w[v] = w.get(v, 0.0) + share
        return w


def solve(exe, work, name, text):
    """Run superjoin: ({(sub, node): [u1..ur3]}, [(node, dof, force)], listing text)."""
    path = os.path.join(work, name + ".deck")
    with open(path, "w") as f:
        f.write(text)
    out = os.path.join(work, name + "_csv")
    lst = os.path.join(work, name + ".lst")
    r = subprocess.run([exe, "-q", "--csv", out, "-o", lst, path], capture_output=True, text=True)
    if r.returncode != 0:
        check(False, f"{name}: exit {r.returncode}: {r.stderr.strip()[:400]}")
        return None, None
    disp, reac = {}, []
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            disp[int(row["node"])] = [float(row[c]) for c in ("u1", "u2", "u3", "ur1", "ur2", "ur3")]
    with open(os.path.join(out, "reactions.csv")) as f:
        for row in csv.DictReader(f):
            reac.append((int(row["node"]), int(row["dof"]), float(row["force"])))
    return disp, reac


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def resultant(blk, reac, about):
    """Force and moment (about `about`) of the reactions."""
    f = [0.0] * 3
    m = [0.0] * 3
    for n, d, v in reac:
        if d > 3:
            m[d - 4] += v
            continue
        f[d - 1] += v
        x = blk.nodes.get(n)
        r = [x[i] - about[i] for i in range(3)]
        fv = [0.0] * 3
        fv[d - 1] = v
        m = [a + b for a, b in zip(m, cross(r, fv))]
    return f, m


def rigid_error(blk, disp, ref, xr):
    """Largest |u_i - u_r - theta_r x (x_i - x_r)| over the end face."""
    worst = 0.0
    ur, th = disp[ref][:3], disp[ref][3:]
    for n in blk.at(blk.size[0]):
        r = [blk.nodes[n][i] - xr[i] for i in range(3)]
        want = [a + b for a, b in zip(ur, cross(th, r))]
        worst = max(worst, max(abs(a - b) for a, b in zip(disp[n][:3], want)))
    return worst


def timoshenko(p, length, b, h):
    i = b * h ** 3 / 12
    return p * length ** 3 / (3 * E * i) + p * length / (5 / 6 * G * b * h)


LOADS = (0.0, 1.0, 0.5, 2.0, 0.3, -0.7)   # Fx, Fy, Fz, Mx, My, Mz on the reference node


def loads_text(ref):
    return "*CLOAD\n" + "\n".join(f" {ref}, {d}, {fmt(v)}" for d, v in enumerate(LOADS, 1) if v != 0.0)


def check_statics(name, blk, reac, xr):
    f, m = resultant(blk, reac, xr)
    scale = max(abs(v) for v in LOADS)
    err = max(max(abs(a + b) for a, b in zip(f, LOADS[:3])), max(abs(a + b) for a, b in zip(m, LOADS[3:])))
    check(err < 1e-9 * scale, f"{name}: reactions balance the force and moment on the reference node "
          f"(|R + F| {err:.1e})")


def kinematic_cases(exe, work):
    print("\n## KINEMATIC coupling of the end face\n")
    for etype, n in (("C3D8", (16, 2, 2)), ("C3D20R", (8, 2, 2))):
        blk = Block(etype, n, (8.0, 1.0, 1.0))
        ref = len(blk.nodes) + 1
        xr = (8.5, 0.5, 0.5)
        body = (f"*NODE\n {ref}, {fmt(xr[0])}, {fmt(xr[1])}, {fmt(xr[2])}\n"
                f"*COUPLING, REF NODE={ref}, SURFACE=END, CONSTRAINT NAME=TIPC\n*KINEMATIC\n 1, 3")
        disp, reac = solve(exe, work, f"kin_{etype}", blk.deck(body, loads_text(ref)))
        if disp is None:
            continue
        check_statics(f"{etype} KINEMATIC", blk, reac, xr)
        err = rigid_error(blk, disp, ref, xr)
        scale = max(abs(v) for v in disp[ref][:3])
        check(err < 1e-10 * scale, f"{etype} KINEMATIC: the end face moves rigidly with the reference node "
              f"({err:.1e} of {scale:.3e})")
        if etype != "C3D20R":
            continue
        # bending under Fy alone: tip deflection against Timoshenko
        step = f"*CLOAD\n {ref}, 2, 1.0"
        disp, reac = solve(exe, work, "kin_fy", blk.deck(body, step))
        if disp is None:
            continue
        at_face = disp[ref][1] - 0.5 * disp[ref][5]
        # the force at the arm e = 0.5 also bends the block by the moment P e: P e L^2 / 2EI
        want = timoshenko(1.0, 8.0, 1.0, 1.0) + 1.0 * 0.5 * 8.0 ** 2 / (2 * E / 12)
        ratio = at_face / want
        check(abs(ratio - 1) < 0.02, f"C3D20R 8x2x2 KINEMATIC: face-centre deflection {at_face:.6e} / "
              f"Timoshenko {want:.6e} = {ratio:.4f}")


def distributing_case(exe, work):
    print("\n## DISTRIBUTING coupling of the end face\n")
    blk = Block("C3D20R", (8, 2, 2), (8.0, 1.0, 1.0))
    ref = len(blk.nodes) + 1
    xr = (8.0, 0.5, 0.5)
    body = (f"*NODE\n {ref}, {fmt(xr[0])}, {fmt(xr[1])}, {fmt(xr[2])}\n"
            f"*COUPLING, REF NODE={ref}, SURFACE=END, CONSTRAINT NAME=TIPD\n*DISTRIBUTING")
    disp, reac = solve(exe, work, "dist_c3d20r", blk.deck(body, loads_text(ref)))
    if disp is None:
        return
    check_statics("C3D20R DISTRIBUTING", blk, reac, xr)
    w = blk.face_weights()
    wsum = sum(w.values())
    mean = [sum(w[n] * disp[n][i] for n in w) / wsum for i in range(3)]
    err = max(abs(a - b) for a, b in zip(mean, disp[ref][:3]))
    scale = max(abs(v) for v in mean)
    check(err < 1e-10 * scale, f"DISTRIBUTING: reference node displacement = area-weighted mean of the face "
          f"({err:.1e} of {scale:.3e})")
    # weighted least-squares rotation: J theta = sum w rho x u
    xbar = [sum(w[n] * blk.nodes[n][i] for n in w) / wsum for i in range(3)]
    jm = [[0.0] * 3 for _ in range(3)]
    rhs = [0.0] * 3
    for n in w:
        rho = [blk.nodes[n][i] - xbar[i] for i in range(3)]
        r2 = sum(v * v for v in rho)
        for a in range(3):
            for b in range(3):
                jm[a][b] += w[n] * ((r2 if a == b else 0.0) - rho[a] * rho[b])
        rhs = [a + w[n] * b for a, b in zip(rhs, cross(rho, disp[n][:3]))]
    th = disp[ref][3:]
    res = [sum(jm[a][b] * th[b] for b in range(3)) - rhs[a] for a in range(3)]
    err = max(abs(v) for v in res)
    check(err < 1e-10 * max(abs(v) for v in rhs), f"DISTRIBUTING: reference node rotation = weighted "
          f"least-squares rotation of the face (residual {err:.1e})")
    warp = rigid_error(blk, disp, ref, xr)
    check(warp > 1e-3 * scale, f"DISTRIBUTING: the end face is free to warp (departs from the rigid motion "
          f"by {warp:.2e}, {warp / scale:.1%} of the displacement)")


def rigid_body_case(exe, work):
    print("\n## *RIGID BODY with ROT NODE (CalculiX) against *KINEMATIC 1-6\n")
    blk = Block("C3D8", (16, 2, 2), (8.0, 1.0, 1.0))
    ref, rot = len(blk.nodes) + 1, len(blk.nodes) + 2
    xr = (8.5, 0.5, 0.5)
    nodes = f"*NODE\n {ref}, {fmt(xr[0])}, {fmt(xr[1])}, {fmt(xr[2])}\n {rot}, 0.0, 0.0, 0.0\n"
    kin, _ = solve(exe, work, "rb_kin", blk.deck(nodes + f"*COUPLING, REF NODE={ref}, SURFACE=END\n*KINEMATIC\n 1, 6",
                                                 loads_text(ref)))
    step = "*CLOAD\n" + "\n".join(f" {ref if d <= 3 else rot}, {(d - 1) % 3 + 1}, {fmt(v)}"
                                   for d, v in enumerate(LOADS, 1) if v != 0.0)
    rb, reac = solve(exe, work, "rb_rot", blk.deck(nodes + f"*RIGID BODY, NSET=FACE, REF NODE={ref}, ROT NODE={rot}",
                                                   step))
    if kin is None or rb is None:
        return
    scale = max(max(abs(v) for v in u[:3]) for u in kin.values())
    err = max(max(abs(a - b) for a, b in zip(kin[n][:3], rb[n][:3])) for n in blk.nodes)
    check(err < 1e-10 * scale, f"RIGID BODY (ROT NODE) = KINEMATIC 1-6: every solid node ({err:.1e} of {scale:.3e})")
    err = max(abs(a - b) for a, b in zip(kin[ref][3:], rb[rot][:3]))
    check(err < 1e-10 * max(abs(v) for v in kin[ref][3:]), f"RIGID BODY: the ROT NODE's translations are the "
          f"body's rotations ({err:.1e})")
    # a face node also held by a *BOUNDARY: the constraint eliminates another DOF
    corner = blk.at(8.0)[0]
    held, reac = solve(exe, work, "rb_held", blk.deck(
        nodes + f"*RIGID BODY, NSET=FACE, REF NODE={ref}, ROT NODE={rot}\n*BOUNDARY\n {corner}, 2, 2", step))
    if held is None:
        return
    check(abs(held[corner][1]) == 0.0, "a coupled node held by *BOUNDARY: solved, its DOF stays 0")
    worst = 0.0
    for n in blk.at(8.0):
        r = [blk.nodes[n][i] - xr[i] for i in range(3)]
        want = [a + b for a, b in zip(held[ref][:3], cross(held[rot][:3], r))]
        worst = max(worst, max(abs(a - b) for a, b in zip(held[n][:3], want)))
    check(worst < 1e-10 * max(abs(v) for v in held[ref][:3]), f"... and the face is still rigid ({worst:.1e})")
    f, m = resultant(blk, [(n if n != rot else ref, d + 3 if n == rot else d, v) for n, d, v in reac], xr)
    err = max(max(abs(a + b) for a, b in zip(f, LOADS[:3])), max(abs(a + b) for a, b in zip(m, LOADS[3:])))
    check(err < 1e-9 * 2.0, f"... and the reactions balance the loads ({err:.1e})")


def beam_case(exe, work):
    print("\n## A C3D20R block and a B31 beam joined through a KINEMATIC coupling\n")
    blk = Block("C3D20R", (8, 2, 2), (8.0, 1.0, 1.0))
    first = len(blk.nodes) + 1
    nb, lb = 8, 8.0
    beam = ["*NODE"] + [f" {first + k}, {fmt(8.0 + lb * k / nb)}, 0.5, 0.5" for k in range(nb + 1)]
    beam += ["*ELEMENT, TYPE=B31, ELSET=BEAM"] + [f" {1000 + k}, {first + k}, {first + k + 1}" for k in range(nb)]
    beam += ["*BEAM SECTION, ELSET=BEAM, MATERIAL=MAT, SECTION=RECT", " 1.0, 1.0", " 0.0, 0.0, 1.0"]
    tip = first + nb
    body = "\n".join(beam) + f"\n*COUPLING, REF NODE={first}, SURFACE=END\n*KINEMATIC"
    disp, reac = solve(exe, work, "solid_beam", blk.deck(body, f"*CLOAD\n {tip}, 2, 1.0"))
    # the beam alone, clamped at its first node
    alone = "\n".join(beam) + f"\n*BOUNDARY\n {first}, 1, 6"
    text = ["*HEADING", "beam alone", "*MATERIAL, NAME=MAT", "*ELASTIC", f" {fmt(E)}, {fmt(NU)}", alone,
            "*STEP", "*STATIC", f"*CLOAD\n {tip}, 2, 1.0", "*END STEP"]
    bdisp, _ = solve(exe, work, "beam_alone", "\n".join(text) + "\n")
    if disp is None or bdisp is None:
        return
    want = disp[first][1] + disp[first][5] * lb + bdisp[tip][1]
    err = abs(disp[tip][1] - want)
    check(err < 1e-10 * abs(want), f"solid + B31: beam tip = face deflection + face rotation x l + the beam's own "
          f"cantilever deflection ({err:.1e} of {want:.6e})")
    full = timoshenko(1.0, 16.0, 1.0, 1.0)
    ratio = disp[tip][1] / full
    check(abs(ratio - 1) < 0.02, f"solid + B31: tip deflection {disp[tip][1]:.6e} / Timoshenko of the whole "
          f"length {full:.6e} = {ratio:.4f}")
    check_statics_beam = max(abs(sum(v for n, d, v in reac if d == 2) + 1.0), 0.0)
    check(check_statics_beam < 1e-9, f"solid + B31: the reactions balance the tip force ({check_statics_beam:.1e})")


def mpc_case(exe, work):
    print("\n## *MPC BEAM, PLANE, STRAIGHT (linearised)\n")
    blk = Block("C3D8", (8, 2, 2), (8.0, 1.0, 1.0))
    face = blk.at(8.0)          # 9 nodes, ordered by y then z
    mid = blk.at(4.0)
    a, b = face[0], face[-1]
    body = (f"*MPC\nBEAM, {a}, {b}\n*MPC\nPLANE, {face[0]}, {face[2]}, {face[6]}\n {face[4]}, {face[8]}\n"
            f"*NSET, NSET=AXIS\n {mid[1]}, {mid[4]}, {mid[7]}\n*MPC\nSTRAIGHT, AXIS")
    disp, _ = solve(exe, work, "mpc", blk.deck(body, f"*CLOAD\n {face[1]}, 2, 1.0\n {face[5]}, 3, 0.5\n"
                                                      f" {face[4]}, 1, 2.0\n {mid[4]}, 3, 0.3"))
    if disp is None:
        return
    x = blk.nodes
    scale = max(max(abs(v) for v in u[:3]) for u in disp.values())

    def sub3(p, q):
        return [p[i] - q[i] for i in range(3)]

    def dot(p, q):
        return sum(i * j for i, j in zip(p, q))
    r, du = sub3(x[b], x[a]), sub3(disp[b], disp[a])
    val = dot(r, du) / math.sqrt(dot(r, r))
    check(abs(val) < 1e-10 * scale, f"*MPC BEAM: (x_b - x_a).(u_b - u_a) / |x_b - x_a| = {val:.1e} "
          f"(displacements {scale:.2e})")
    n1, n2, n3 = face[0], face[2], face[6]
    ea, eb = sub3(x[n2], x[n1]), sub3(x[n3], x[n1])
    ua, ub = sub3(disp[n2], disp[n1]), sub3(disp[n3], disp[n1])
    worst = 0.0
    for p in (face[4], face[8]):
        d, ud = sub3(x[p], x[n1]), sub3(disp[p], disp[n1])
        # first variation of d.(a x b)
        var = dot(ud, cross(ea, eb)) + dot(d, cross(ua, eb)) + dot(d, cross(ea, ub))
        worst = max(worst, abs(var))
    check(worst < 1e-10 * scale, f"*MPC PLANE: first variation of (x_p - x_1).(a x b) at the two nodes "
          f"{worst:.1e}")
    t, ut = sub3(x[mid[7]], x[mid[1]]), sub3(disp[mid[7]], disp[mid[1]])
    d, ud = sub3(x[mid[4]], x[mid[1]]), sub3(disp[mid[4]], disp[mid[1]])
    var = [p + q for p, q in zip(cross(ud, t), cross(d, ut))]
    check(max(abs(v) for v in var) < 1e-10 * scale, f"*MPC STRAIGHT (a node set): first variation of "
          f"(x_p - x_1) x t {max(abs(v) for v in var):.1e}")
    bent = abs(disp[mid[4]][2] - 0.5 * (disp[mid[1]][2] + disp[mid[7]][2]))
    print(f"      (the middle node sits on the line of its neighbours: {bent:.1e} off, displacements {scale:.1e})")


def ccx_case(exe, work):
    print("\n## CalculiX (ccx -i) on the same KINEMATIC and DISTRIBUTING decks\n")
    ccx = shutil.which("ccx")
    if ccx is None:
        print("skip  ccx is not on PATH")
        return
    blk = Block("C3D20R", (8, 2, 2), (8.0, 1.0, 1.0))
    ref = len(blk.nodes) + 1
    for kind, dofs in (("KINEMATIC", "1, 3"), ("DISTRIBUTING", "1, 6")):
        body = (f"*NODE\n {ref}, 8.0, 0.5, 0.5\n*COUPLING, REF NODE={ref}, SURFACE=END, CONSTRAINT NAME=C\n"
                f"*{kind}\n {dofs}")
        step = f"*CLOAD\n {ref}, 2, 1.0\n {ref}, 3, 0.5\n {ref}, 4, 2.0\n*NODE PRINT, NSET=FACE\nU"
        text = blk.deck(body, step)
        job = f"ccx_{kind.lower()}"
        disp, _ = solve(exe, work, job, text)
        with open(os.path.join(work, job + ".inp"), "w") as f:
            f.write(text)
        r = subprocess.run([ccx, "-i", job], cwd=work, capture_output=True, text=True)
        if r.returncode != 0 or disp is None:
            check(False, f"{kind}: ccx exit {r.returncode}")
            continue
        got = {}
        with open(os.path.join(work, job + ".dat")) as f:
            for line in f:
                v = line.split()
                if len(v) == 4 and v[0].isdigit():
                    got[int(v[0])] = [float(t) for t in v[1:]]
        scale = max(max(abs(t) for t in u) for u in got.values())
        err = max(max(abs(a - b) for a, b in zip(disp[n][:3], got[n])) for n in got)
        check(len(got) == len(blk.at(8.0)) and err <= 1e-6 * scale,
              f"{kind}: {len(got)} face nodes against ccx, max |u - u_ccx| / table {err / scale:.1e}")


def main(argv):
    if len(argv) != 3:
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    exe, work = os.path.abspath(argv[1]), argv[2]
    os.makedirs(work, exist_ok=True)
    kinematic_cases(exe, work)
    distributing_case(exe, work)
    rigid_body_case(exe, work)
    beam_case(exe, work)
    mpc_case(exe, work)
    ccx_case(exe, work)
    print()
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("all coupling checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
