"""Exact answers for the stress-test structures (pure Python, no numpy).

A statically determinate chain fixed at its base (a cantilever of segments:
Euler-Bernoulli beam elements and contact joints) under a load at its free end
has the closed form used here: the resultant at the end of segment s is
F_s = F, M_s = M + (r_tip - r_s) x F; the segment deforms by
[d; theta] = C_s [F_s; M_s] (C_s its flexibility, in global axes), which moves
the tip by d + theta x (r_tip - r_s) and turns it by theta.  Summing over the
segments gives the tip displacement exactly (Euler-Bernoulli elements with
nodes at the load points are exact, so the discrete answer is this too).
"""
import math


def sub(a, b):
    return [a[i] - b[i] for i in range(3)]


def add(a, b):
    return [a[i] + b[i] for i in range(3)]


def scale(s, a):
    return [s * x for x in a]


def dot(a, b):
    return sum(a[i] * b[i] for i in range(3))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(a):
    n = math.sqrt(dot(a, a))
    return [x / n for x in a]


def to_local(axes, v):
    return [dot(e, v) for e in axes]


def to_global(axes, v):
    return [sum(axes[k][i] * v[k] for k in range(3)) for i in range(3)]


def beam_axes(x1, x2, v=None):
    """Local axes of a beam (deck.md section 2): x from n1 to n2, y in the plane of
    x and v (default global Z, global X for a beam parallel to Z), z = x cross y."""
    ex = unit(sub(x2, x1))
    if v is None:
        v = [0.0, 0.0, 1.0]
        if abs(abs(ex[2]) - 1.0) < 1e-12:
            v = [1.0, 0.0, 0.0]
    ey = unit(sub(v, scale(dot(v, ex), ex)))
    return [ex, ey, cross(ex, ey)]


def frame_axes(a, b):
    """*ORIENTATION: local 1 along a, 2 in the a-b plane, 3 = 1 x 2."""
    e1 = unit(a)
    e2 = unit(sub(b, scale(dot(b, e1), e1)))
    return [e1, e2, cross(e1, e2)]


def beam_segment(x1, x2, e, nu, a, iy, iz, j, v=None, shear=None):
    """Flexibility of a cantilever beam element (fixed at x1): returns a function
    (F, M) at x2 -> (d, theta) of x2 relative to x1, global axes. shear: the
    transverse shear stiffnesses (Ky, Kz) of a Timoshenko beam (None: Euler-Bernoulli)."""
    axes = beam_axes(x1, x2, v)
    length = math.sqrt(dot(sub(x2, x1), sub(x2, x1)))
    g = e / (2.0 * (1.0 + nu))
    cy, cz = (0.0, 0.0) if shear is None else (1.0 / shear[0], 1.0 / shear[1])

    def flex(f, m):
        fl, ml = to_local(axes, f), to_local(axes, m)
        d = [fl[0] * length / (e * a),
             fl[1] * length**3 / (3 * e * iz) + ml[2] * length**2 / (2 * e * iz) + fl[1] * length * cy,
             fl[2] * length**3 / (3 * e * iy) - ml[1] * length**2 / (2 * e * iy) + fl[2] * length * cz]
        t = [ml[0] * length / (g * j),
             -fl[2] * length**2 / (2 * e * iy) + ml[1] * length / (e * iy),
             fl[1] * length**2 / (2 * e * iz) + ml[2] * length / (e * iz)]
        return to_global(axes, d), to_global(axes, t)
    return x2, flex


def joint_segment(x, gt, gr, axes=None):
    """Flexibility of a contact joint at x: springs gt (3 translations) and gr
    (3 rotations) in the frame axes; a value None is RIGID; 0 is a mechanism."""
    if axes is None:
        axes = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]

    def comp(g):
        if g is None:
            return 0.0
        if g == 0.0:
            raise ZeroDivisionError('g = 0: mechanism')
        return 1.0 / g

    def flex(f, m):
        fl, ml = to_local(axes, f), to_local(axes, m)
        d = [fl[k] * comp(gt[k]) for k in range(3)]
        t = [ml[k] * comp(gr[k]) for k in range(3)]
        return to_global(axes, d), to_global(axes, t)
    return x, flex


def chain_tip(segments, r_tip, f, m):
    """Tip translation and rotation of a chain of segments fixed at its base."""
    u, th = [0.0] * 3, [0.0] * 3
    for r_s, flex in segments:
        arm = sub(r_tip, r_s)
        d, t = flex(f, add(m, cross(arm, f)))
        u = add(u, add(d, cross(t, arm)))
        th = add(th, t)
    return u + th
