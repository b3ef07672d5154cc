#!/usr/bin/env python3
"""Body loads on the 3D solids (*DLOAD CENTRIF and GRAV) and the C3D8R
element, through the whole program, against closed forms.

usage: verify_body_loads.py SUPERJOIN WORKDIR
Exit status 1 if any check fails.

Cases
- CENTRIF resultant, every solid type (C3D8, C3D8I, C3D8R, C3D20, C3D20R,
  C3D4, C3D10, C3D6, C3D15): a box clamped on one face, spinning about an
  axis parallel to z: the reactions sum to -rho w^2 V r_c (r_c: the
  centroid's distance vector from the axis) to round-off (the consistent
  loads integrate N_a r exactly);
- CENTRIF on a bar along a radius (L = 10, 0.2 x 0.2, nu = 0, axis z through
  its root, u_x = 0 at the root): N = rho A w^2 (L^2 - x^2)/2, the tip
  u = rho w^2 L^3 / (3 E); C3D20R, 5 / 10 / 20 x 2 x 2 elements: u_x exact
  at the nodes between elements (as a 1D bar with consistent loads), the
  root force exact;
- CENTRIF on a rotating thick disk with a hole (a = 0.2, b = 1, a quarter,
  symmetry planes, u_z = 0 everywhere: the plane-strain solution of Timoshenko
  & Goodier, Theory of Elasticity, 3rd ed., sec. 32, with nu/(1 - nu) for nu),
  C3D20R on curved (exact arcs) meshes of 2 x 2, 4 x 4, 8 x 8: radial
  displacement at the bore and the rim, convergence rate (measured 3.5-3.6);
- GRAV on a hanging column (1 x 1 x L, hung by its top face on rollers, three
  points against rigid motion): sigma_zz = rho g (L - z) from the bottom
  z = 0, u_z quadratic: exact for the quadratic types (C3D20, C3D20R, C3D10,
  C3D15), tip displacement -rho g L^2 / (2 E);
- C3D8R: the constant-stress patch test on the distorted 2 x 2 x 2 block of
  verify_solids (interior exact to round-off, stress at every element centre
  the constant one); MacNeal & Harder's straight cantilever (6 x 0.2 x 0.1,
  E = 1e7, nu = 0.3, 6 x 1 x 1 elements, unit tip loads in-plane and
  out-of-plane): the ratio to the beam theory tip deflection, and CalculiX
  2.20's on the same mesh if `ccx` is on PATH.
"""
import csv
import math
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import verify_solids as vs  # noqa: E402

ALL_TYPES = ("C3D8", "C3D8I", "C3D8R", "C3D20", "C3D20R", "C3D4", "C3D10", "C3D6", "C3D15")


class PolarMesh(vs.Mesh):
    """A Mesh whose grid (s_r, s_t, s_z) maps to a quarter of an annulus
    a <= r <= b, 0 <= theta <= 90 degrees, 0 <= z <= h (arcs exact at the
    mid-side nodes)."""

    def __init__(self, n, a, b, h, etype):
        self.a, self.b, self.h = a, b, h
        super().__init__(n, (1.0, 1.0, 1.0), etype, False, curved=True)

    def map(self, p):
        s = [p[d] / (2 * self.n[d]) for d in range(3)]
        r = self.a + (self.b - self.a) * s[0]
        t = 0.5 * math.pi * s[1]
        return (r * math.cos(t), r * math.sin(t), self.h * s[2])


def run_deck(exe, work, name, text):
    return vs.solve(exe, work, name, text)


def centrif_resultant(exe, work):
    print("\n## CENTRIF resultant, every solid type (box 2 x 1.5 x 1, axis parallel to z through (-1, 0.5))\n")
    rho, w2 = 7.8e-3, 1.0e4
    size = (2.0, 1.5, 1.0)
    axis_p = (-1.0, 0.5, 0.0)
    for et in ALL_TYPES:
        mesh = vs.Mesh((2, 2, 2), size, et, False)
        bnd = [(n, d, 0.0) for n, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
        card = f"*DLOAD\n ALL, CENTRIF, {vs.fmt(w2)}, {axis_p[0]}, {axis_p[1]}, {axis_p[2]}, 0., 0., 1."
        disp, reac = run_deck(exe, work, "centrif_sum_" + et, vs.deck(mesh, 2.0e5, 0.3, bnd, [], extra=card,
                                                                       density=rho))
        if disp is None:
            continue
        vol = size[0] * size[1] * size[2]
        want = [-rho * w2 * vol * (size[0] / 2 - axis_p[0]), -rho * w2 * vol * (size[1] / 2 - axis_p[1]), 0.0]
        got = [sum(v for (n, d), v in reac.items() if d == k) for k in (1, 2, 3)]
        err = max(abs(g - w) for g, w in zip(got, want)) / max(abs(v) for v in want)
        vs.check(err < 1e-12, f"{et}: reactions {got[0]:.12g}, {got[1]:.12g}, {got[2]:.3g} = -rho w^2 V r_c "
                              f"({err:.1e})")


def centrif_bar(exe, work):
    print("\n## CENTRIF on a bar along a radius (C3D20R, L = 10, 0.2 x 0.2, E = 2e5, nu = 0, rho = 7.8e-3, "
          "w^2 = 1e4)\n")
    length, b, e, rho, w2 = 10.0, 0.2, 2.0e5, 7.8e-3, 1.0e4
    tip_exact = rho * w2 * length ** 3 / (3 * e)
    print(f"closed form: tip u = rho w^2 L^3 / (3 E) = {tip_exact:.9e}, N(0) = rho A w^2 L^2 / 2 = "
          f"{rho * b * b * w2 * length ** 2 / 2:.9e}\n")
    print("| elements | tip u | / closed form | root reaction / N(0) |")
    print("|---|---|---|---|")
    errs = []
    for n in (5, 10, 20):
        mesh = vs.Mesh((n, 2, 2), (length, b, b), "C3D20R", False)
        mesh.nodes = {k: (x[0], x[1] - b / 2, x[2] - b / 2) for k, x in mesh.nodes.items()}
        bnd = [(nd, 1, 0.0) for nd, x in mesh.nodes.items() if x[0] == 0.0]
        bnd += [(nd, d, 0.0) for nd, x in mesh.nodes.items() if x[0] == 0.0 and x[1] == 0.0 and x[2] == 0.0
                for d in (2, 3)]
        bnd += [(nd, 3, 0.0) for nd, x in mesh.nodes.items() if x[0] == 0.0 and x[1] == b / 2 and x[2] == 0.0]
        card = f"*DLOAD\n ALL, CENTRIF, {vs.fmt(w2)}, 0., 0., 0., 0., 0., 1."
        disp, reac = run_deck(exe, work, f"centrif_bar_{n}", vs.deck(mesh, e, 0.0, sorted(bnd), [], extra=card,
                                                                      density=rho))
        if disp is None:
            return
        tip = [disp[nd][0] for nd, x in mesh.nodes.items() if x[0] == length]
        mean = sum(tip) / len(tip)
        root = -sum(v for (nd, d), v in reac.items() if d == 1)
        # u(x) = rho w^2 (L^2 x - x^3 / 3) / (2E) at the nodes between elements (1D nodal exactness)
        ends = [abs(disp[nd][0] - rho * w2 * (length ** 2 * x[0] - x[0] ** 3 / 3) / (2 * e))
                for nd, x in mesh.nodes.items() if mesh.index[nd][0] % 2 == 0]
        errs.append(max(ends) / tip_exact)
        print(f"| {n} | {mean:.9e} | {mean / tip_exact:.12f} | {root / (rho * b * b * w2 * length ** 2 / 2):.12f} |")
        # exact up to round-off: the sum of K u - f over the support's nodes, cancelling terms of the
        # size of the largest nodal force (the 20-element bar measured 2e-12, dense or structured B^T D B)
        vs.check(abs(root / (rho * b * b * w2 * length ** 2 / 2) - 1) < 1e-10, f"bar, {n} elements: root force "
                 "= rho A w^2 L^2 / 2")
    print(f"\nlargest error of u_x at the nodes between elements / tip u: {', '.join(f'{v:.1e}' for v in errs)} "
          "(exact: consistent loads on a uniaxial field)")
    vs.check(max(errs) < 1e-10, "bar: u_x exact at the element ends (rho w^2 (L^2 x - x^3/3) / 2E)")


def disk_exact(r, a, b, e, nu, rho, w2):
    """Radial displacement of the rotating annulus a <= r <= b in plane strain
    (free bore and rim): plane-stress stresses with nu' = nu / (1 - nu), then
    eps_theta = ((1 + nu)/E) ((1 - nu) s_t - nu s_r), u = r eps_theta."""
    nup = nu / (1 - nu)
    k = (3 + nup) / 8 * rho * w2
    s_r = k * (a * a + b * b - a * a * b * b / r ** 2 - r * r)
    s_t = k * (a * a + b * b + a * a * b * b / r ** 2 - (1 + 3 * nup) / (3 + nup) * r * r)
    return r * (1 + nu) / e * ((1 - nu) * s_t - nu * s_r)


def centrif_disk(exe, work):
    a, b, h, e, nu, rho, w2 = 0.2, 1.0, 0.25, 2.0e5, 0.3, 7.8e-3, 1.0e4
    print(f"\n## CENTRIF on a thick disk with a hole in plane strain (C3D20R, a = {a}, b = {b}, nu = {nu}, "
          "quarter, u_z = 0)\n")
    ua, ub = disk_exact(a, a, b, e, nu, rho, w2), disk_exact(b, a, b, e, nu, rho, w2)
    print(f"closed form: u(a) = {ua:.9e}, u(b) = {ub:.9e}\n")
    print("| mesh (radial x around) | u(a) / exact | u(b) / exact | largest nodal error / u(b) |")
    print("|---|---|---|---|")
    errs = []
    for n in (2, 4, 8):
        mesh = PolarMesh((n, n, 1), a, b, h, "C3D20R")
        bnd = [(nd, 3, 0.0) for nd in mesh.nodes]
        bnd += [(nd, 2, 0.0) for nd, x in mesh.nodes.items() if abs(x[1]) < 1e-12]
        bnd += [(nd, 1, 0.0) for nd, x in mesh.nodes.items() if abs(x[0]) < 1e-12]
        card = f"*DLOAD\n ALL, CENTRIF, {vs.fmt(w2)}, 0., 0., 0., 0., 0., 1."
        disp, _ = run_deck(exe, work, f"centrif_disk_{n}", vs.deck(mesh, e, nu, sorted(bnd), [], extra=card,
                                                                    density=rho))
        if disp is None:
            return
        worst, ra, rb = 0.0, [], []
        for nd, x in mesh.nodes.items():
            r = math.hypot(x[0], x[1])
            ur = (disp[nd][0] * x[0] + disp[nd][1] * x[1]) / r
            worst = max(worst, abs(ur - disk_exact(r, a, b, e, nu, rho, w2)))
            if abs(r - a) < 1e-9:
                ra.append(ur)
            if abs(r - b) < 1e-9:
                rb.append(ur)
        errs.append(worst / ub)
        print(f"| {n} x {n} | {sum(ra) / len(ra) / ua:.8f} | {sum(rb) / len(rb) / ub:.8f} | {worst / ub:.2e} |")
    rates = [math.log(errs[i] / errs[i + 1]) / math.log(2) for i in range(len(errs) - 1)]
    print(f"\nlargest nodal error: rates {', '.join(f'{q:.2f}' for q in rates)} as the elements halve")
    vs.check(errs[-1] < 1e-4, f"disk: nodal radial displacements within 1e-4 of u(b) on 8 x 8 ({errs[-1]:.1e})")
    vs.check(all(q > 2.5 for q in rates), "disk: the error falls at least as h^2.5")


def hanging_column(exe, work):
    length, e, nu, rho, g = 4.0, 2.0e5, 0.0, 7.8e-3, 9.81
    print(f"\n## GRAV on a hanging column (1 x 1 x {length}, hung by its top face z = L on rollers, nu = 0)\n")
    tip = -rho * g * length ** 2 / (2 * e)
    print(f"closed form: sigma_zz = rho g z (rho g (L - z) from the top), u_z = -rho g (L^2 - z^2) / (2E), "
          f"bottom {tip:.9e}\n")
    for et in ("C3D20", "C3D20R", "C3D10", "C3D15", "C3D8", "C3D8R"):
        mesh = vs.Mesh((2, 2, 4), (1.0, 1.0, length), et, False)
        top = [nd for nd, x in mesh.nodes.items() if x[2] == length]
        bnd = [(nd, 3, 0.0) for nd in top]
        corner = [nd for nd in top if mesh.nodes[nd][0] == 0.0 and mesh.nodes[nd][1] == 0.0][0]
        other = [nd for nd in top if mesh.nodes[nd][0] == 1.0 and mesh.nodes[nd][1] == 0.0][0]
        bnd += [(corner, 1, 0.0), (corner, 2, 0.0), (other, 2, 0.0)]
        disp, _ = run_deck(exe, work, "hanging_" + et, vs.deck(mesh, e, nu, sorted(bnd), [],
                           extra=f"*DLOAD\n ALL, GRAV, {vs.fmt(g)}, 0., 0., -1.\n*EL FILE\nS", density=rho))
        if disp is None:
            continue
        worst = max(abs(disp[nd][2] + rho * g * (length ** 2 - x[2] ** 2) / (2 * e)) for nd, x in mesh.nodes.items())
        with open(os.path.join(work, "hanging_" + et + "_csv", "nodal_stresses.csv")) as f:
            szz = [(float(r["szz"]), mesh.nodes[int(r["node"])][2]) for r in csv.DictReader(f)]
        serr = max(abs(s - rho * g * z) for s, z in szz) / (rho * g * length)
        bottom = [disp[nd][2] for nd, x in mesh.nodes.items() if x[2] == 0.0]
        mean = sum(bottom) / len(bottom)
        print(f"{et}: bottom u_z {mean:.9e} ({mean / tip:.9f}), largest error of u_z {worst / abs(tip):.1e}, "
              f"of nodal sigma_zz {serr:.1e} (of rho g L)")
        if et in ("C3D20", "C3D20R", "C3D10", "C3D15"):
            vs.check(worst < 1e-10 * abs(tip) and serr < 1e-10, f"{et}: hanging column exact (u_z and sigma_zz)")
        else:
            vs.check(abs(mean / tip - 1) < 0.02, f"{et}: hanging column tip within 2%")


def c3d8r_patch(exe, work):
    print("\n## C3D8R patch test (distorted 2 x 2 x 2 block, linear field on the boundary, interior free)\n")
    e, nu = 1.0e3, 0.25
    grad = [[1.0e-3, 2.0e-4, -3.0e-4], [4.0e-4, -5.0e-4, 1.0e-4], [-2.0e-4, 3.0e-4, 6.0e-4]]
    mesh = vs.Mesh((2, 2, 2), (2.0, 1.5, 1.0), "C3D8R", True)

    def field(x):
        return [1e-3 + sum(grad[i][j] * x[j] for j in range(3)) for i in range(3)]
    bnd = [(n, d + 1, field(x)[d]) for n, x in sorted(mesh.nodes.items()) if mesh.boundary(n) for d in range(3)]
    disp, _ = run_deck(exe, work, "c3d8r_patch", vs.deck(mesh, e, nu, bnd, [], extra="*EL FILE\nS"))
    if disp is None:
        return
    umax = max(abs(v) for x in mesh.nodes.values() for v in field(x))
    err = max(abs(disp[n][d] - field(x)[d]) for n, x in mesh.nodes.items() for d in range(3))
    eps = [[(grad[i][j] + grad[j][i]) / 2 for j in range(3)] for i in range(3)]
    sig = vs.elasticity(e, nu, eps)
    serr = vs.stress_error(os.path.join(work, "c3d8r_patch_csv"), sig)
    vs.check(err < 1e-12 * umax, f"C3D8R patch: interior displacements exact ({err / umax:.1e})")
    vs.check(serr < 1e-10, f"C3D8R patch: stresses the constant one ({serr:.1e})")


def macneal(exe, work):
    length, w, t, e, nu = 6.0, 0.2, 0.1, 1.0e7, 0.3
    print("\n## MacNeal & Harder straight cantilever (6 x 0.2 x 0.1, E = 1e7, nu = 0.3, 6 x 1 x 1 "
          "rectangular elements, unit tip load)\n")
    beam = {"in-plane (y)": length ** 3 / (3 * e * t * w ** 3 / 12),
            "out-of-plane (z)": length ** 3 / (3 * e * w * t ** 3 / 12)}
    print("MacNeal & Harder's reference tip deflections: 0.1081 (in-plane), 0.4321 (out-of-plane);\n"
          f"beam theory (Euler-Bernoulli): {beam['in-plane (y)']:.4f}, {beam['out-of-plane (z)']:.4f}\n")
    print("| element | load | tip deflection | / beam | / MacNeal-Harder | CalculiX 2.20 |")
    print("|---|---|---|---|---|---|")
    ref = {"in-plane (y)": 0.1081, "out-of-plane (z)": 0.4321}
    ratios = {}
    for et in ("C3D8R", "C3D8I", "C3D8"):
        mesh = vs.Mesh((6, 1, 1), (length, w, t), et, False)
        bnd = [(nd, d, 0.0) for nd, x in sorted(mesh.nodes.items()) if x[0] == 0.0 for d in (1, 2, 3)]
        tipn = [nd for nd, x in mesh.nodes.items() if x[0] == length]
        for load, dof in (("in-plane (y)", 2), ("out-of-plane (z)", 3)):
            cl = [(nd, dof, 1.0 / len(tipn)) for nd in sorted(tipn)]
            text = vs.deck(mesh, e, nu, bnd, cl)
            name = f"macneal_{et}_{dof}"
            disp, _ = run_deck(exe, work, name, text)
            if disp is None:
                continue
            tip = sum(disp[nd][dof - 1] for nd in tipn) / len(tipn)
            ccx = ccx_tip(work, name, text, tipn, dof)
            ratios[(et, dof)] = tip / beam[load]
            print(f"| {et} | {load} | {tip:.5f} | {tip / beam[load]:.4f} | {tip / ref[load]:.4f} | {ccx} |")
    # equal in exact arithmetic; the tolerance allows the round-off of another build (Debug: 2e-9)
    diff = max(abs(ratios.get(("C3D8R", d), 0) - ratios.get(("C3D8I", d), 1)) for d in (2, 3))
    vs.check(diff < 1e-7,
             f"C3D8R: on rectangular elements, C3D8I's deflections (its hourglass stiffness is C3D8I's; {diff:.1e})")
    vs.check(all(0.95 < ratios.get(("C3D8R", d), 0) < 1.05 for d in (2, 3)),
             "C3D8R: MacNeal-Harder tip deflections within 5% of beam theory")


def ccx_tip(work, name, text, tipn, dof):
    """CalculiX's mean tip deflection of the same deck (`ccx -i`), '-' without ccx."""
    if shutil.which("ccx") is None:
        return "-"
    job = os.path.join(work, name + "_ccx")
    with open(job + ".inp", "w") as f:
        f.write(text)
    r = subprocess.run(["ccx", "-i", os.path.basename(job)], cwd=work, capture_output=True, text=True)
    if r.returncode != 0 or not os.path.exists(job + ".dat"):
        return "failed"
    vals = {}
    with open(job + ".dat") as f:
        for line in f:
            p = line.split()
            if len(p) == 4 and p[0].isdigit():
                vals[int(p[0])] = [float(v) for v in p[1:]]
    return f"{sum(vals[nd][dof - 1] for nd in tipn) / len(tipn):.5f}"


def main():
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    exe, work = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    os.makedirs(work, exist_ok=True)
    centrif_resultant(exe, work)
    centrif_bar(exe, work)
    centrif_disk(exe, work)
    hanging_column(exe, work)
    c3d8r_patch(exe, work)
    macneal(exe, work)
    if vs.failures:
        print(f"\nFAIL: {len(vs.failures)} checks")
        sys.exit(1)
    print("\nall checks passed")


if __name__ == "__main__":
    main()
