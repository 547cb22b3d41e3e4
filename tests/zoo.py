"""A mechanism zoo: seeded random mechanisms of every kind the contract accepts (FORMAT.md section 1).

``zoo(seed, count)`` returns ``count`` :class:`Specimen` s, cycling through the kinds of
:data:`KINDS` (so every kind appears in every run), each a dict for ``velpoly.load``.

Every specimen is built **pose first**: random link lengths and angles give the positions of
the drawn pose (a dyad's free pin by intersecting its two circles, on a random side), and the
file is written from those positions, as coordinates or as the constructions a textbook file
would use (two circles with ``near``, ``from``/``along``). So every specimen assembles at its
drawn pose by construction; its lengths and paths are what the positions make them, and its
mobility is 1 by its structure. Draws whose drawn pose is close to a toggle (a dyad's
transmission sine below ``MIN_SINE``) or whose points nearly coincide are drawn again, so
that the drawn pose is regular; the other driver angles a specimen asks for may lie beyond a
toggle (a rocker's limit), which ``velpoly.solve`` must then report as exit 3, not solve.

Finally the whole drawing is turned by a random angle, moved and scaled (lengths from 0.01
to 100 units), so that nothing depends on the frame lying along +x.
"""
from __future__ import annotations

import copy
import math
from dataclasses import dataclass, field, replace

import numpy as np

MIN_SINE = 0.2        # smallest transmission sine of a dyad at the drawn pose
MIN_GAP = 0.03        # smallest distance between two points, in units of the drawing's size


@dataclass(frozen=True)
class Specimen:
    """One generated mechanism: ``kind`` (a key of KINDS, with its variant), the dict for
    ``velpoly.load`` and the driver angle offsets (degrees from the drawn pose; None: the drawn
    pose itself; a slider driver has only the drawn pose)."""

    kind: str
    mech: dict
    offsets: tuple
    drawn: object = field(default=None, compare=False, repr=False)   # velpoly.solve at the drawn pose


class Redraw(Exception):
    """This draw is degenerate (no assembly, a near toggle, coincident points): draw again."""


# -- plane geometry on the drawn pose ------------------------------------------------------------------
def pol(p, r, deg):
    t = math.radians(deg)
    return (p[0] + r * math.cos(t), p[1] + r * math.sin(t))


def dist(p, q):
    return math.hypot(q[0] - p[0], q[1] - p[1])


def ang(p, q):
    """Direction from p to q, degrees."""
    return math.degrees(math.atan2(q[1] - p[1], q[0] - p[0]))


def circles(p, r1, q, r2, side):
    """Intersection of circle (p, r1) and circle (q, r2) on ``side`` (+1 left of p->q, -1 right)."""
    d = dist(p, q)
    if d == 0 or d > r1 + r2 or d < abs(r1 - r2):
        raise Redraw
    a = (r1 * r1 - r2 * r2 + d * d) / (2 * d)
    h = math.sqrt(max(r1 * r1 - a * a, 0.0))
    ux, uy = (q[0] - p[0]) / d, (q[1] - p[1]) / d
    m = (p[0] + a * ux, p[1] + a * uy)
    x = (m[0] - side * h * uy, m[1] + side * h * ux)
    need(transmission(p, x, q) >= MIN_SINE)   # the dyad's angle at its free pin: far from a toggle
    return x


def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


def transmission(p, x, q):
    """|sin| of the angle p-x-q (a dyad's pins p and q, its middle pin x)."""
    u, v = (p[0] - x[0], p[1] - x[1]), (q[0] - x[0], q[1] - x[1])
    return abs(_cross(u, v)) / (math.hypot(*u) * math.hypot(*v))


def need(ok):
    if not ok:
        raise Redraw


def line_circle(c, r, p, deg, near):
    """Where the line through p at deg meets the circle (c, r), nearest to ``near``."""
    t = math.radians(deg)
    d = (math.cos(t), math.sin(t))
    f = (p[0] - c[0], p[1] - c[1])
    b = f[0] * d[0] + f[1] * d[1]
    disc = b * b - (f[0] ** 2 + f[1] ** 2 - r * r)
    if disc <= 0:
        raise Redraw
    s = math.sqrt(disc)
    xs = [(p[0] + (-b + k) * d[0], p[1] + (-b + k) * d[1]) for k in (s, -s)]
    return min(xs, key=lambda x: dist(x, near))


# -- the file ------------------------------------------------------------------------------------------
class Draft:
    """A mechanism being written: points (positions in the drawn pose), links, joints, driver."""

    def __init__(self, rng, kind):
        self.rng, self.kind = rng, kind
        self.pos = {}          # name -> (x, y)
        self.spec = {}         # name -> how the file writes it (None: as coordinates)
        self.links = {}
        self.sliders, self.slots, self.contacts = [], [], []
        self.driver = None
        self.offsets = (None,)

    def point(self, name, xy, spec=None):
        self.pos[name] = (float(xy[0]), float(xy[1]))
        self.spec[name] = spec
        return self.pos[name]

    def link(self, name, *points, frame=False):
        self.links[str(name)] = {"points": list(points), **({"frame": True} if frame else {})}

    def crank_driver(self, link, far=False):
        """A crank driver; the specimen is solved at its drawn pose, a few degrees away and, where
        ``far`` (mechanisms that re-assemble by dyads, in closed form), anywhere on the turn."""
        rng = self.rng
        self.driver = {"link": str(link), "omega": float(rng.choice([-1, 1]) * rng.uniform(0.5, 30)),
                       "alpha": float(rng.uniform(-50, 50)) if rng.random() < 0.7 else 0.0}
        self.offsets = (None, float(rng.uniform(1.5, 5) * rng.choice([-1, 1])))
        if far:
            self.offsets += (float(rng.uniform(30, 330)),)

    def slider_driver(self, point):
        rng = self.rng
        self.driver = {"slider": point, "speed": float(rng.choice([-1, 1]) * rng.uniform(0.1, 5)),
                       "accel": float(rng.uniform(-20, 20)) if rng.random() < 0.7 else 0.0}
        self.offsets = (None,)

    def finish(self):
        """Check the drawing (no near-coincident points), then turn, move and scale it."""
        rng = self.rng
        xy = np.array(list(self.pos.values()))
        size = float(np.ptp(xy, axis=0).max())
        gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
        need(gaps[np.triu_indices(len(xy), 1)].min() >= MIN_GAP * size)
        phi = float(rng.uniform(-180, 180))
        k = float(10 ** rng.uniform(-2, 2)) / size
        c, s = math.cos(math.radians(phi)), math.sin(math.radians(phi))
        shift = rng.uniform(-1, 1, 2) * 50 * k * size

        def tr(p):
            return [k * (c * p[0] - s * p[1]) + float(shift[0]), k * (s * p[0] + c * p[1]) + float(shift[1])]

        points = {}
        for name, p in self.pos.items():
            sp = self.spec[name]
            if sp is None:
                points[name] = tr(p)
            elif sp[0] == "circles":           # ("circles", P, Q): the two circles, and near the point
                _, a, b = sp
                points[name] = {"circles": [[a, k * dist(self.pos[a], p)], [b, k * dist(self.pos[b], p)]],
                                "near": tr(p)}
            elif sp[0] == "polar":             # ("polar", P): from P, length, absolute angle
                q = self.pos[sp[1]]
                points[name] = {"from": sp[1], "length": k * dist(q, p), "angle": ang(q, p) + phi}
            elif sp[0] == "along":             # ("along", P, Q, R): from P, along Q->R, turned
                _, a, q, r = sp
                turn = ang(self.pos[a], p) - ang(self.pos[q], self.pos[r])
                points[name] = {"from": a, "length": k * dist(self.pos[a], p), "along": [q, r],
                                "turn": (turn + 180) % 360 - 180}
            else:
                raise AssertionError(sp)
        mech = {"format": 1, "title": f"zoo: {self.kind}", "units": "mm", "points": points,
                "links": self.links, "driver": dict(self.driver)}
        if self.sliders:
            mech["sliders"] = [{**sl, **({"angle": sl["angle"] + phi} if "angle" in sl else {})}
                               for sl in self.sliders]
        if self.slots:
            mech["slots"] = [{**sl, **({"angle": sl["angle"] + phi} if "angle" in sl else {})}
                             for sl in self.slots]
        if self.contacts:   # a contact given by its normal: the normal turns with the drawing
            mech["contacts"] = [{**ct, **({"normal": self.normal + phi} if "normal" in ct else {}),
                                 **({"slip": ct["slip"] * k * size} if "slip" in ct else {})}
                                for ct in self.contacts]
        if "slider" in mech["driver"]:
            mech["driver"]["speed"] *= k * size
            mech["driver"]["accel"] *= k * size
        return Specimen(self.kind, mech, self.offsets)


def _any(rng, items):
    return items[int(rng.integers(len(items)))]


def _side(rng):
    return float(rng.choice([-1.0, 1.0]))


# -- four-bars -----------------------------------------------------------------------------------------
GRASHOF = ("crank-rocker", "double-crank", "double-rocker", "change-point", "triple-rocker")


def fourbar_lengths(rng, cls):
    """(frame, crank, coupler, rocker) of a Grashof class: which link is the shortest fixes it."""
    s, l = rng.uniform(0.6, 1.0), rng.uniform(2.4, 3.2)
    if cls == "triple-rocker":                       # s + l > p + q
        p = rng.uniform(1.3, 2.0)
        need(s + l - p - 0.15 > s + 0.05)
        q = rng.uniform(s + 0.05, s + l - p - 0.15)
        need(s + l > p + q and max(p, q) <= l)
        ls = [s, l, p, q]
        rng.shuffle(ls)
        return tuple(ls)
    p = rng.uniform(1.4, 2.2)
    q = s + l - p if cls == "change-point" else rng.uniform(s + l - p + 0.2, s + l - p + 1.2)
    need(q >= s and l >= max(p, q))
    rest = [l, p, q]
    rng.shuffle(rest)
    where = {"crank-rocker": 1, "double-crank": 0, "double-rocker": 2, "change-point": int(rng.integers(4))}[cls]
    ls = rest[:where] + [s] + rest[where:]
    return tuple(ls)


def fourbar_pose(rng, cls, d: Draft, couplers=True):
    """O2, O4 on the frame (link 1), crank 2 (O2 A), coupler 3 (A B, maybe E), rocker 4 (O4 B)."""
    f, a, b, c = fourbar_lengths(rng, cls)
    for _ in range(40):
        theta = rng.uniform(-180, 180)
        try:
            O2, O4 = (0.0, 0.0), (f, 0.0)
            A = pol(O2, a, theta)
            B = circles(A, b, O4, c, _side(rng))
            break
        except Redraw:
            continue
    else:
        raise Redraw
    d.point("O2", O2)
    d.point("O4", O4)
    d.point("A", A, ("polar", "O2") if rng.random() < 0.5 else None)
    d.point("B", B, ("circles", "A", "O4") if rng.random() < 0.5 else None)
    pts3 = ["A", "B"]
    if couplers and rng.random() < 0.6:
        E = pol(A, rng.uniform(0.3, 1.2) * b, ang(A, B) + rng.uniform(-120, 120))
        d.point("E", E, ("along", "A", "A", "B") if rng.random() < 0.5 else None)
        pts3.append("E")
    d.link(1, "O2", "O4", frame=True)
    d.link(2, "O2", "A")
    d.link(3, *pts3)
    d.link(4, "O4", "B")
    return dict(O2=O2, O4=O4, A=A, B=B, f=f, a=a, b=b, c=c)


def gen_fourbar(rng, variant=None):
    cls = variant or _any(rng, GRASHOF)
    d = Draft(rng, f"four-bar {cls}")
    fourbar_pose(rng, cls, d)
    driver = "2" if rng.random() < 0.75 else "4"
    d.crank_driver(driver, far=True)
    return d.finish()


# -- slider-cranks ---------------------------------------------------------------------------------------
def gen_slider_crank(rng, variant=None):
    """Crank 2 (O2 A), rod 3 (A B), block 4 on a frame path offset e (0: through the pivot)."""
    variant = variant or _any(rng, SLIDER_CRANKS)
    d = Draft(rng, f"slider-crank {variant}")
    r = rng.uniform(0.5, 1.0)
    l = rng.uniform(1.8, 4.0)
    e = 0.0 if "through" in variant else rng.uniform(-0.7, 0.7) * r
    theta = rng.uniform(-180, 180)
    O2 = d.point("O2", (0.0, 0.0))
    A = d.point("A", pol(O2, r, theta))
    if "curved" in variant:   # the block in a circular slot of the frame about K
        B = d.point("B", pol(A, l, rng.uniform(-60, 60)))
        K = d.point("K", pol(B, rng.uniform(1.0, 3.0) * l, ang(A, B) + _side(rng) * rng.uniform(50, 130)))
        need(transmission(A, B, pol(B, 1.0, ang(K, B) + 90)) >= MIN_SINE)
        d.link(1, "O2", "K", frame=True)
        d.link(2, "O2", "A")
        d.link(3, "A", "B")
        d.link(4, "B")
        d.sliders.append({"block": "4", "guide": "1", "point": "B", "centre": "K"})
        need(transmission(O2, A, B) >= 0.1)
        if "slider" in variant:
            d.slider_driver("B")
        else:
            d.crank_driver(2)
        return d.finish()
    B = line_circle(A, l, (0.0, e), 0.0, (A[0] + _side(rng) * 2 * l, e))
    need(transmission(A, B, (B[0] + 1, B[1])) >= MIN_SINE)
    d.point("B", B)
    if "through" in variant:
        need(transmission(O2, A, B) >= 0.05)   # off the dead centre
    d.link(1, "O2", frame=True)
    d.link(2, "O2", "A")
    d.link(3, "A", "B")
    d.link(4, "B")
    d.sliders.append({"block": "4", "guide": "1", "point": "B", "angle": float(rng.choice([0.0, 180.0]))})
    need(transmission(O2, A, B) >= 0.1)
    if "slider" in variant:
        d.slider_driver("B")
    else:
        d.crank_driver(2, far=True)
    return d.finish()


SLIDER_CRANKS = ("offset crank", "through crank", "offset slider", "through slider", "curved crank", "curved slider")
INVERTED = ("curved crank", "curved slider", "through both crank", "through block slider", "through both slider", "through guide-lists slider",
            "offset block slider", "offset both crank", "offset both slider", "second-pin slider",
            "second-pin crank", "swinging-block slider", "swinging-block crank", "rocker slider")


def gen_inverted(rng, variant=None):
    """A block on a turning guide (inverted slider-crank): block 3 pinned to the crank 2 at A,
    sliding on the guide 4 about O4, the path through O4 or offset from it; the slider point listed
    on the block, or on block and guide; the block pinned to the crank at a second point; or the
    block pivoted on the frame and the guide pinned to the crank (swinging block). Crank or
    slider driven."""
    variant = variant or _any(rng, INVERTED)
    d = Draft(rng, f"inverted slider-crank {variant}")
    r = rng.uniform(0.5, 1.5)
    dd = rng.uniform(1.0, 3.0) * _any(rng, (1.0, 0.5)) if "rocker" not in variant else rng.uniform(1.6, 3.0)
    if "rocker" in variant:
        r = rng.uniform(0.8, 1.3) * dd            # a rocker, not a crank: its swing is limited
    theta = rng.uniform(-180, 180)
    O2, O4 = d.point("O2", (0.0, 0.0)), d.point("O4", (dd, 0.0))
    A = pol(O2, r, theta)
    need(dist(A, O4) > 0.2 * dd)
    offset = 0.0 if "through" in variant else rng.uniform(15, 50) * _side(rng)
    path = ang(O4, A) + offset
    d.link(1, "O2", "O4", frame=True)
    if "curved" in variant:
        # the block 3 (pinned to crank 2 at A) in a circular slot of the rocker 4 about its point K
        d.point("A", A)
        K = d.point("K", pol(A, rng.uniform(0.5, 1.5) * dist(A, O4), ang(A, O4) + rng.uniform(30, 150) * _side(rng)))
        d.link(2, "O2", "A")
        d.link(3, "A")
        d.link(4, "O4", "K", *(["A"] if rng.random() < 0.5 else []))
        d.sliders.append({"block": "3", "guide": "4", "point": "A", "centre": "K"})
        need(transmission(O2, A, pol(A, 1.0, ang(K, A) + 90)) >= MIN_SINE)
        drive_point = "A"
    elif "swinging-block" in variant:
        # the block 3 turns about O4 on the frame, the guide 4 (pinned to crank 2 at A) slides in it
        d.point("A", A)
        path = ang(A, O4) + offset
        C = d.point("C", pol(A, rng.uniform(1.2, 2.0) * dist(A, O4), path if not offset else path + 20))
        d.link(2, "O2", "A")
        d.link(3, "O4")
        d.link(4, "A", "C", *(["O4"] if rng.random() < 0.5 else []))
        d.sliders.append({"block": "3", "guide": "4", "point": "O4", "angle": path})
        need(transmission(O2, A, O4) >= 0.15 if not offset else True)
        drive_point = "O4"
    else:
        d.point("A", A, ("polar", "O2") if rng.random() < 0.5 else None)
        C = d.point("C", pol(O4, dist(O4, A) * rng.uniform(1.3, 2.0), ang(O4, A) + rng.uniform(-30, 30)))
        guide = ["O4", "C"]
        if "second-pin" in variant:
            # the block is pinned to the crank at A and driven at its point F, further along the path
            F = d.point("F", pol(A, rng.uniform(0.2, 0.5) * r * _side(rng), path))
            d.link(2, "O2", "A")
            d.link(3, "A", "F")
            if rng.random() < 0.5:
                guide.append("F")
            drive_point = "F"
        else:
            d.link(2, "O2", "A")
            d.link(3, "A")
            if "both" in variant or "guide-lists" in variant:
                guide.append("A")
            drive_point = "A"
        d.link(4, *guide)
        d.sliders.append({"block": "3", "guide": "4", "point": drive_point, "angle": path})
        # regular: the crank's velocity at A is not along the guide's normal direction only
        need(transmission(O2, A, (A[0] + math.cos(math.radians(path)), A[1] + math.sin(math.radians(path))))
             >= 0.15)
    if "slider" in variant:
        d.slider_driver(drive_point)
    else:
        d.crank_driver(2)
    return d.finish()


# -- six-bars and eight-bars -------------------------------------------------------------------------------
def _dyad(rng, d: Draft, p_name, q_name, x_name, spread=(0.8, 2.0)):
    """A dyad's free pin X between the known points P and Q, lengths from random ones."""
    P, Q = d.pos[p_name], d.pos[q_name]
    L = dist(P, Q)
    need(L > 0)
    r1, r2 = rng.uniform(*spread) * L, rng.uniform(*spread) * L
    X = circles(P, r1, Q, r2, _side(rng))
    d.point(x_name, X, ("circles", p_name, q_name) if rng.random() < 0.5 else None)
    return X


def _on_link(rng, d: Draft, base, toward, name, scale=(0.4, 1.1), spread=100):
    P, Q = d.pos[base], d.pos[toward]
    X = pol(P, rng.uniform(*scale) * dist(P, Q), ang(P, Q) + rng.uniform(-spread, spread))
    d.point(name, X, ("along", base, base, toward) if rng.random() < 0.4 else None)
    return X


def _point_on(rng, d: Draft, link, base, toward, name):
    """A new point ``name`` of ``link``, placed about its points ``base`` and ``toward``."""
    _on_link(rng, d, base, toward, name)
    d.links[link]["points"].append(name)
    return name


def _add_dyad(rng, d: Draft, p, q, x, l1, l2):
    """Links l1 (p x) and l2 (q x): a dyad from the known points p and q to its new pin x."""
    _dyad(rng, d, p, q, x)
    d.link(l1, p, x)
    d.link(l2, q, x)


def _frame_pivot(rng, d: Draft, name, near):
    c = d.pos[near]
    size = max(dist(d.pos["O2"], d.pos["O4"]), 1.0)
    X = pol(c, rng.uniform(0.8, 2.0) * size, rng.uniform(-180, 180))
    d.point(name, X)
    d.links["1"]["points"].append(name)
    return name


SIXBARS = ("watt I", "watt II", "stephenson I", "stephenson III", "stephenson III by its binary",
           "stephenson III ternary-driven triad", "stephenson III ternary class IV",
           "floating guide crank", "floating guide slider", "floating guide lists the point slider",
           "slider on frame", "slider on coupler point", "quick-return crank", "quick-return slider",
           "quick-return ram")


# the six-bars made of a four-bar and a dyad: where the dyad's two ends are (link, placed about
# base and toward, name), None for a new pivot on the frame
DYADS = {
    "watt II": (("4", "O4", "B", "C"), None),                            # rocker 4 ternary
    "watt I": (("3", "A", "B", "E"), ("4", "O4", "B", "C")),             # coupler and rocker ternary, adjacent
    "stephenson I": (("2", "O2", "A", "C"), ("4", "O4", "B", "G")),      # crank and rocker ternary, not adjacent
    "stephenson III": (("3", "A", "B", "E"), None),                      # coupler ternary, dyad to the frame
    "stephenson III by its binary": (("3", "A", "B", "E"), None),
}


def gen_sixbar(rng, variant=None):
    variant = variant or _any(rng, SIXBARS)
    if variant.startswith("quick-return"):
        return gen_quick_return(rng, variant)
    if variant.startswith("stephenson III ternary"):
        return gen_stephenson_ternaries(rng, variant)
    if variant.startswith("floating guide"):
        return gen_floating_guide(rng, variant)
    d = Draft(rng, f"six-bar {variant}")
    cls = _any(rng, ("crank-rocker", "double-crank", "double-rocker", "triple-rocker"))
    fourbar_pose(rng, cls, d, couplers=False)
    driver = "2"
    if variant in DYADS:
        ends = [_point_on(rng, d, *where) if where else None for where in DYADS[variant]]
        q = ends[1] or _frame_pivot(rng, d, "O6", ends[0])
        _add_dyad(rng, d, ends[0], q, "D", 5, 6)
        if variant.endswith("binary"):
            driver = "6"
    else:                                # a rod from the rocker (or a coupler point) to a block on the frame
        src = _point_on(rng, d, *(("4", "O4", "B", "C") if variant == "slider on frame" else ("3", "A", "B", "E")))
        S = d.pos[src]
        L = max(dist(d.pos["O2"], d.pos["O4"]), 1.0) * rng.uniform(1.0, 2.0)
        path = rng.uniform(-180, 180)
        F = d.point("F", pol(S, L, path + rng.uniform(-60, 60)))
        need(transmission(S, F, pol(F, 1.0, path)) >= MIN_SINE)
        d.link(5, src, "F")
        d.link(6, "F")
        d.sliders.append({"block": "6", "guide": "1", "point": "F", "angle": path})
    d.crank_driver(driver)
    if rng.random() < 0.2 and "slider" in variant:
        d.slider_driver("F")
    return d.finish()


def gen_stephenson_ternaries(rng, variant):
    """Stephenson III drawn the other way: the ternary T1 (O1 P Q) about O1 on the frame, the
    ternary T2 (S U R) hung on the binaries P-S, Q-U and O4-R. Driven by T1 the rest is a triad (no
    dyad: an auxiliary point); driven by O4-R, two ternaries joined by two binaries (a class IV
    group: the trial solution)."""
    d = Draft(rng, f"six-bar {variant}")
    O1, O4 = d.point("O1", (0.0, 0.0)), d.point("O4", (rng.uniform(1.5, 2.5), rng.uniform(-0.3, 0.3)))
    P = d.point("P", pol(O1, rng.uniform(0.3, 0.6), rng.uniform(20, 80)))
    Q = d.point("Q", pol(O1, rng.uniform(0.3, 0.6), ang(O1, P) + rng.uniform(40, 100)))
    R = d.point("R", pol(O4, rng.uniform(0.5, 1.0), rng.uniform(60, 120)))
    S = d.point("S", pol(P, rng.uniform(0.6, 1.0), rng.uniform(40, 80)))
    U = d.point("U", pol(Q, rng.uniform(0.5, 1.0), rng.uniform(60, 120)))
    need(min(transmission(P, S, R), transmission(Q, U, R), transmission(O4, R, S)) >= MIN_SINE)
    d.link(0, "O1", "O4", frame=True)
    d.link(1, "O1", "P", "Q")
    d.link(2, "P", "S")
    d.link(3, "Q", "U")
    d.link(4, "O4", "R")
    d.link(5, "S", "U", "R")
    d.crank_driver(4 if variant.endswith("class IV") else 1)
    return d.finish()


def gen_floating_guide(rng, variant):
    """A block on a guide that no pivot holds: crank 2 (O2 A), block 3 at A sliding on the guide 4
    (B C), which hangs on the rockers 5 (O5 B) and 6 (O6 C). Driven by the crank or by the block
    along the guide (neither side of the driven slip then has a known image: an instant centre, an
    auxiliary point or a trial solution)."""
    d = Draft(rng, f"six-bar {variant}")
    O2 = d.point("O2", (0.0, 0.0))
    A = d.point("A", pol(O2, rng.uniform(0.6, 1.0), rng.uniform(-180, 180)))
    B = d.point("B", pol(A, rng.uniform(1.2, 2.0), rng.uniform(-30, 30)))
    C = d.point("C", pol(A, rng.uniform(1.0, 1.8), ang(A, B) + rng.uniform(40, 80)))
    d.point("O5", pol(B, rng.uniform(0.8, 1.5), rng.uniform(-150, -30)))
    d.point("O6", pol(C, rng.uniform(0.8, 1.5), rng.uniform(30, 150)))
    d.link(1, "O2", "O5", "O6", frame=True)
    d.link(2, "O2", "A")
    d.link(3, "A")
    d.link(4, "B", "C", *(["A"] if "lists" in variant else []))
    d.link(5, "O5", "B")
    d.link(6, "O6", "C")
    d.sliders.append({"block": "3", "guide": "4", "point": "A", "angle": ang(A, B) + rng.uniform(-25, 25)})
    if variant.endswith("slider"):
        d.slider_driver("A")
    else:
        d.crank_driver(2)
    return d.finish()


def gen_quick_return(rng, variant):
    """Whitworth / crank-shaper: crank 2 (O2 A), block 3 at A on the slotted lever 4 (O4 ... B),
    rod 5 (B D), ram 6 on a frame path. Driven by the crank, by the block along the lever, or by
    the ram."""
    d = Draft(rng, f"six-bar {variant}")
    r = rng.uniform(0.6, 1.2)
    O2 = d.point("O2", (0.0, 0.0))
    O4 = d.point("O4", (0.0, -rng.uniform(1.2, 2.5) * r))
    A = d.point("A", pol(O2, r, rng.uniform(-180, 180)))
    need(dist(A, O4) > 0.3 * r)
    B = d.point("B", pol(O4, rng.uniform(2.5, 4.0) * r, ang(O4, A)))
    h = O2[1] + rng.uniform(1.0, 2.5) * r
    D = line_circle(B, rng.uniform(1.5, 3.0) * r, (0.0, h), 0.0, (B[0] + _side(rng) * 3 * r, h))
    d.point("D", D)
    need(transmission(B, D, (D[0] + 1.0, D[1])) >= MIN_SINE)
    need(transmission(O2, A, O4) >= 0.1)
    d.link(1, "O2", "O4", frame=True)
    d.link(2, "O2", "A")
    d.link(3, "A")
    d.link(4, "O4", "B", *(["A"] if rng.random() < 0.5 else []))
    d.link(5, "B", "D")
    d.link(6, "D")
    d.sliders.append({"block": "3", "guide": "4", "point": "A", "angle": ang(O4, A)})
    d.sliders.append({"block": "6", "guide": "1", "point": "D", "angle": 0.0})
    if variant.endswith("crank"):
        d.crank_driver(2)
    else:
        d.slider_driver("A" if variant.endswith("slider") else "D")
    return d.finish()


def gen_eightbar(rng, variant=None):
    """A Watt II or Stephenson III six-bar with one more dyad to the frame (or to the crank)."""
    variant = variant or _any(rng, ("watt II + dyad", "stephenson III + dyad", "watt II + dyad to crank"))
    d = Draft(rng, f"eight-bar {variant}")
    fourbar_pose(rng, _any(rng, ("crank-rocker", "double-crank", "double-rocker")), d, couplers=False)
    first = _point_on(rng, d, *(("4", "O4", "B", "C") if variant.startswith("watt") else ("3", "A", "B", "E")))
    _add_dyad(rng, d, first, _frame_pivot(rng, d, "O6", first), "D", 5, 6)
    h = _point_on(rng, d, "6", "O6", "D", "H")
    q = _point_on(rng, d, "2", "O2", "A", "K") if variant.endswith("crank") else _frame_pivot(rng, d, "O8", h)
    _add_dyad(rng, d, h, q, "J", 7, 8)
    d.crank_driver(_any(rng, ("2", "2", "6")) if not variant.endswith("crank") else "2")
    return d.finish()


# -- pins in slots ----------------------------------------------------------------------------------------
def gen_slot(rng, variant=None):
    """A crank's pin A in a slot of a lever 3 (O3 ...): straight through the lever's pivot (a Geneva
    wheel's radial slot, a slotted lever) or offset from it, or circular about the lever's point K;
    the lever listing the pin or not; driven by the crank or by the lever; or a six-bar: the lever
    drives a ram through a rod."""
    variant = variant or _any(rng, ("straight through", "straight offset", "circular", "straight six-bar",
                                    "circular six-bar"))
    d = Draft(rng, f"pin in a slot {variant}")
    r = rng.uniform(0.5, 1.0)
    O2, O3 = d.point("O2", (0.0, 0.0)), d.point("O3", (rng.uniform(1.2, 2.5) * r, 0.0))
    A = d.point("A", pol(O2, r, rng.uniform(-180, 180)))
    need(dist(A, O3) > 0.3 * r)
    lever = ["O3", "D"]
    D = d.point("D", pol(O3, dist(O3, A) * rng.uniform(1.3, 2.0), ang(O3, A) + rng.uniform(-20, 20)))
    if rng.random() < 0.4:
        lever.append("A")
    d.link(1, "O2", "O3", frame=True)
    d.link(2, "O2", "A")
    if variant.startswith("circular"):
        rho = rng.uniform(0.6, 2.0) * dist(O3, A)
        K = d.point("K", pol(A, rho, ang(O3, A) + _side(rng) * rng.uniform(50, 130)))
        lever.append("K")
        d.slots.append({"pin": "A", "link": "2", "slot": "3", "centre": "K"})
        tangent = ang(K, A) + 90
    else:
        tangent = ang(O3, A) + (0.0 if "through" in variant else rng.uniform(15, 45) * _side(rng))
        d.slots.append({"pin": "A", "link": "2", "slot": "3", "angle": tangent})
    need(transmission(O2, A, pol(A, 1.0, tangent)) >= MIN_SINE)
    d.link(3, *lever)
    driver = "2"
    if "six-bar" in variant:
        S = d.pos["D"]
        F = d.point("F", pol(S, rng.uniform(1.0, 2.0) * dist(O2, O3), rng.uniform(-180, 180)))
        path = ang(S, F) + rng.uniform(-60, 60)
        need(transmission(S, F, pol(F, 1.0, path)) >= MIN_SINE)
        d.link(4, "D", "F")
        d.link(5, "F")
        d.sliders.append({"block": "5", "guide": "1", "point": "F", "angle": path})
    elif rng.random() < 0.3:
        driver = "3"
    d.crank_driver(driver)
    return d.finish()


# -- contacts ----------------------------------------------------------------------------------------------
CONTACTS = ("wheel on ground", "wheel slipping on ground", "cam flat follower by its normal", "gears", "internal gears", "cam flat follower", "cam roller follower",
            "cam curved follower", "cam oscillating follower")


def gen_contact(rng, variant=None):
    variant = variant or _any(rng, CONTACTS)
    d = Draft(rng, f"contact {variant}")
    if variant.startswith("wheel"):
        # crank 2 (O2 A), rod 3 (A C), wheel 4 (C) rolling on the ground (the frame's flat), or
        # sliding on it with a prescribed slip
        R = rng.uniform(0.3, 1.0)
        O2 = d.point("O2", (0.0, rng.uniform(1.5, 3.0)))
        A = d.point("A", pol(O2, rng.uniform(0.3, 0.8), rng.uniform(-180, 180)))
        C = line_circle(A, rng.uniform(2.5, 4.0), (0.0, R), 0.0, (A[0] + _side(rng) * 4, R))
        need(transmission(A, C, (C[0] + 1, C[1])) >= MIN_SINE)
        d.point("C", C)
        d.point("P", (C[0], 0.0))
        d.point("G", (C[0] + 1.0, 0.0))
        d.link(1, "O2", "G", frame=True)
        d.link(2, "O2", "A")
        d.link(3, "A", "C")
        d.link(4, "C")
        contact = {"links": ["4", "1"], "point": "P", "kind": "rolling", "centres": ["C", "flat"]}
        d.contacts.append(contact)
        d.crank_driver(2)
        if "slipping" in variant:   # a slip constant in time: other poses only at a constant omega
            contact.update(kind="sliding", slip=float(rng.uniform(-3, 3)))
            d.driver["alpha"] = 0.0
    elif variant in ("gears", "internal gears"):
        r2 = rng.uniform(0.4, 1.2)
        r3 = rng.uniform(0.4, 1.2) + (r2 + 0.3 if variant == "internal gears" else 0.0)
        O2 = d.point("O2", (0.0, 0.0))
        t = rng.uniform(-180, 180)
        O3 = d.point("O3", pol(O2, r2 + r3 if variant == "gears" else r3 - r2, t))
        d.point("P", pol(O2, r2, t) if variant == "gears" else pol(O2, r2, t + 180))
        d.point("T2", pol(O2, r2, t + 70))
        d.point("T3", pol(O3, r3, t + 150))
        d.link(1, "O2", "O3", frame=True)
        d.link(2, "O2", "T2")
        d.link(3, "O3", "T3")
        d.contacts.append({"links": ["2", "3"], "point": "P", "kind": "rolling", "centres": ["O2", "O3"]})
        d.crank_driver(2)
    elif variant.startswith(("cam flat", "cam roller", "cam curved")):
        # an eccentric circular cam 2 (O centre of rotation, K centre of its profile, radius rho)
        e, rho = rng.uniform(0.2, 0.6), rng.uniform(1.0, 2.0)
        O = d.point("O", (0.0, 0.0))
        K = d.point("K", pol(O, e, rng.uniform(-180, 180)))
        path = 90.0 + rng.uniform(-15, 15)
        off = rng.uniform(-0.3, 0.3)
        d.link(1, "O", frame=True)
        d.link(2, "O", "K")
        if variant.startswith("cam flat"):
            u = path + rng.uniform(-20, 20)                 # the flat's normal
            P = d.point("P", pol(K, rho, u))
            F = d.point("F", pol(P, rng.uniform(0.5, 1.0), u - 90))
            d.link(3, "F")
            d.sliders.append({"block": "3", "guide": "1", "point": "F", "angle": path})
            d.contacts.append({"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "flat"]})
            if variant.endswith("by its normal"):           # the curvature not given: velocities only
                d.contacts[-1] = {"links": ["2", "3"], "point": "P", "kind": "sliding", "normal": "NORMAL"}
                d.normal = u
        else:
            rr = rng.uniform(0.2, 0.6)
            # the roller's (or the curved face's) centre R on the follower's line x = off
            R = line_circle(K, rho + rr, (off, 0.0), path, pol(O, 5.0, path))
            d.point("R", R)
            d.point("P", pol(K, rho, ang(K, R)))
            need(transmission(K, R, pol(R, 1.0, path)) >= MIN_SINE)
            if variant == "cam roller follower":
                d.link(3, "R")
                d.link(4, "R")
                d.sliders.append({"block": "3", "guide": "1", "point": "R", "angle": path})
                d.contacts.append({"links": ["2", "4"], "point": "P", "kind": "rolling", "centres": ["K", "R"]})
            else:
                S = d.point("S", pol(R, 0.5, path))
                d.link(3, "R", "S")
                d.sliders.append({"block": "3", "guide": "1", "point": "S", "angle": path})
                d.contacts.append({"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "R"]})
        d.crank_driver(2)
        if variant.endswith("by its normal"):
            d.offsets = (None,)   # no position equation: only the drawn pose can be analysed
    else:   # cam oscillating follower: follower 3 about O3 with a curved face (centre C), sliding
        e, rho = rng.uniform(0.2, 0.6), rng.uniform(0.8, 1.5)
        O = d.point("O", (0.0, 0.0))
        K = d.point("K", pol(O, e, rng.uniform(-180, 180)))
        O3 = d.point("O3", (rng.uniform(2.5, 3.5), rng.uniform(-1, 1)))
        rc = rng.uniform(0.2, 0.8)
        C = circles(K, rho + rc, O3, rng.uniform(1.0, 2.5), _side(rng))
        d.point("C", C)
        d.point("P", pol(K, rho, ang(K, C)))
        d.link(1, "O", "O3", frame=True)
        d.link(2, "O", "K")
        d.link(3, "O3", "C")
        d.contacts.append({"links": ["2", "3"], "point": "P", "kind": "sliding", "centres": ["K", "C"]})
        d.crank_driver(2)
    return d.finish()


KINDS = {
    "four-bar": (gen_fourbar, GRASHOF),
    "slider-crank": (gen_slider_crank, SLIDER_CRANKS),
    "inverted slider-crank": (gen_inverted, INVERTED),
    "six-bar": (gen_sixbar, SIXBARS),
    "slot": (gen_slot, ("straight through", "straight offset", "circular", "straight six-bar", "circular six-bar")),
    "contact": (gen_contact, CONTACTS),
    "eight-bar": (gen_eightbar, ("watt II + dyad", "stephenson III + dyad", "watt II + dyad to crank")),
}


def variants():
    """Every (kind, variant) pair, in a fixed order."""
    return [(k, v) for k, (_, vs) in KINDS.items() for v in vs]


MAX_CONDITION = 3e4   # the drawn pose's condition number (velpoly.solve's) at most: well away from a toggle


def specimen(rng, kind, variant=None, tries=200) -> Specimen:
    """One valid specimen of a kind (and variant), drawn again until the draw is regular: each
    dyad's transmission at least MIN_SINE, and the whole mechanism's velocity system (a toggle of
    the loop as a whole, which no single dyad shows) conditioned better than MAX_CONDITION."""
    import velpoly
    gen = KINDS[kind][0]
    for _ in range(tries):
        try:
            sp = gen(rng, variant)
        except Redraw:
            continue
        sol = velpoly.solve(velpoly.load(sp.mech))
        if sol.condition <= MAX_CONDITION:
            return replace(sp, drawn=sol)
    raise RuntimeError(f"no regular draw of {kind} {variant} in {tries} tries")


def fresh_zoo(seed: int = 2026, count: int = 300) -> list[Specimen]:
    """``count`` specimens cycling through every kind and variant (seeded), made anew."""
    rng = np.random.default_rng(seed)
    pairs = variants()
    return [specimen(rng, *pairs[i % len(pairs)]) for i in range(count)]


_MADE: dict = {}   # seed -> (its generator, as the last specimen made left it; the specimens made, in order)


def zoo(seed: int = 2026, count: int = 300) -> list[Specimen]:
    """:func:`fresh_zoo`'s specimens, made once per process and shared: each specimen draws on from where the
    one before it left the seeded generator, so the first n of a seed's specimens are the same whatever the
    count, and a longer batch goes on from a shorter one (test_zoo's 300 of seed 20261125, test_captions' 90,
    test_chain_poles' 57; test_zoo checks them against :func:`fresh_zoo`'s). Each call gets its own copies of
    the mechanisms' dicts (a test may change them); the drawn poses' solutions are shared (read only)."""
    return [replace(sp, mech=copy.deepcopy(sp.mech)) for sp in _made(seed, count)[:count]]


def each(seed: int = 2026, count: int = 300):
    """:func:`zoo`'s specimens one at a time (the same, shared the same way, each with its own copy of the
    mechanism's dict), made as they are asked for: a test that stops at the first few that suit it makes no more."""
    for k in range(count):
        sp = _made(seed, k + 1)[k]
        yield replace(sp, mech=copy.deepcopy(sp.mech))


def _made(seed: int, count: int) -> list:
    """The seed's specimens made so far in this process, at least ``count`` of them."""
    rng, made = _MADE.setdefault(seed, (np.random.default_rng(seed), []))
    pairs = variants()
    try:
        while len(made) < count:
            made.append(specimen(rng, *pairs[len(made) % len(pairs)]))
    except BaseException:
        del _MADE[seed]     # the generator went on without its specimen: start that seed again
        raise
    return made
