#!/usr/bin/env python3
"""make_scenes.py - writes the scenes of the stability suite
(`splinecast bench --stability`, tests/test_stability.c) into this folder.

Each scene provokes one way a ray-patch method fails; README.md in this
folder is the suite's table (scene, file, camera, what it provokes), which
the bench and the tests read. The scenes are small and deterministic
(a fixed linear congruential generator, points printed with 17 digits), so
that running this again reproduces the checked-in files byte for byte:

    python3 examples/scenes/stability/make_scenes.py && git diff --stat

Only the standard library is used.
"""
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))


def num(x):
    """A coordinate as the readers parse it back exactly; -0 printed as 0."""
    x = float(x)
    return "0" if x == 0 else "%.17g" % x


class Rand:
    """The C library's classic LCG, so the sequence does not depend on
    Python's random module across versions."""

    def __init__(self, seed):
        self.state = seed

    def next(self):
        self.state = (self.state * 1103515245 + 12345) % (1 << 32)
        return ((self.state >> 16) % 10000) / 10000.0


def bpt(patches):
    """A .bpt file: patches as (du, dv, points u fastest)."""
    out = ["%d" % len(patches)]
    for du, dv, pts in patches:
        out.append("%d %d" % (du, dv))
        out += ["%s %s %s" % tuple(num(c) for c in p) for p in pts]
    return "\n".join(out) + "\n"


def grid(du, dv, f):
    """(du+1)(dv+1) control points f(i, j), u fastest."""
    return [f(i, j) for j in range(dv + 1) for i in range(du + 1)]


def blossom_points(coeffs, n):
    """Bezier ordinates over u in [0, 1] of the polynomial sum c_k s^k in
    s = 2u - 1 (degree <= n): ordinate m is the blossom at m arguments 1
    and n - m arguments -1, and the blossom of s^k is the k-th elementary
    symmetric function of the arguments over C(n, k)."""
    result = []
    for m in range(n + 1):
        args = [1.0] * m + [-1.0] * (n - m)
        e = [1.0] + [0.0] * n
        for a in args:
            for k in range(n, 0, -1):
                e[k] += a * e[k - 1]
        result.append(sum(c * e[k] / math.comb(n, k) for k, c in enumerate(coeffs)))
    return result


# ---- untrimmed Bezier patches (.bpt) -------------------------------------


def grazing():
    """A gently waving sheet of 2 x 2 bicubic patches over [-2, 2]^2,
    about 0.1 high: seen from 3 degrees above its plane."""
    patches = []
    for pj in range(2):
        for pi in range(2):
            def f(i, j, pi=pi, pj=pj):
                x = -2 + 2 * pi + 2 * i / 3
                y = -2 + 2 * pj + 2 * j / 3
                return (x, y, 0.08 * math.sin(2.1 * x) * math.cos(1.7 * y))
            patches.append((3, 3, grid(3, 3, f)))
    return bpt(patches)


def silhouette():
    """Three rows of bicubic hills (a sine surface 0.5 high): from the side
    every hilltop is a silhouette in front of the next one."""
    patches = []
    for pj in range(3):
        for pi in range(3):
            def f(i, j, pi=pi, pj=pj):
                x = -1.5 + pi + i / 3
                y = -1.5 + pj + j / 3
                return (x, y, 0.5 * math.sin(math.pi * x) * math.sin(math.pi * y))
            patches.append((3, 3, grid(3, 3, f)))
    return bpt(patches)


def apex():
    """Four bicubic patches of a pointed dome whose upper edge collapses
    to one point (a polynomial pole): the partial along that edge vanishes."""
    patches = []
    for q in range(4):
        a0 = q * math.pi / 2

        def f(i, j, a0=a0):
            a = a0 + (math.pi / 2) * i / 3
            r = 1.0 - j / 3
            z = 1.2 * (1 - (1 - j / 3) ** 2)
            # A square-ish ring (not a circle): corners at i = 0, 3.
            return (r * math.cos(a), r * math.sin(a), z)
        patches.append((3, 3, grid(3, 3, f)))
    return bpt(patches)


def cusp():
    """x = 0.8 s^2, z = 0.5 s^3 in u (s = 2u - 1) swept along y with a bend:
    a cuspidal edge at s = 0, where the partial in u vanishes on a whole
    line of the patch and both sheets meet tangentially."""
    xs = blossom_points([0, 0, 0.8], 3)
    zs = blossom_points([0, 0, 0, 0.5], 3)

    def f(i, j):
        y = -1 + 2 * j / 3
        return (xs[i] + 0.2 * y * y, y, zs[i] + 0.1 * y)
    return bpt([(3, 3, grid(3, 3, f))])


def fold():
    """A bicubic patch folded twice along u (an S in x): a ray from above
    crosses it up to three times, and the two fold lines are silhouettes
    inside the patch."""
    xs = [-1.0, 2.2, -2.2, 1.0]
    zs = [0.0, 0.25, 0.5, 0.75]

    def f(i, j):
        y = -1 + 2 * j / 3
        return (xs[i] + 0.3 * y, y, zs[i] + 0.15 * y * y)
    return bpt([(3, 3, grid(3, 3, f))])


def high_degree():
    """Random heights on a 9 x 9 and a 12 x 12 patch side by side: the
    unrolled program's highest default degree, and a generic one above it."""
    rnd = Rand(20240601)
    patches = []
    for x0, d in ((-2.1, 9), (0.1, 12)):
        def f(i, j, x0=x0, d=d):
            return (x0 + 2 * i / d, -1 + 2 * j / d, 0.9 * (rnd.next() - 0.5))
        patches.append((d, d, grid(d, d, f)))
    return bpt(patches)


def bump(scale, offset):
    """Two bicubic bumps over [-1, 1] x [-1, 1] (one upright, one upside
    down beside it), scaled and moved."""
    patches = []
    for k, sign in enumerate((1, -1)):
        def f(i, j, k=k, sign=sign):
            inner = 0 < i < 3 and 0 < j < 3
            p = (-1 + 2 * i / 3 + 2.2 * k, -1 + 2 * j / 3, sign * (0.8 if inner else 0.1 * i))
            return tuple(offset[c] + scale * p[c] for c in range(3))
        patches.append((3, 3, grid(3, 3, f)))
    return bpt(patches)


def coincident():
    """A waving bicubic sheet and a copy of it tilted by 1/20 about the y
    axis: they cross along x = 0 at 3 degrees, so that near that line the two
    are closer than a pixel and farther out several pixels apart; a ray must
    stop at the nearer one."""
    patches = []
    for tilt in (0.0, 0.05):
        def f(i, j, tilt=tilt):
            x = -1 + 2 * i / 3
            y = -1 + 2 * j / 3
            return (x, y, 0.2 * math.sin(2 * x) * math.cos(1.5 * y) + tilt * x)
        patches.append((3, 3, grid(3, 3, f)))
    return bpt(patches)


# ---- OBJ free-form --------------------------------------------------------


def obj_surface(kind, du, dv, nu, nv, pts, parm_u, parm_v, trims=""):
    """One surf body: pts are (x, y, z) or (x, y, z, w), u fastest; vertex
    references are negative (relative), so bodies can be concatenated."""
    n = nu * nv
    out = ["v " + " ".join(num(c) for c in p) for p in pts]
    out.append("cstype " + kind)
    out.append("deg %d %d" % (du, dv))
    if kind.endswith("bspline"):
        lo_u, hi_u, lo_v, hi_v = parm_u[du], parm_u[-du - 1], parm_v[dv], parm_v[-dv - 1]
    else:
        lo_u, hi_u, lo_v, hi_v = parm_u[0], parm_u[-1], parm_v[0], parm_v[-1]
    refs = " ".join(str(k - n) for k in range(n))
    out.append("surf %s %s %s %s %s" % (num(lo_u), num(hi_u), num(lo_v), num(hi_v), refs))
    out.append("parm u " + " ".join(num(k) for k in parm_u))
    out.append("parm v " + " ".join(num(k) for k in parm_v))
    if trims:
        out.append(trims)
    out.append("end")
    return "\n".join(out) + "\n"


def poles():
    """The unit sphere as a rational biquadratic surface of 4 x 2 Bezier
    patches; its first and last rows of control points collapse to the
    poles."""
    h = math.sqrt(0.5)
    circle = [(1, 0, 1), (1, 1, h), (0, 1, 1), (-1, 1, h), (-1, 0, 1), (-1, -1, h),
              (0, -1, 1), (1, -1, h), (1, 0, 1)]
    meridian = [(0, -1, 1), (1, -1, h), (1, 0, 1), (1, 1, h), (0, 1, 1)]
    pts = [(cx * r, cy * r, z, cw * mw) for (r, z, mw) in meridian for (cx, cy, cw) in circle]
    return obj_surface("rat bezier", 2, 2, 9, 5, pts, [0, 1, 2, 3, 4], [0, 1, 2])


def knots():
    """One bicubic B-spline surface of 20 x 20 knot spans with uneven knots
    (a few spans 1/1000 of the others): 400 Bezier patches, some of them
    slivers in parameter space."""
    rnd = Rand(7)
    spans = 20
    widths = [0.001 if k in (5, 6, 13) else 0.5 + rnd.next() for k in range(spans)]
    inner = [0.0]
    for w in widths:
        inner.append(inner[-1] + w)
    total = inner[-1]
    inner = [k / total for k in inner]
    knot = [0.0] * 3 + inner + [1.0] * 3
    n = spans + 3
    pts = []
    for j in range(n):
        for i in range(n):
            x = -1 + 2 * i / (n - 1)
            y = -1 + 2 * j / (n - 1)
            pts.append((x, y, 0.25 * math.sin(3 * x) * math.cos(2.5 * y) + 0.04 * rnd.next()))
    return obj_surface("bspline", 3, 3, n, n, pts, knot, knot)


def polygon_loop(points):
    """A closed polygon as one degree-1 curv2; returns (vp lines, curv2 and
    its parm, the trim statement's parameter range)."""
    m = len(points)
    vps = ["vp %s %s" % (num(u), num(v)) for u, v in points + [points[0]]]
    refs = " ".join(str(k - (m + 1)) for k in range(m + 1))
    knots_ = [0] + list(range(m + 1)) + [m]
    curve = "cstype bspline\ndeg 1\ncurv2 %s\nparm u %s\nend" % (
        refs, " ".join(str(k) for k in knots_))
    return "\n".join(vps) + "\n" + curve + "\n", m


def trim_centres():
    """A flat bilinear square over [-1, 1]^2 (u, v = (x + 1)/2, (y + 1)/2)
    trimmed by a quadrilateral whose two edges through the middle have
    slopes 1 and 3: seen straight down with the view centred on the middle
    and an even square image, both lines pass through pixel centres at every
    size (pixel centres are odd multiples of half a pixel from the middle)."""
    loop, m = polygon_loop([(0.5, 0.5), (0.5 + 0.5 / 3, 1.0), (0.0, 1.0), (0.0, 0.0)])
    pts = grid(1, 1, lambda i, j: (-1 + 2 * i, -1 + 2 * j, 0))
    return loop + obj_surface("bezier", 1, 1, 2, 2, pts, [0, 1], [0, 1],
                              "trim 0 %d 1" % m)


def sliver():
    """A half-pipe (a cubic arc in u swept along a bent v) trimmed to a
    thin tapering tail: a lens between two cubic trim curves that runs
    along the pipe and narrows from 0.02 of the domain to nothing at its
    ends, much of it below a pixel wide; a body square joins it, as the
    thin tail of a trimmed part joins the part."""
    xs = [-1.0, -1.0, 1.0, 1.0]
    zs = [0.0, 1.3, 1.3, 0.0]

    def f(i, j):
        y = -2 + 4 * j / 3
        return (xs[i] + 0.4 * math.sin(y), y, zs[i] - 0.1 * y)
    pts = grid(3, 3, f)
    # The loop, counter-clockwise in (u, v): the body square, then out along
    # the tail's lower edge to its tip and back along the upper one.
    vps = [(0.10, 0.05), (0.30, 0.05), (0.30, 0.15),
           (0.45, 0.40), (0.60, 0.70), (0.88, 0.97),
           (0.595, 0.715), (0.44, 0.42), (0.26, 0.25), (0.10, 0.25)]
    lines = ["vp %s %s" % (num(u), num(v)) for u, v in vps + [vps[0]]]
    # Degree 1 for the square's sides, degree 3 for the two tail edges:
    # one B-spline curve of degree 3 would round the corners, so the loop
    # is three curves chained.
    body = "cstype bspline\ndeg 1\ncurv2 -11 -10 -9\nparm u 0 0 1 2 2\nend\n"
    tail = ("cstype bezier\ndeg 3\ncurv2 -9 -8 -7 -6 -5 -4 -3\nparm u 0 1 2\nend\n")
    back = "cstype bspline\ndeg 1\ncurv2 -3 -2 -1\nparm u 0 0 1 2 2\nend\n"
    curves = "\n".join(lines) + "\n" + body + tail + back
    return curves + obj_surface("bezier", 3, 3, 4, 4, pts, [0, 1], [0, 1],
                                "trim 0 2 1 0 2 2 0 2 3")


SCENES = [
    ("grazing.bpt", grazing),
    ("silhouette.bpt", silhouette),
    ("poles.obj", poles),
    ("apex.bpt", apex),
    ("cusp.bpt", cusp),
    ("fold.bpt", fold),
    ("high_degree.bpt", high_degree),
    ("far.bpt", lambda: bump(1.0, (10000.0, -20000.0, 5000.0))),
    ("tiny.bpt", lambda: bump(1e-4, (0.0, 0.0, 0.0))),
    ("coincident.bpt", coincident),
    ("knots.obj", knots),
    ("trim_centres.obj", trim_centres),
    ("sliver.obj", sliver),
]

if __name__ == "__main__":
    for name, make in SCENES:
        text = make()
        if name.endswith(".obj"):
            doc = make.__doc__ if make.__doc__ else ""
            text = "".join("# " + l.strip() + "\n" for l in doc.strip().splitlines()) + \
                "# (examples/scenes/stability/make_scenes.py)\n" + text
        with open(os.path.join(HERE, name), "w") as f:
            f.write(text)
