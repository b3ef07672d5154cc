#!/usr/bin/env python3
"""*TIE verification through the whole program: generates decks of two
blocks of solids tied face to face, solves them with superjoin and compares
with the single block, closed forms and the beam.

usage: verify_ties.py SUPERJOIN WORKDIR
Exit status 1 if any check fails.

Cases
- matching meshes: two 2 x 2 x 2 C3D8 blocks tied (slave: element faces S6,
  master: faces S4) = the 4 x 2 x 2 block, all displacements to round-off,
  under a tip load with bending, torsion and tension;
- shells as the master: a C3D8 block standing on S4 shells (and C3D20 on
  S8R), its bottom faces tied to the shells' SPOS = the model whose block and
  shells share those nodes, to round-off;
- non-matching meshes under uniform tension (the block [0, 2] x [0, 1]^2,
  tied at x = 1): the constant stress state is exact when the slave face mesh
  refines the master's (2 x 2 master, 4 x 4 slave), and is only approximate
  otherwise (2 x 2 master and 3 x 3 slave, or the other way round): the
  error is measured and printed;
- a tied cantilever (C3D20R, 10 x 1 x 1, two halves of 5 x 2 x 2 and 5 x 3 x 3
  elements, tied at mid-length, either side master) against Timoshenko's tip
  deflection and the untied 10 x 2 x 2 block;
- a quadratic face: a C3D10 block (node surface, TYPE=NODE) tied to a C3D20
  block's 8-node faces, uniform tension: measured error;
- slave DOFs already dependent: an *EQUATION on one of them and a second
  *TIE of the same surfaces leave the result that of the single block, and
  the notes count the DOFs left untied;
- ADJUST: the slave block moved off the master face by 1e-4 (inside the
  POSITION TOLERANCE) is moved back (ADJUST=YES, as the matching case) or
  left (ADJUST=NO); with a tolerance below the gap, nothing is tied and the
  listing says so.
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import verify_solids as vs  # noqa: E402

E, NU = 1000.0, 0.3


def block(n, size, etype, x0, nid0, eid0):
    """A structured block shifted to x = x0, ids offset: (nodes, elems, mesh)."""
    m = vs.Mesh(n, size, etype, False)
    nodes = {nid0 + k: (x[0] + x0, x[1], x[2]) for k, x in m.nodes.items()}
    elems = [tuple(nid0 + v for v in el) for el in m.elems]
    return nodes, elems, m


def two_block_deck(parts, tie_lines, boundary, cloads, extra=""):
    """parts: [(nodes, elems, etype, elset, eid0)]."""
    out = ["*HEADING", "tie verification", "*MATERIAL, NAME=MAT", "*ELASTIC", f" {vs.fmt(E)}, {vs.fmt(NU)}", "*NODE"]
    allnodes = {}
    for nodes, _, _, _, _ in parts:
        allnodes.update(nodes)
    out += [f" {n}, {vs.fmt(x[0])}, {vs.fmt(x[1])}, {vs.fmt(x[2])}" for n, x in sorted(allnodes.items())]
    for nodes, elems, etype, elset, eid0 in parts:
        out.append(f"*ELEMENT, TYPE={etype}, ELSET={elset}")
        for k, el in enumerate(elems, eid0 + 1):
            fields = [str(k)] + [str(v) for v in el]
            for c in range(0, len(fields), 16):
                tail = "," if c + 16 < len(fields) else ""
                out.append(" " + ", ".join(fields[c:c + 16]) + tail)
        out.append(f"*SOLID SECTION, ELSET={elset}, MATERIAL=MAT")
    out += tie_lines
    out.append("*BOUNDARY")
    out += [f" {n}, {d}, {d}, {vs.fmt(v)}" for n, d, v in boundary]
    out += ["*STEP", "*STATIC", "*CLOAD"]
    out += [f" {n}, {d}, {vs.fmt(v)}" for n, d, v in cloads if v != 0.0]
    out += [extra, "*END STEP"]
    return "\n".join(out) + "\n", allnodes

FACES = {"hex": [(1, 2, 3, 4), (5, 8, 7, 6), (1, 5, 6, 2), (2, 6, 7, 3), (3, 7, 8, 4), (4, 8, 5, 1)],
         "tet": [(1, 2, 3), (1, 4, 2), (2, 4, 3), (3, 4, 1)]}


def faces_on_plane(elems, nodes, etype, x, eid0):
    """Surface lines `element, Sk` of the faces lying on the plane x = const."""
    table = FACES["tet" if etype in ("C3D4", "C3D10") else "hex"]
    out = []
    for k, el in enumerate(elems, eid0 + 1):
        for f, corners in enumerate(table, 1):
            if all(abs(nodes[el[c - 1]][0] - x) < 1e-12 for c in corners):
                out.append(f" {k}, S{f}")
    return out


def tie_cards(slave, master, params=""):
    """*SURFACE cards (slave: list of lines, or ('NODE', node ids)) and the *TIE."""
    out = []
    if slave[0] == "NODE":
        out += ["*NSET, NSET=SLAVENODES"] + [f" {n}," for n in slave[1]]
        out += ["*SURFACE, NAME=SLAVE, TYPE=NODE", " SLAVENODES"]
    else:
        out += ["*SURFACE, NAME=SLAVE, TYPE=ELEMENT"] + slave
    out += ["*SURFACE, NAME=MASTER"] + master
    out += ["*TIE, NAME=T1" + params, " SLAVE, MASTER"]
    return out


def run(exe, work, name, text):
    disp, reac = vs.solve(exe, work, name, text)
    return disp


def by_position(nodes, disp):
    return {tuple(round(c, 9) for c in nodes[n]): u for n, u in disp.items() if n in nodes}


def tip_loads(nodes):
    """A load with tension, bending and torsion on the nodes at x = 2."""
    out = []
    for n, x in sorted(nodes.items()):
        if abs(x[0] - 2.0) < 1e-12:
            out += [(n, 1, 0.5 + 0.1 * x[1]), (n, 2, 0.2 * (x[2] - 0.5)), (n, 3, -0.3 * (x[1] - 0.5) + 0.1)]
    return out


def matching(exe, work, gap=0.0, params="", label="matching meshes", pinned=False, extra=()):
    a_nodes, a_el, _ = block((2, 2, 2), (1.0, 1.0, 1.0), "C3D8", 0.0, 0, 0)
    b_nodes, b_el, _ = block((2, 2, 2), (1.0, 1.0, 1.0), "C3D8", 1.0, 1000, 100)
    slave = faces_on_plane(b_el, b_nodes, "C3D8", 1.0, 100)
    master = faces_on_plane(a_el, a_nodes, "C3D8", 1.0, 0)
    if gap:
        b_nodes = {n: ((x[0] + gap) if abs(x[0] - 1.0) < 1e-12 else x[0], x[1], x[2]) for n, x in b_nodes.items()}
    bnd = [(n, d, 0.0) for n, x in sorted(a_nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
    if pinned:      # nothing tied: the slave block held on its far face
        bnd += [(n, d, 0.0) for n, x in sorted(b_nodes.items()) if x[0] == 2.0 for d in (1, 2, 3)]
    text, nodes = two_block_deck([(a_nodes, a_el, "C3D8", "A", 0), (b_nodes, b_el, "C3D8", "B", 100)],
                                 tie_cards(slave, master, params) + list(extra), bnd, tip_loads(b_nodes))
    name = "tie_matching" + ("_gap" if gap else "") + params.replace(",", "_").replace("=", "_").replace(" ", "")
    name += "_extra" if extra else ""
    tied = run(exe, work, name, text)
    mesh = vs.Mesh((4, 2, 2), (2.0, 1.0, 1.0), "C3D8", False)
    bnd1 = [(n, d, 0.0) for n, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
    one = run(exe, work, "tie_single", vs.deck(mesh, E, NU, bnd1, tip_loads(mesh.nodes)))
    if tied is None or one is None:
        return None
    ref = by_position(mesh.nodes, one)
    scale = max(max(abs(c) for c in u) for u in one.values())
    diff = 0.0
    for n, u in tied.items():
        x = nodes[n]
        if gap and abs(x[0] - 1.0 - gap) < 1e-12:
            x = (1.0, x[1], x[2])
        r = ref[tuple(round(c, 9) for c in x)]
        diff = max(diff, max(abs(p - q) for p, q in zip(u, r)))
    print(f"| {label} | {diff / scale:.2e} |")
    with open(os.path.join(work, name + ".lst")) as f:
        listing = f.read()
    return diff / scale, listing


def tension(exe, work, etypes, n_a, n_b, slave_side, node_slave=False):
    """The block [0, 2] x [0, 1]^2 in two halves tied at x = 1, uniform tension 1 along x."""
    a_nodes, a_el, _ = block((2, n_a, n_a), (1.0, 1.0, 1.0), etypes[0], 0.0, 0, 0)
    b_nodes, b_el, b_mesh = block((2, n_b, n_b), (1.0, 1.0, 1.0), etypes[1], 1.0, 10000, 1000)
    fa = faces_on_plane(a_el, a_nodes, etypes[0], 1.0, 0)
    fb = faces_on_plane(b_el, b_nodes, etypes[1], 1.0, 1000)
    slave, master = (fb, fa) if slave_side == "B" else (fa, fb)
    if node_slave:
        side = b_nodes if slave_side == "B" else a_nodes
        slave = ("NODE", [n for n, x in sorted(side.items()) if abs(x[0] - 1.0) < 1e-12])
    allnodes = dict(a_nodes)
    allnodes.update(b_nodes)
    bnd = []
    for n, x in sorted(allnodes.items()):
        if x[0] == 0.0:
            bnd.append((n, 1, 0.0))
        if x[1] == 0.0:
            bnd.append((n, 2, 0.0))
        if x[2] == 0.0:
            bnd.append((n, 3, 0.0))
    loads = {}
    for nd, shares in b_mesh.face_weights().items():
        for normal, s in shares:
            if normal[0] == 1.0:
                loads[10000 + nd] = loads.get(10000 + nd, 0.0) + s
    cl = [(n, 1, v) for n, v in sorted(loads.items())]
    text, nodes = two_block_deck([(a_nodes, a_el, etypes[0], "A", 0), (b_nodes, b_el, etypes[1], "B", 1000)],
                                 tie_cards(slave, master), bnd, cl)
    name = f"tie_tension_{etypes[0]}_{n_a}_{etypes[1]}_{n_b}_slave{slave_side}"
    disp = run(exe, work, name, text)
    if disp is None:
        return None
    err = 0.0
    for n, u in disp.items():
        x = nodes[n]
        exact = (x[0] / E, -NU * x[1] / E, -NU * x[2] / E)
        err = max(err, max(abs(p - q) for p, q in zip(u, exact)))
    err /= 2.0 / E
    side = {"A": f"{etypes[0]} {n_a} x {n_a}", "B": f"{etypes[1]} {n_b} x {n_b}"}
    master_side = "A" if slave_side == "B" else "B"
    print(f"| {side[slave_side]}{' (nodes)' if node_slave else ''} | {side[master_side]} | {err:.2e} |")
    return err


def cantilever(exe, work, slave_side):
    length, e, p = 10.0, 1.0e5, 1.0
    inertia, area, g = 1.0 / 12, 1.0, e / 2
    exact = p * length ** 3 / (3 * e * inertia) + p * length / (5.0 / 6.0 * g * area)
    a_nodes, a_el, _ = block((5, 2, 2), (5.0, 1.0, 1.0), "C3D20R", 0.0, 0, 0)
    b_nodes, b_el, b_mesh = block((5, 3, 3), (5.0, 1.0, 1.0), "C3D20R", 5.0, 10000, 1000)
    fa = faces_on_plane(a_el, a_nodes, "C3D20R", 5.0, 0)
    fb = faces_on_plane(b_el, b_nodes, "C3D20R", 5.0, 1000)
    slave, master = (fb, fa) if slave_side == "B" else (fa, fb)
    bnd = [(n, d, 0.0) for n, x in sorted(a_nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
    loads = {}
    for nd, shares in b_mesh.face_weights().items():
        for normal, s in shares:
            if normal[0] == 1.0:
                loads[10000 + nd] = loads.get(10000 + nd, 0.0) + s * p / area
    cl = [(n, 2, v) for n, v in sorted(loads.items())]
    global E, NU
    saved = E, NU
    E, NU = e, 0.0
    text, nodes = two_block_deck([(a_nodes, a_el, "C3D20R", "A", 0), (b_nodes, b_el, "C3D20R", "B", 1000)],
                                 tie_cards(slave, master), bnd, cl)
    E, NU = saved
    disp = run(exe, work, f"tie_cantilever_slave{slave_side}", text)
    if disp is None:
        return None
    tip = [disp[n][1] for n, x in nodes.items() if abs(x[0] - length) < 1e-12]
    mean = sum(tip) / len(tip)
    return mean, exact


def untied_cantilever(exe, work):
    mesh = vs.Mesh((10, 2, 2), (10.0, 1.0, 1.0), "C3D20R", False)
    bnd = [(nd, d, 0.0) for nd, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
    loads = {}
    for nd, shares in mesh.face_weights().items():
        for normal, s in shares:
            if normal[0] == 1.0:
                loads[nd] = loads.get(nd, 0.0) + s
    cl = [(nd, 2, v) for nd, v in sorted(loads.items())]
    disp = run(exe, work, "tie_cantilever_single", vs.deck(mesh, 1.0e5, 0.0, bnd, cl))
    if disp is None:
        return None
    tip = [disp[nd][1] for nd, x in mesh.nodes.items() if x[0] == 10.0]
    return sum(tip) / len(tip)


def shell_base(exe, work, etype, stype):
    """A solid block standing on a shell plate: its bottom face tied to the
    shell's mid-surface (faces SPOS, matching meshes) against the same
    model with the block's bottom nodes shared by the shells."""
    _, _, m = block((2, 2, 2), (1.0, 1.0, 1.0), etype, 0.0, 0, 0)
    bottom = [k for k, el in enumerate(m.elems, 1)]
    face = [1, 2, 3, 4] + ([9, 10, 11, 12] if etype == "C3D20" else [])
    shells = [[m.elems[k - 1][c - 1] for c in face] for k in bottom
              if all(m.nodes[m.elems[k - 1][c - 1]][2] == 0.0 for c in face)]
    base = sorted({n for sh in shells for n in sh})
    results = []
    for tied in (False, True):
        off = 50000 if tied else 0
        out = ["*HEADING", "block on a shell plate", "*MATERIAL, NAME=MAT", "*ELASTIC", f" {vs.fmt(E)}, {vs.fmt(NU)}",
               "*NODE"]
        out += [f" {n}, {vs.fmt(x[0])}, {vs.fmt(x[1])}, {vs.fmt(x[2])}" for n, x in sorted(m.nodes.items())]
        if tied:
            out += [f" {n + off}, {vs.fmt(m.nodes[n][0])}, {vs.fmt(m.nodes[n][1])}, 0.0" for n in base]
        out.append(f"*ELEMENT, TYPE={etype}, ELSET=BLOCK")
        for k, el in enumerate(m.elems, 1):
            fields = [str(k)] + [str(v) for v in el]
            for c in range(0, len(fields), 16):
                out.append(" " + ", ".join(fields[c:c + 16]) + ("," if c + 16 < len(fields) else ""))
        out.append(f"*ELEMENT, TYPE={stype}, ELSET=PLATE")
        out += [f" {100 + k}, " + ", ".join(str(n + off) for n in sh) for k, sh in enumerate(shells, 1)]
        out += ["*SOLID SECTION, ELSET=BLOCK, MATERIAL=MAT", "*SHELL SECTION, ELSET=PLATE, MATERIAL=MAT", " 0.2"]
        if tied:
            out += ["*SURFACE, NAME=BOTTOM"] + [f" {k}, S1" for k in bottom if m.nodes[m.elems[k - 1][0]][2] == 0.0]
            out += ["*SURFACE, NAME=PLATE", " PLATE, SPOS", "*TIE, NAME=BASE", " BOTTOM, PLATE"]
        out.append("*BOUNDARY")
        out += [f" {n + off}, 1, 6" for n in base if m.nodes[n][0] == 0.0]
        out += ["*STEP", "*STATIC", "*CLOAD"]
        out += [f" {n}, 1, 0.3\n {n}, 3, {vs.fmt(-0.2 - 0.1 * x[1])}" for n, x in sorted(m.nodes.items())
                if x[2] == 1.0 and x[0] == 1.0]
        out += ["*END STEP"]
        text = "\n".join(out) + "\n"
        results.append(run(exe, work, f"tie_shell_{stype}_{'tied' if tied else 'shared'}", text))
    if None in results:
        vs.check(False, f"{etype} block on {stype} shells")
        return
    shared, tied_u = results
    scale = max(max(abs(c) for c in u) for u in shared.values())
    diff = max(max(abs(p - q) for p, q in zip(shared[n], tied_u[n])) for n in m.nodes)
    print(f"| {etype} block tied to {stype} shells (SPOS) | {diff / scale:.2e} |")
    vs.check(diff / scale < 1e-10, f"{etype} block tied to {stype} shells = the shared-node model to round-off")


def main():
    exe, work = sys.argv[1], sys.argv[2]
    os.makedirs(work, exist_ok=True)
    print("## Matching meshes: two C3D8 blocks tied = one block\n")
    print("| case | largest difference / largest displacement |")
    print("|---|---|")
    res = matching(exe, work)
    vs.check(res is not None and res[0] < 1e-10, "matching meshes tied = the single block to round-off")
    vs.check(res is not None and "*TIE T1: 9 of 9 slave nodes tied to 4 master faces" in res[1],
             "the listing's note counts the tied slave nodes")
    res = matching(exe, work, label="an *EQUATION on a slave DOF, a second *TIE on the same nodes",
                   extra=("*EQUATION", "2", " 1001, 1, 1.0, 5, 1, -1.0", "*TIE, NAME=T2", " SLAVE, MASTER"))
    vs.check(res is not None and res[0] < 1e-10 and "9 of 9 slave nodes tied to 4 master faces (POSITION TOLERANCE "
             "6.2500E-03); 1 slave DOFs already dependent" in res[1] and "*TIE T2: 9 of 9 slave nodes tied to 4 master "
             "faces (POSITION TOLERANCE 6.2500E-03); 27 slave DOFs already dependent" in res[1],
             "slave DOFs an *EQUATION or an earlier *TIE makes dependent are not tied again (counted in the note)")
    res = matching(exe, work, gap=1.0e-4, params=", POSITION TOLERANCE=1e-3",
                   label="slave face 1e-4 off, ADJUST=YES (default)")
    vs.check(res is not None and res[0] < 1e-10 and "ADJUST moved 9 slave nodes" in res[1],
             "ADJUST=YES moves the slave nodes onto the master face: the single block again")
    res = matching(exe, work, gap=1.0e-4, params=", POSITION TOLERANCE=1e-3, ADJUST=NO",
                   label="slave face 1e-4 off, ADJUST=NO")
    vs.check(res is not None and 1e-6 < res[0] < 1e-2 and "ADJUST" not in res[1].split("*TIE T1")[1].split("\n")[0],
             "ADJUST=NO keeps the gap (a different, slightly distorted model)")
    res = matching(exe, work, gap=1.0e-4, params=", POSITION TOLERANCE=1e-5, ADJUST=NO", label="gap beyond tolerance",
                   pinned=True)
    vs.check(res is not None and "0 of 9 slave nodes tied to 4 master faces (POSITION TOLERANCE 1.0000E-05); 9 farther "
             "than the tolerance from the master surface are not tied" in res[1],
             "slave nodes beyond the POSITION TOLERANCE are not tied, and the listing says how many")

    shell_base(exe, work, "C3D8", "S4")
    shell_base(exe, work, "C3D20", "S8R")

    print("\n## Uniform tension across non-matching meshes (error / exact largest displacement)\n")
    print("| slave face mesh | master face mesh | error |")
    print("|---|---|---|")
    err = tension(exe, work, ("C3D8", "C3D8"), 2, 4, "B")
    vs.check(err is not None and err < 1e-10, "uniform tension exact when the slave mesh refines the master's")
    err = tension(exe, work, ("C3D8", "C3D8"), 2, 4, "B", node_slave=True)
    vs.check(err is not None and err < 1e-10, "the same with the slave as a node surface (TYPE=NODE)")
    # not nested: the measured errors (deterministic) within a factor of 1.5
    for n_a, n_b, side, measured in ((2, 3, "B", 0.0389), (2, 3, "A", 0.0811), (2, 4, "A", 0.572)):
        err = tension(exe, work, ("C3D8", "C3D8"), n_a, n_b, side)
        vs.check(err is not None and measured / 1.5 < err < measured * 1.5,
                 f"uniform tension, slave {side} ({n_b if side == 'B' else n_a} x ..): approximate ({err})")
    err = tension(exe, work, ("C3D20", "C3D10"), 2, 2, "B", node_slave=True)
    vs.check(err is not None and err < 1e-10, f"C3D10 nodes tied to C3D20 8-node faces: exact ({err})")
    err = tension(exe, work, ("C3D20", "C3D10"), 2, 2, "A")
    vs.check(err is not None and 0.156 / 1.5 < err < 0.156 * 1.5,
             f"C3D20 faces (slave) tied to C3D10 6-node faces: approximate ({err})")
    err = tension(exe, work, ("C3D20", "C3D20"), 2, 4, "B")
    vs.check(err is not None and err < 1e-10, "C3D20: uniform tension exact when the slave mesh refines the master's")

    print("\n## Tied C3D20R cantilever (10 x 1 x 1, nu = 0, end shear 1): 5 x 2 x 2 and 5 x 3 x 3 halves\n")
    single = untied_cantilever(exe, work)
    print("| model | tip deflection | / Timoshenko |")
    print("|---|---|---|")
    for side in ("B", "A"):
        res = cantilever(exe, work, side)
        if res is None:
            vs.check(False, f"tied cantilever, slave {side}")
            continue
        mean, exact = res
        print(f"| tied, slave the {'3 x 3' if side == 'B' else '2 x 2'} half | {mean:.6e} | {mean / exact:.5f} |")
        vs.check(abs(mean / exact - 1) < 0.02, f"tied cantilever (slave {side}) within 2% of Timoshenko")
    if single is not None:
        print(f"| one block 10 x 2 x 2 | {single:.6e} | {single / exact:.5f} |")
    print(f"\n{len(vs.failures)} failures")
    return 1 if vs.failures else 0


if __name__ == "__main__":
    sys.exit(main())
