#!/usr/bin/env python3
"""Structural check of superjoin's VTK output (what ParaView's XML readers need),
and comparison of its values with the CSV files of the same run.

usage: check_vtk.py FILE.pvd [--csv DIR]

The .pvd collection and every .vtu it names are parsed with xml.etree and
checked against the VTK XML format: element structure, data array types,
component and tuple counts, offsets, connectivity and cell types. With --csv,
every number of displacements.csv, reactions.csv, contact_forces.csv,
element_forces.csv (and plate_results.csv when present) must be found, exactly,
in the VTK cell or point data, and everything the CSV files do not list must
be zero. Exit status 0 when all is well, 1 with one line per problem.
"""
import csv
import math
import os
import re
import sys
import xml.etree.ElementTree as ET

VTK_TYPES = {
    "Int8": (-2**7, 2**7 - 1), "UInt8": (0, 2**8 - 1),
    "Int16": (-2**15, 2**15 - 1), "UInt16": (0, 2**16 - 1),
    "Int32": (-2**31, 2**31 - 1), "UInt32": (0, 2**32 - 1),
    "Int64": (-2**63, 2**63 - 1), "UInt64": (0, 2**64 - 1),
    "Float32": None, "Float64": None,
}
CELL_POINTS = {1: 1, 3: 2, 4: 3, 5: 3, 9: 4, 12: 8, 22: 6, 23: 8}   # 4: poly line, only B32   # vertex, line, triangle, quad, quadratic ones
KIND_ELEMENT, KIND_CONTACT, KIND_SUPPORT = 1, 2, 3
LINE_TYPES = {"T2D2", "T3D2", "B23", "B33", "B21", "B31"}
ELEMENT_TYPE_CODES = {"T2D2": 1, "T3D2": 2, "B23": 3, "B33": 4, "CPS3": 5, "CPS4": 6, "S3": 7, "S4": 8,
                      "B21": 9, "B31": 10, "CPE3": 11, "CPE4": 12, "S4R": 13, "S3R": 14, "S8R": 15,
                      "CPS6": 16, "CPS8": 17, "CPE6": 18, "CPE8": 19, "CPS8R": 20, "CPE8R": 21, "B32": 22,
                      "S8": 31, "C3D8": 23}
ELEMENT_CELL = {1: 3, 2: 3, 3: 3, 4: 3, 5: 5, 6: 9, 7: 5, 8: 9, 9: 3, 10: 3, 11: 5, 12: 9, 13: 9, 14: 5, 15: 23,
                16: 22, 17: 23, 18: 22, 19: 23, 20: 23, 21: 23, 22: 4, 31: 23, 23: 12}

problems = []


def fail(msg):
    problems.append(msg)


def data_array(elem, where, ntuples_expected=None):
    """Parse and check one DataArray; returns (name, ncomp, values)."""
    name = elem.get("Name", "")
    vtype = elem.get("type")
    if vtype not in VTK_TYPES:
        fail(f"{where}: DataArray {name!r} has type {vtype!r}")
        return name, 1, []
    if elem.get("format") != "ascii":
        fail(f"{where}: DataArray {name!r} format {elem.get('format')!r} (expected ascii)")
    ncomp = int(elem.get("NumberOfComponents", "1"))
    if ncomp < 1:
        fail(f"{where}: DataArray {name!r} NumberOfComponents {ncomp}")
    named = [elem.get(f"ComponentName{k}") is not None for k in range(ncomp)]
    if any(named) and not all(named) or elem.get(f"ComponentName{ncomp}") is not None:
        fail(f"{where}: DataArray {name!r} names some of its {ncomp} components")
    if ncomp == 6 and not all(named):
        fail(f"{where}: 6-component DataArray {name!r} does not name its components")
    tokens = (elem.text or "").split()
    rng = VTK_TYPES[vtype]
    values = []
    for t in tokens:
        try:
            if rng is None:
                x = float(t)
                if not math.isfinite(x):
                    fail(f"{where}: {name!r} holds {t}")
            else:
                x = int(t)
                if not rng[0] <= x <= rng[1]:
                    fail(f"{where}: {name!r} value {t} out of range of {vtype}")
        except ValueError:
            fail(f"{where}: {name!r} token {t!r} is not a {vtype}")
            return name, ncomp, []
        values.append(x)
    if len(values) % ncomp:
        fail(f"{where}: {name!r} has {len(values)} values, not a multiple of {ncomp}")
    if ntuples_expected is not None and len(values) != ntuples_expected * ncomp:
        fail(f"{where}: {name!r} has {len(values)} values, expected {ntuples_expected} x {ncomp}")
    return name, ncomp, values


def tuples(values, ncomp):
    return [values[i:i + ncomp] for i in range(0, len(values), ncomp)]


def read_attributes(parent, where, n):
    """PointData / CellData: unique names, Scalars/Vectors attributes valid."""
    arrays = {}
    if parent is None:
        return arrays
    for elem in parent:
        if elem.tag != "DataArray":
            fail(f"{where}: unexpected element <{elem.tag}>")
            continue
        name, ncomp, values = data_array(elem, where, n)
        if not name:
            fail(f"{where}: DataArray without Name")
        if name in arrays:
            fail(f"{where}: two arrays named {name!r}")
        arrays[name] = (ncomp, values)
    for attr, want in (("Scalars", None), ("Vectors", 3), ("Tensors", 9), ("Normals", 3)):
        ref = parent.get(attr)
        if ref is None:
            continue
        if ref not in arrays:
            fail(f"{where}: {attr}={ref!r} names no array")
        elif want is not None and arrays[ref][0] != want:
            fail(f"{where}: {attr}={ref!r} has {arrays[ref][0]} components")
    return arrays


def read_vtu(path):
    """Check one .vtu and return its grid and arrays."""
    where = os.path.basename(path)
    with open(path, encoding="ascii") as f:
        text = f.read()
    root = ET.fromstring(text)
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        fail(f"{where}: root is <{root.tag} type={root.get('type')!r}>")
    if root.get("byte_order") not in ("LittleEndian", "BigEndian"):
        fail(f"{where}: byte_order {root.get('byte_order')!r}")
    if not re.fullmatch(r"\d+\.\d+", root.get("version", "")):
        fail(f"{where}: version {root.get('version')!r}")
    grids = root.findall("UnstructuredGrid")
    if len(grids) != 1 or len(root) != 1:
        fail(f"{where}: VTKFile must hold exactly one <UnstructuredGrid>")
        return None
    grid = grids[0]
    for elem in grid:
        if elem.tag not in ("Piece", "FieldData"):
            fail(f"{where}: unexpected <{elem.tag}> in <UnstructuredGrid>")
    fd = grid.find("FieldData")
    if fd is not None:
        for elem in fd:
            if elem.get("NumberOfTuples") is None:
                fail(f"{where}: FieldData array {elem.get('Name')!r} lacks NumberOfTuples")
            else:
                data_array(elem, where + " FieldData", int(elem.get("NumberOfTuples")))
    pieces = grid.findall("Piece")
    if len(pieces) != 1:
        fail(f"{where}: {len(pieces)} pieces (superjoin writes one)")
        return None
    piece = pieces[0]
    for elem in piece:
        if elem.tag not in ("PointData", "CellData", "Points", "Cells"):
            fail(f"{where}: unexpected <{elem.tag}> in <Piece>")
    npoint = int(piece.get("NumberOfPoints"))
    ncell = int(piece.get("NumberOfCells"))
    pts = piece.find("Points")
    if pts is None or len(pts) != 1:
        fail(f"{where}: <Points> must hold one DataArray")
        return None
    _, ncomp, xyz = data_array(pts[0], where + " Points", npoint)
    if ncomp != 3 or pts[0].get("type") not in ("Float32", "Float64"):
        fail(f"{where}: Points must be 3-component floats")
    cells = piece.find("Cells")
    carr = {}
    for elem in (cells if cells is not None else []):
        n = elem.get("Name")
        if n in ("offsets", "types"):
            carr[n] = data_array(elem, where + " Cells", ncell)[2]
        elif n == "connectivity":
            carr[n] = data_array(elem, where + " Cells")[2]
        else:
            fail(f"{where}: unexpected Cells array {n!r}")
    if set(carr) != {"connectivity", "offsets", "types"}:
        fail(f"{where}: <Cells> needs connectivity, offsets and types")
        return None
    conn, offs, types = carr["connectivity"], carr["offsets"], carr["types"]
    prev = 0
    cell_points = []
    for c, (o, t) in enumerate(zip(offs, types)):
        if o <= prev and c > 0 or o < 0:
            fail(f"{where}: offsets not increasing at cell {c}")
        if t not in CELL_POINTS:
            fail(f"{where}: cell {c} has type {t}")
        elif o - prev != CELL_POINTS[t]:
            fail(f"{where}: cell {c} of type {t} has {o - prev} points")
        cell_points.append(conn[prev:o])
        prev = o
    if offs and offs[-1] != len(conn):
        fail(f"{where}: last offset {offs[-1]} but {len(conn)} connectivity entries")
    for p in conn:
        if not 0 <= p < npoint:
            fail(f"{where}: connectivity names point {p} of {npoint}")
            break
    pdata = read_attributes(piece.find("PointData"), where + " PointData", npoint)
    cdata = read_attributes(piece.find("CellData"), where + " CellData", ncell)
    subs = {int(k): v for k, v in re.findall(r"<!-- substructure (\d+) (\S+) -->", text)}
    contacts = {int(k): v for k, v in re.findall(r"<!-- contact (\d+) (\S+) -->", text)}
    return dict(npoint=npoint, ncell=ncell, xyz=tuples(xyz, 3), cells=cell_points, types=types,
                pdata=pdata, cdata=cdata, subs=subs, contacts=contacts)


def read_pvd(path):
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "Collection":
        fail(f"{path}: root is not a VTKFile of type Collection")
    coll = root.find("Collection")
    if coll is None:
        fail(f"{path}: no <Collection>")
        return []
    out = []
    for k, ds in enumerate(coll):
        if ds.tag != "DataSet" or ds.get("file") is None or ds.get("timestep") is None:
            fail(f"{path}: entry {k} is not a DataSet with file and timestep")
            continue
        if int(ds.get("timestep")) != k + 1:
            fail(f"{path}: DataSet {k} has timestep {ds.get('timestep')}")
        out.append((ds.get("name"), os.path.join(os.path.dirname(path), ds.get("file"))))
    return out


def csv_rows(path):
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def get(g, kind, name):
    arrays = g["pdata"] if kind == "p" else g["cdata"]
    if name not in arrays:
        fail(f"missing {'point' if kind == 'p' else 'cell'} array {name!r}")
        return None
    ncomp, values = arrays[name]
    return tuples(values, ncomp)


def optional(g, kind, name, csvdir, table, n):
    """An array that the grid holds exactly when the CSV table exists (file
    requests select both); absent, its values count as zeros."""
    arrays = g["pdata"] if kind == "p" else g["cdata"]
    present = os.path.exists(os.path.join(csvdir, table))
    if present != (name in arrays):
        fail(f"array {name!r} {'missing' if present else 'written'} while {table} is "
             f"{'written' if present else 'not'}")
    if name in arrays:
        return get(g, kind, name)
    return [[0.0] * 6 for _ in range(n)]


def compare(g, step_name, csvdir):
    """Every CSV value of the step is in the grid; what the CSV omits is zero."""
    npt, ncl = g["npoint"], g["ncell"]
    disp = optional(g, "p", "displacement", csvdir, "displacements.csv", npt)
    rot = optional(g, "p", "rotation", csvdir, "displacements.csv", npt)
    psub, pnode = get(g, "p", "substructure"), get(g, "p", "node")
    kind, csub = get(g, "c", "kind"), get(g, "c", "substructure")
    celem, ctype, ccon = get(g, "c", "element"), get(g, "c", "element_type"), get(g, "c", "contact")
    end1 = optional(g, "c", "end1", csvdir, "element_forces.csv", ncl)
    end2 = optional(g, "c", "end2", csvdir, "element_forces.csv", ncl)
    plate = optional(g, "c", "plate", csvdir, "element_forces.csv", ncl)
    delta, force = get(g, "c", "delta"), get(g, "c", "force")
    reac = optional(g, "c", "reaction", csvdir, "reactions.csv", ncl)
    presults = get(g, "p", "results") if "results" in g["pdata"] else [[1]] * npt
    if None in (disp, rot, psub, pnode, kind, csub, celem, ctype, ccon, end1, end2, plate, delta, force, reac):
        return
    subname = g["subs"]
    point_of = {(subname.get(psub[p][0]), pnode[p][0]): p for p in range(g["npoint"])}
    if len(point_of) != g["npoint"]:
        fail("point (substructure, node) pairs are not unique")
    where = f"step {step_name}"

    # displacements
    seen = set()
    for r in csv_rows(os.path.join(csvdir, "displacements.csv")) or []:
        if r["step"] != step_name:
            continue
        p = point_of.get((r["substructure"], int(r["node"])))
        if p is None:
            fail(f"{where}: node {r['substructure']}.{r['node']} of the CSV is not a point")
            continue
        seen.add(p)
        want = [float(r[c]) for c in ("u1", "u2", "u3", "ur1", "ur2", "ur3")]
        if disp[p] + rot[p] != want:
            fail(f"{where}: point {r['substructure']}.{r['node']}: {disp[p] + rot[p]} != CSV {want}")
    for p in set(range(g["npoint"])) - seen:
        if any(disp[p]) or any(rot[p]):
            fail(f"{where}: point {p} moves but is not in displacements.csv")

    # cells of each kind
    ncell = g["ncell"]
    elem_cells = {}
    for c in range(ncell):
        k = kind[c][0]
        if k == KIND_ELEMENT:
            key = (subname.get(csub[c][0]), celem[c][0])
            if key in elem_cells:
                fail(f"{where}: element {key} appears twice")
            elem_cells[key] = c
            if g["types"][c] != ELEMENT_CELL.get(ctype[c][0]):
                fail(f"{where}: element {key} has cell type {g['types'][c]} for element type {ctype[c][0]}")
        elif k == KIND_CONTACT:
            if g["types"][c] != 3 or ccon[c][0] not in g["contacts"]:
                fail(f"{where}: contact cell {c} is not a line of a known contact")
        elif k == KIND_SUPPORT:
            if g["types"][c] != 1:
                fail(f"{where}: support cell {c} is not a vertex")
        else:
            fail(f"{where}: cell {c} has kind {k}")
        if k != KIND_ELEMENT and (any(end1[c]) or any(end2[c]) or any(plate[c]) or celem[c][0] or ctype[c][0]):
            fail(f"{where}: cell {c} of kind {k} carries element data")
        if k != KIND_CONTACT and (any(delta[c]) or any(force[c]) or ccon[c][0]):
            fail(f"{where}: cell {c} of kind {k} carries contact data")
        if k != KIND_SUPPORT and any(reac[c]):
            fail(f"{where}: cell {c} of kind {k} carries a reaction")

    # element forces (trusses and beams)
    seen = set()
    nline = 0
    for r in csv_rows(os.path.join(csvdir, "element_forces.csv")) or []:
        if r["step"] != step_name:
            continue
        c = elem_cells.get((r["substructure"], int(r["element"])))
        if c is None:
            fail(f"{where}: element {r['substructure']}.{r['element']} of the CSV is not a cell")
            continue
        if ctype[c][0] != ELEMENT_TYPE_CODES[r["type"]]:
            fail(f"{where}: element {r['substructure']}.{r['element']} type {ctype[c][0]} != {r['type']}")
        seen.add(c)
        nline += 1
        want = [float(r[k]) for k in ("n", "vy", "vz", "t", "my", "mz")]
        got = end1[c] if r["end"] == "1" else end2[c]
        if got != want:
            fail(f"{where}: element {r['substructure']}.{r['element']} end {r['end']}: {got} != CSV {want}")
    cresults = get(g, "c", "results") if "results" in g["cdata"] else [[1]] * ncell
    nlinecells = sum(1 for c in elem_cells.values() if g["types"][c] in (3, 4) and cresults[c][0])
    if os.path.exists(os.path.join(csvdir, "element_forces.csv")) and nline != 2 * nlinecells:
        fail(f"{where}: {nline} element_forces.csv rows for {nlinecells} line elements")
    for c in set(elem_cells.values()) - seen:
        if any(end1[c]) or any(end2[c]):
            fail(f"{where}: cell {c} has end forces that element_forces.csv lacks")

    # plate resultants
    rows = csv_rows(os.path.join(csvdir, "plate_results.csv"))
    seen = set()
    for r in rows or []:
        if r["step"] != step_name:
            continue
        c = elem_cells.get((r["substructure"], int(r["element"])))
        if c is None:
            fail(f"{where}: plate element {r['substructure']}.{r['element']} is not a cell")
            continue
        seen.add(c)
        want = [float(r[k]) for k in ("nx", "ny", "nxy", "mx", "my", "mxy")]
        if plate[c] != want:
            fail(f"{where}: plate {r['substructure']}.{r['element']}: {plate[c]} != CSV {want}")
    for c in set(elem_cells.values()) - seen:
        if any(plate[c]):
            fail(f"{where}: cell {c} has plate resultants that plate_results.csv lacks")

    # contacts: (contact name, master id, slave id) -> cell
    contact_cells = {}
    for c in range(ncell):
        if kind[c][0] != KIND_CONTACT:
            continue
        m, s = g["cells"][c]
        key = (g["contacts"].get(ccon[c][0]), pnode[m][0], pnode[s][0])
        contact_cells.setdefault(key, []).append(c)
    expected = {}
    for r in csv_rows(os.path.join(csvdir, "contact_forces.csv")):
        if r["step"] != step_name:
            continue
        key = (r["contact"], int(r["master_node"]), int(r["slave_node"]))
        expected.setdefault(key, {})[int(r["dof"])] = (float(r["delta"]), float(r["force"]))
    for key, cs in contact_cells.items():
        dofs = expected.pop(key, {})
        matched = False
        for c in cs:   # the same node ids may pair nodes of different substructures
            ok = all((delta[c][d - 1], force[c][d - 1]) == dofs.get(d, (0.0, 0.0)) for d in range(1, 7))
            matched = matched or ok
        if not matched and len(cs) == 1:
            fail(f"{where}: contact {key}: delta {delta[cs[0]]} force {force[cs[0]]} != CSV {dofs}")
        elif not matched:
            fail(f"{where}: contact {key}: no cell matches the CSV")
    for key in expected:
        fail(f"{where}: contact {key} of the CSV is not a cell")

    # reactions: one vertex cell per supported node
    sup_cells = {}
    for c in range(ncell):
        if kind[c][0] == KIND_SUPPORT:
            p = g["cells"][c][0]
            if presults[p][0]:
                sup_cells[(subname.get(psub[p][0]), pnode[p][0])] = c
            elif any(reac[c]):
                fail(f"{where}: support cell {c} holds a reaction at a point without results")
    expected = {}
    reactions = csv_rows(os.path.join(csvdir, "reactions.csv"))
    if reactions is None:   # *NODE FILE requests without RF: no reactions table to compare with
        return
    for r in reactions:
        if r["step"] != step_name:
            continue
        vec = expected.setdefault((r["substructure"], int(r["node"])), [0.0] * 6)
        vec[int(r["dof"]) - 1] += float(r["force"])
    if set(expected) != set(sup_cells):
        fail(f"{where}: supported nodes {sorted(sup_cells)} != reactions.csv nodes {sorted(expected)}")
    for key, vec in expected.items():
        c = sup_cells.get(key)
        if c is not None and reac[c] != vec:
            fail(f"{where}: reaction at {key}: {reac[c]} != CSV {vec}")


def main(argv):
    if len(argv) not in (2, 4) or (len(argv) == 4 and argv[2] != "--csv"):
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    pvd = argv[1]
    csvdir = argv[3] if len(argv) == 4 else None
    pieces = read_pvd(pvd)
    if not pieces:
        fail(f"{pvd}: names no data set")
    ncell = None
    for name, path in pieces:
        if not os.path.exists(path):
            fail(f"{pvd}: names {path}, which does not exist")
            continue
        g = read_vtu(path)
        if g is None:
            continue
        if ncell is not None and (g["ncell"], g["npoint"]) != ncell:
            fail(f"{path}: the grid differs between steps")
        ncell = (g["ncell"], g["npoint"])
        if csvdir:
            compare(g, name, csvdir)
    for p in problems:
        print("FAIL: " + p)
    if not problems:
        print(f"{pvd}: {len(pieces)} steps, {ncell[1]} points, {ncell[0]} cells: format OK"
              + (", values equal the CSV files" if csvdir else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
