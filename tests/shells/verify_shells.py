#!/usr/bin/env python3
"""Plate and shell verification: generates decks (shellgen.py), solves them with
superjoin, compares with closed forms and published benchmarks, prints tables.

usage: verify_shells.py SUPERJOIN WORKDIR [--full] [--markdown FILE]
Exit status 1 if any check fails. The default set is the test-suite one;
--full adds the finer meshes used for doc/verification.md.
"""
import argparse
import csv
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import shellgen as g  # noqa: E402

failures = []
lines = []


def say(text=""):
    print(text)
    lines.append(text)


def check(ok, what):
    if not ok:
        failures.append(what)
        say(f"FAIL: {what}")


def solve(exe, work, case):
    """Run superjoin on a case; return (displacements {(sub, node): [6]}, seconds)."""
    path = os.path.join(work, case.name + ".deck")
    with open(path, "w") as f:
        f.write(case.deck)
    out = os.path.join(work, case.name + "_csv")
    t0 = time.perf_counter()
    r = subprocess.run([exe, "-q", "--csv", out, "-o", os.path.join(work, case.name + ".lst"), path],
                       capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if r.returncode != 0:
        failures.append(f"{case.name}: exit {r.returncode}: {r.stderr.strip()[:300]}")
        say(f"FAIL: {case.name}: exit {r.returncode}: {r.stderr.strip()[:300]}")
        return None, dt
    disp = {}
    with open(os.path.join(out, "displacements.csv")) as f:
        for row in csv.DictReader(f):
            disp[(row["substructure"], int(row["node"]))] = [float(row[k]) for k in
                                                              ("u1", "u2", "u3", "ur1", "ur2", "ur3")]
    return disp, dt


def value(disp, case):
    return disp[(case.sub, case.node)][case.dof - 1]


def convergence(exe, work, title, make, meshes, tol_fine, min_order, exact_ref):
    """Mesh sequence of one case: table of value/reference - 1 and observed order."""
    say(f"\n### {title}\n")
    say("| mesh | DOFs | w / w_ref | error | order | time (s) |")
    say("|---|---|---|---|---|---|")
    errs = []
    vals = []
    for n in meshes:
        case = make(n)
        disp, dt = solve(exe, work, case)
        if disp is None:
            return
        v = value(disp, case)
        err = v / case.reference - 1.0
        order = ""
        if errs and exact_ref and abs(err) > 0 and abs(errs[-1]) > 0:
            order = f"{math.log(abs(errs[-1] / err), 2):.2f}"
        elif len(vals) >= 2 and not exact_ref:
            d1, d2 = vals[-1] - vals[-2], v - vals[-1]
            if d2 != 0 and d1 / d2 > 0:
                order = f"{math.log(d1 / d2, 2):.2f}*"
        errs.append(err)
        vals.append(v)
        say(f"| {n}x{n} | {case.ndof} | {v / case.reference:.6f} | {err:+.2e} | {order} | {dt:.2f} |")
    extra = ""
    if not exact_ref and len(vals) >= 3:
        d1, d2 = vals[-2] - vals[-3], vals[-1] - vals[-2]
        if d2 != 0 and d1 / d2 > 1:
            rich = vals[-1] + d2 / (d1 / d2 - 1)
            extra = f"; Richardson extrapolation of the last three meshes {rich:+.6g}"
    say(f"\nreference {case.reference:+.8g} ({case.source})" +
        ("" if exact_ref else "; * order from successive differences") + extra)
    check(abs(errs[-1]) < tol_fine, f"{title}: finest mesh error {errs[-1]:.2e} above {tol_fine}")
    if exact_ref and len(errs) >= 3 and min_order:
        p = math.log(abs(errs[-2] / errs[-1]), 2)
        check(p > min_order, f"{title}: observed order {p:.2f} below {min_order}")
    if not exact_ref and len(vals) >= 3 and min_order:
        d1, d2 = vals[-2] - vals[-3], vals[-1] - vals[-2]
        p = math.log(d1 / d2, 2) if d2 != 0 and d1 / d2 > 0 else 0.0
        check(p > min_order, f"{title}: observed order {p:.2f} below {min_order}")


def single(exe, work, cases, tol):
    say("\n| case | DOFs | value | reference | ratio | time (s) |")
    say("|---|---|---|---|---|---|")
    for case, t in cases:
        disp, dt = solve(exe, work, case)
        if disp is None:
            continue
        v = value(disp, case)
        say(f"| {case.name} | {case.ndof} | {v:.6g} | {case.reference:.6g} | {v / case.reference:.4f} | {dt:.2f} |")
        if t is not None:
            check(abs(v / case.reference - 1.0) < t, f"{case.name}: ratio {v / case.reference:.4f} outside 1 +- {t}")


def split_plate(exe, work, n, etype):
    """Split plate with RIGID contacts against the one-piece plate: every
    displacement to round-off (relative to the largest)."""
    one, _ = solve(exe, work, g.square_plate(n, etype, "SS", "UNIFORM"))
    two, _ = solve(exe, work, g.square_plate(n, etype, "SS", "UNIFORM", split="RIGID"))
    if one is None or two is None:
        return
    h = n // 2
    scale = max(abs(v) for vals in one.values() for v in vals)
    worst = 0.0
    for j in range(n + 1):
        for i in range(n + 1):
            a = one[("PLATE", 1 + j * (n + 1) + i)]
            b = two[("L", 1 + j * (h + 1) + i)] if i <= h else two[("R", 1001 + j * (h + 1) + i - h)]
            worst = max(worst, max(abs(x - y) for x, y in zip(a, b)))
    say(f"| {etype} {n}x{n} | {worst / scale:.1e} |")
    check(worst / scale < 1e-10, f"split plate {etype} {n}: RIGID differs from one piece by {worst / scale:.1e}")


def patch_tests(exe, work, etypes=("S4", "S3")):
    """Membrane + bending patch test of S4 and S3 (or etypes) in an oblique plane through the
    whole program: interior displacements and every element's resultants exact."""
    say("\n## Shell patch test (MacNeal-Harder patch, membrane + bending, oblique plane)\n")
    say("| element | max interior DOF error / max DOF | max resultant error / max resultant |")
    say("|---|---|---|")
    e, nu, t = g.PATCH_E, g.PATCH_NU, g.PATCH_T
    c = e * t / (1 - nu * nu)
    n_ex = [c * (1e-3 + nu * 1e-3), c * (1e-3 + nu * 1e-3), e * t / (2 * (1 + nu)) * 1e-3]
    d = e * t ** 3 / (12 * (1 - nu * nu))
    m_ex = [-d * (1e-3 + nu * 1e-3), -d * (1e-3 + nu * 1e-3), -d * (1 - nu) * 0.5e-3]
    for et in etypes:
        deck, rot, part = g.shell_patch(et)
        case = g.Case(f"patch_{et}", deck, "PATCH", 5, 1, 1.0, "exact")
        disp, _ = solve(exe, work, case)
        if disp is None:
            continue
        worst = scale = 0.0
        for i in (5, 6, 7, 8):
            f = g.patch_field(*g.PATCH_NODES[i])
            ex = [sum(rot[r][k] * f[k] for k in range(3)) for r in range(3)] + \
                 [sum(rot[r][k] * f[3 + k] for k in range(3)) for r in range(3)]
            got = disp[("PATCH", i)]
            worst = max(worst, max(abs(a - b) for a, b in zip(got, ex)))
            scale = max(scale, max(abs(x) for x in ex))
        res_worst = 0.0
        with open(os.path.join(work, case.name + "_csv", "plate_results.csv")) as fcsv:
            for row in csv.DictReader(fcsv):
                nodes = [n for (eid, _, ns) in part.elems if eid == int(row["element"]) for n in ns]
                (x1, y1), (x2, y2) = g.PATCH_NODES[nodes[0]], g.PATCH_NODES[nodes[1]]
                ln = math.hypot(x2 - x1, y2 - y1)
                cs, sn = (x2 - x1) / ln, (y2 - y1) / ln

                def rotate(tens):
                    sx, sy, sxy = tens
                    return [sx * cs * cs + sy * sn * sn + 2 * sxy * sn * cs,
                            sx * sn * sn + sy * cs * cs - 2 * sxy * sn * cs,
                            (sy - sx) * sn * cs + sxy * (cs * cs - sn * sn)]
                exn, exm = rotate(n_ex), rotate(m_ex)
                got = [float(row[k]) for k in ("nx", "ny", "nxy", "mx", "my", "mxy")]
                res_worst = max(res_worst, max(abs(a - b) for a, b in zip(got[:3], exn)) / max(map(abs, n_ex)),
                                max(abs(a - b) for a, b in zip(got[3:], exm)) / max(map(abs, m_ex)))
        say(f"| {et} | {worst / scale:.1e} | {res_worst:.1e} |")
        check(worst / scale < 1e-9, f"patch {et}: interior displacements off by {worst / scale:.1e}")
        check(res_worst < 1e-9, f"patch {et}: resultants off by {res_worst:.1e}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--markdown")
    a = ap.parse_args()
    os.makedirs(a.work, exist_ok=True)
    exe = a.exe
    meshes = [2, 4, 8, 16, 32, 64]

    patch_tests(exe, a.work)

    say("\n## Square plates, centre deflection (a = 1, D = 1, nu = 0.3)")
    for et in ("S4", "S3"):
        convergence(exe, a.work, f"{et} simply supported, uniform pressure",
                    lambda n, et=et: g.square_plate(n, et, "SS", "UNIFORM"), meshes, 2e-3, 1.7, True)
        convergence(exe, a.work, f"{et} simply supported, central point load",
                    lambda n, et=et: g.square_plate(n, et, "SS", "POINT"), meshes, 2e-3, 1.6, True)
        convergence(exe, a.work, f"{et} clamped, uniform pressure",
                    lambda n, et=et: g.square_plate(n, et, "CL", "UNIFORM"), meshes, 2e-3, 1.7, True)
        convergence(exe, a.work, f"{et} clamped, central point load",
                    lambda n, et=et: g.square_plate(n, et, "CL", "POINT"), meshes, 2e-3, 1.6, True)

    say("\n## Plate split at x = a/2 into two substructures joined by RIGID contacts\n")
    say("| mesh | max difference / max displacement |")
    say("|---|---|")
    for et in ("S4", "S3"):
        for n in (4, 16):
            split_plate(exe, a.work, n, et)

    say("\n## Stiffened panel: B33 rib on an S4 plate, shared nodes against a separate substructure")
    say("joined by contacts on all six DOFs (centre deflection; RIGID must equal shared nodes to round-off)\n")
    say("| joint | centre deflection | relative to shared nodes |")
    say("|---|---|---|")
    shared, _ = solve(exe, a.work, g.stiffened_panel(8, "SHARED"))
    if shared is not None:
        ref_case = g.stiffened_panel(8, "SHARED")
        w0 = value(shared, ref_case)
        say(f"| shared nodes | {w0:.10e} | |")
        for joint in ("RIGID", 1e12, 1e8, 1e4):
            c = g.stiffened_panel(8, joint)
            d, _ = solve(exe, a.work, c)
            if d is None:
                continue
            w = value(d, c)
            say(f"| {joint} | {w:.10e} | {w / w0 - 1:+.2e} |")
            if joint == "RIGID":
                worst = max(abs(x - y) for k in shared for x, y in zip(shared[k], d[k]))
                scale = max(abs(x) for v in shared.values() for x in v)
                check(worst / scale < 1e-10, f"stiffened panel RIGID vs shared: {worst / scale:.1e}")
            if joint == 1e12:
                check(abs(w / w0 - 1) < 1e-6, f"stiffened panel g = 1e12: {w / w0 - 1:.1e}")

    say("\n## Plate split at x = a/2, joined by a rotational line spring k = 10 D / a"
        " (translations RIGID): convergence of the compliant answer")
    for et in ("S4", "S3"):
        convergence(exe, a.work, f"{et} simply supported, uniform pressure, joint k = 10",
                    lambda n, et=et: g.square_plate(n, et, "SS", "UNIFORM", split=10.0),
                    [4, 8, 16, 32, 64], 2e-3, 1.7, True)

    say("\n## MacNeal-Harder and other shell benchmarks")
    cases = [
        (g.straight_cantilever("CPS4", "IN", "regular"), 0.02),
        (g.straight_cantilever("CPS4", "IN", "trapezoid"), None),
        (g.straight_cantilever("CPS4", "IN", "parallelogram"), None),
        (g.straight_cantilever("S4", "IN", "regular"), 0.02),
        (g.straight_cantilever("S4", "OUT", "regular"), 0.02),
        (g.straight_cantilever("S4", "OUT", "trapezoid"), None),
        (g.twisted_beam(12, 2, "S4", "IN"), 0.05),
        (g.twisted_beam(12, 2, "S4", "OUT"), 0.05),
        (g.twisted_beam(24, 4, "S4", "IN"), 0.02),
        (g.twisted_beam(24, 4, "S4", "OUT"), 0.02),
    ]
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.scordelis_lo(n, "S4"), 0.03 if n >= 16 else None))
        cases.append((g.scordelis_lo(n, "S3"), 0.05 if n >= 16 else None))
    cases.append((g.scordelis_lo(16, "S4", gravity=True), 0.03))
    for n in (4, 8, 16) + ((32,) if a.full else ()):
        cases.append((g.pinched_hemisphere(n, "S4"), 0.03 if n >= 16 else None))
        cases.append((g.pinched_hemisphere(n, "S3"), 0.05 if n >= 16 else None))
    single(exe, a.work, cases, None)

    if a.markdown:
        with open(a.markdown, "w") as f:
            f.write("\n".join(lines) + "\n")
    print(f"\n{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
