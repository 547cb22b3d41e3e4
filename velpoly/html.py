"""``velpoly html``: one self-contained interactive page of the sheet.

The page (``velpoly/html_assets/``: a template, a script and a style sheet,
all inlined) draws the whole sheet as SVG: the space diagram, the velocity
and acceleration polygons with their construction lines and link images, the
instant centres with their Kennedy lines and the Kennedy circle, and a results
table. A slider turns the driver over its cycle (the full turn, or the range a
limited-rotation linkage reaches on its drawn branch; a slider driver's
stroke); a stepper walks through the construction as ``velpoly draw --steps``
does. Nothing is solved in the browser: every pose is precomputed here.

**Poses.** The cycle is :func:`velpoly.sweeps.run_cycle` (one pose a
``step`` degrees); a crank that stops at a toggle is followed both ways from
the drawn pose to the ends of its reachable range. Each pose is turned into a
:class:`velpoly.Solution` (:func:`velpoly.sweeps.solution_at`) and its
polygons (:mod:`velpoly.polygons`) and poles (:mod:`velpoly.poles`) are
built from it exactly as the static sheet builds them, so the page shows the
same construction objects: images, construction lines with their reasons,
vectors with their textbook names, each step's vector equation.

**Space diagram.** Every drawn part of the mechanism is rigid with one link:
its outline is computed once in the reference pose (q = 0) and each pose
moves it by that link's coordinates ``(x, y, theta)``: a point with reference
position s is at ``(x, y) + R(theta) s``.

**Embedding.** A pose is a nested dict of numbers and strings; its shape (keys,
list lengths) is usually the same from pose to pose, so the page stores each
distinct shape once (a *template*: numbers as 0, strings as "") and every pose
as ``[template, numbers, string ids]`` with the strings in one shared table.
Numbers are written to 8 significant digits.
"""
from __future__ import annotations

import html as _html
import json
import math
import re
import sys
import types
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from .errors import InputError, VelpolyError
from .names import driver_index
from .rigid import direction as _unit

__all__ = ["sheet_data", "page", "html", "HtmlSheet", "write_page", "pose_values"]

PANEL = (480.0, 400.0)        # SVG units of a drawing panel (the page scales it to fit)
MARGIN = 34.0                 # SVG units kept free round a panel's contents
DIGITS = 8                    # significant digits of the embedded numbers


# -- poses -------------------------------------------------------------------------------------------
def _cycle(m, step: float):
    """The sweep the page shows, in driving order, the Kinematics, and whether the range is limited:
    a crank's full turn in the sense of its omega, or (stopped by a toggle) both ways from the
    drawn pose to the ends of its reachable range, in ascending angle; a slider driver's stroke."""
    from .driver import driver_reference_angle
    from .kinematics import prepare
    from .sweeps import check_step, join_sweeps, run_cycle, sweep
    kin = prepare(m)
    if m.driver.is_slider:
        return run_cycle(m, step, kin), kin, True
    step = check_step(step)
    ref = driver_reference_angle(m)
    n = max(int(math.ceil(360.0 / step - 1e-9)), 1)
    sense = -1.0 if m.driver.omega < 0 else 1.0
    ahead = sweep(m, ref + sense * step * np.arange(n), kin)
    if not ahead.stopped:
        return ahead, kin, False
    back = sweep(m, ref - sense * step * np.arange(n), kin)
    down, up = (back, ahead) if sense > 0 else (ahead, back)
    if not len(up.angles) or not len(down.angles):
        return ahead, kin, True
    import dataclasses
    return dataclasses.replace(join_sweeps(down, up), stopped=""), kin, True


def cycle_solutions(m, step: float = 1.0):
    """(sweep, kinematics, limited, [Solution of each pose]): the poses the page shows."""
    from .sweeps import solution_at
    w, kin, limited = _cycle(m, step)
    return w, kin, limited, [solution_at(w, kin, i) for i in range(len(w.angles))]


def _f(x) -> float | None:
    x = float(x)
    return x if math.isfinite(x) else None


def _xy(v) -> list | None:
    x, y = float(v[0]), float(v[1])
    return [x, y] if math.isfinite(x) and math.isfinite(y) else None


def _polygon(p) -> dict:
    """A Polygon (velpoly.polygons) as the page draws it."""
    steps = []
    for s in p.steps:
        steps.append({
            "k": s.kind, "eq": s.equation, "cap": s.caption, "f": list(s.found), "lk": s.link, "aux": list(s.auxiliary),
            "ln": [[*_xy(ln.base), *_xy(ln.direction), ln.base_label, ln.reason] for ln in s.lines],
            "v": [[*_xy(v.tail), *_xy(v.head), v.kind, v.label] for v in s.vectors],
            "w": {lk: _f(w) for lk, w in s.omegas.items()},
        })
    return {"o": p.origin_label, "img": {k: _xy(v) for k, v in p.images.items()},
            "lab": dict(p.labels), "li": {lk: list(keys) for lk, keys in p.link_images.items()},
            "r": {lk: _f(w) for lk, w in p.rates.items()},
            "aux": {k: {"p": _xy(a.position), "i": _xy(a.image), "lab": a.label, "lk": a.link}
                    for k, a in p.auxiliary.items()},
            "st": steps, "err": _f(p.max_error)}


def _pole_step(p, compact: bool) -> str:
    """A pole's step in words, as ``velpoly draw --steps`` captions it (:func:`velpoly.poles.pole_caption`)."""
    from .poles import pole_caption, pole_label
    return pole_caption(p, lambda key: pole_label(key, compact))


def _poles(sol) -> dict:
    from .poles import locate_poles
    ps = locate_poles(sol)
    compact = all(len(lk) == 1 for lk in ps.links)
    out = {}
    for key, p in ps.poles.items():
        out[key] = {"p": _xy(p.position) if p.position is not None else None,
                    "d": _f(p.direction) if p.direction is not None else None,
                    "how": p.how, "o": int(p.order),
                    "ln": [[*_xy(ln.point), *_xy(ln.direction), ln.label] for ln in p.construction],
                    "s": _pole_step(p, compact) if p.order > 0 else ""}
    return out


def pose_values(sol, index: dict) -> dict:
    """Everything the page draws at one pose (a Solution): links' coordinates, points' motion, the
    polygons and the poles. A construction that fails at this pose (a singular pose) is None with
    its message in ``msg``."""
    m = sol.mechanism
    q = sol.q
    out = {
        "q": [[float(q[3 * index[lk.name]]), float(q[3 * index[lk.name] + 1]), float(q[3 * index[lk.name] + 2])]
              for lk in m.moving_links],
        "P": {k: _xy(v) for k, v in sol.position.items()},
        "V": {k: _xy(v) for k, v in sol.velocity.items()},
        "A": {k: _xy(v) for k, v in sol.acceleration.items()} if sol.has_accelerations else None,
        "w": {k: _f(v) for k, v in sol.omega.items()},
        "al": {k: _f(v) for k, v in sol.alpha.items()} if sol.has_accelerations else None,
        "th": {k: _f(v) for k, v in sol.angle.items()},
        "msg": [],
    }
    from .polygons import acceleration_polygon, velocity_polygon
    for name, fn in (("vp", velocity_polygon), ("ap", acceleration_polygon), ("poles", _poles)):
        if name == "ap" and not sol.has_accelerations:
            out[name] = None
            continue
        try:
            out[name] = _polygon(fn(sol)) if name != "poles" else fn(sol)
        except VelpolyError as e:
            out[name] = None
            out["msg"].append(e.what)
    return out


# -- the templates: one shape, many poses ------------------------------------------------------------
def _split(obj, numbers: list, strings: list):
    """The template of ``obj`` (numbers -> 0, strings -> ""), filling ``numbers`` and ``strings``."""
    t = type(obj)
    if t is float or t is int:
        numbers.append(obj)
        return 0
    if t is str:
        strings.append(obj)
        return ""
    if t is dict:   # in the order a browser walks an object: index-like keys first, ascending
        keys = sorted(obj, key=lambda k: (0, int(k), "") if _INDEX.fullmatch(str(k)) else (1, 0, ""))
        return {str(k): _split(obj[k], numbers, strings) for k in keys}
    if t is list or t is tuple:
        return [_split(v, numbers, strings) for v in obj]
    return obj    # None, True, False


_INDEX = re.compile(r"0|[1-9][0-9]{0,8}")   # keys JavaScript orders as array indices (below 2**32 - 1)


def _number(x: float) -> str:
    if x == 0 or not math.isfinite(x):
        return "0"
    s = f"{x:.{DIGITS}g}"
    if "e" in s:
        mant, exp = s.split("e")
        s = mant + "e" + str(int(exp))
    return s


class _Encoder:
    def __init__(self):
        self.templates, self.template_ids = [], {}
        self.strings, self.string_ids = [], {}
        self.poses = []

    def add(self, obj) -> None:
        nums, strs = [], []
        tpl = json.dumps(_split(obj, nums, strs), separators=(",", ":"))
        if tpl not in self.template_ids:
            self.template_ids[tpl] = len(self.templates)
            self.templates.append(tpl)
        sids = []
        for s in strs:
            if s not in self.string_ids:
                self.string_ids[s] = len(self.strings)
                self.strings.append(s)
            sids.append(self.string_ids[s])
        self.poses.append(f"[{self.template_ids[tpl]},[{','.join(_number(x) for x in nums)}],"
                          f"[{','.join(map(str, sids))}]]")

    def json(self) -> str:
        return ('{"templates":[' + ",".join(self.templates) + '],"strings":'
                + json.dumps(self.strings, separators=(",", ":"), ensure_ascii=False)
                + ',"poses":[\n' + ",\n".join(self.poses) + "]}")


# -- the static drawing: parts rigid with a link, in the reference pose ---------------------------
NICE = (1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)
CM = 37.8     # SVG units a centimetre of a panel at its nominal size (96 per inch)


def _nice_up(x: float) -> float:
    """The round value (1, 1.2, 1.5, 2, 2.5, 3, 4, 5, 6, 8 x 10^n) at or above x: a drawing scale."""
    e = 10.0 ** math.floor(math.log10(x))
    return next(f for f in NICE if x / e <= f * (1 + 1e-12)) * e


class _View:
    """Mechanism coordinates -> SVG units of a panel: X = k (x - x0) + ox, Y = k (y1 - y) + oy."""

    def __init__(self, pts, size=PANEL, margin=MARGIN, floor=1e-300):
        pts = np.asarray(pts, float).reshape(-1, 2)
        pts = pts[np.all(np.isfinite(pts), axis=1)]
        if not len(pts):
            pts = np.zeros((1, 2))
        lo, hi = pts.min(axis=0), pts.max(axis=0)
        span = np.maximum(hi - lo, floor)
        w, h = size
        self.k = float(min((w - 2 * margin) / span[0], (h - 2 * margin) / span[1]))
        if not math.isfinite(self.k) or self.k <= 0:
            self.k = 1.0
        self.k = CM / _nice_up(CM / self.k)    # a round scale (NICE x 10^n units a centimetre)
        c = (lo + hi) / 2
        self.x0 = float(c[0] - (w / 2) / self.k)
        self.y1 = float(c[1] + (h / 2) / self.k)
        self.size = size

    def to_dict(self) -> dict:
        return {"k": self.k, "x0": self.x0, "y1": self.y1, "w": self.size[0], "h": self.size[1]}


def _path(geom, k: float) -> str:
    """SVG path data of a shapely geometry given in mechanism units of the reference pose, in the
    link's own SVG frame: (k x, -k y)."""
    polys = getattr(geom, "geoms", [geom])
    out = []
    for poly in polys:
        rings = (poly.exterior, *poly.interiors) if hasattr(poly, "exterior") else (poly,)
        for ring in rings:
            xy = np.asarray(ring.coords)
            if not len(xy):
                continue
            pts = " ".join(f"{k * x:.2f},{-k * y:.2f}" for x, y in xy)
            out.append("M" + pts + ("Z" if hasattr(poly, "exterior") else ""))
    return "".join(out)


def _static(m, sol0, w, view: _View) -> dict:
    """The parts of the space diagram rigid with each link (outlines in the reference pose), ground
    pivots and guides on the frame, and the kinds of points."""
    sp = _SpaceParts(m, sol0, w, view)
    sp.link_bodies()
    sp.sliders()
    sp.slots()
    sp.contacts()
    sp.discs()
    bodies = sp.bodies()
    numbers = _link_numbers(m, sp.ref, sp.px)
    pins_at = sp.pivots()
    return {"bodies": bodies, "ground": sp.ground, "numbers": numbers, "kinds": _point_kinds(m, sol0, pins_at)}


class _SpaceParts:
    """The space diagram's parts as the page moves them: per moving link its shapely outlines
    (``parts``) and holes (a slot, a guide's groove) in its reference-pose coordinates; on the frame
    the static paths (``ground``: [SVG path data, class]). Sizes are in SVG units of the panel
    (``px`` is one of them in mechanism units)."""

    def __init__(self, m, sol0, w, view: _View):
        self.m, self.sol0, self.w = m, sol0, w
        self.k = view.k
        self.px = 1.0 / view.k
        self.bar = 11 * self.px
        self.ref = {p: np.asarray(v, float) for p, v in m.points.items()}
        self.parts: dict = {lk.name: [] for lk in m.moving_links}
        self.holes: dict = {lk.name: [] for lk in m.moving_links}
        self.ground: list = []
        self.index = sol0.kinematics.system.index

    def local(self, lk, pts):
        """Points of link lk over the sweep, in its reference-pose coordinates."""
        i = self.index[lk]
        q = self.w.q
        x, y, th = q[:, 3 * i], q[:, 3 * i + 1], q[:, 3 * i + 2]
        d = np.asarray(pts, float) - np.c_[x, y]
        c, s = np.cos(th), np.sin(th)
        return np.c_[c * d[:, 0] + s * d[:, 1], -s * d[:, 0] + c * d[:, 1]]

    def line(self, a, b) -> str:
        k = self.k
        return f"M{k * a[0]:.2f},{-k * a[1]:.2f}L{k * b[0]:.2f},{-k * b[1]:.2f}"

    def hatch(self, a, b, side, cls="ground"):
        """Hatched ground along a to b, the strokes slanting to ``side``."""
        k, px = self.k, self.px
        a, b, side = (np.asarray(v, float) for v in (a, b, side))
        d = b - a
        L = float(np.hypot(*d))
        if L <= 0:
            return
        u = d / L
        slant = side + 0.75 * u
        slant = slant / np.hypot(*slant) * 8 * px
        n = max(int(L / (6 * px)), 1)
        segs = [self.line(a, b)]
        for j in range(n + 1):
            p = a + u * (j * L / n)
            segs.append(f"M{k * p[0]:.2f},{-k * p[1]:.2f}l{k * slant[0]:.2f},{-k * slant[1]:.2f}")
        self.ground.append(["".join(segs), cls])

    def track(self, point, link):
        """The sweep's positions of a point (its key on ``link`` where the carriers differ)."""
        key = point if point in self.w.position else f"{point}@{link}"
        return self.w.position.get(key, self.w.position.get(point))

    def link_bodies(self):
        """Links with two or more points: the hull of their points, as a bar or a plate."""
        from shapely.geometry import MultiPoint
        for lk in self.m.moving_links:
            if len(lk.points) >= 2:
                hull = MultiPoint([tuple(self.ref[p]) for p in lk.points]).convex_hull
                self.parts[lk.name].append(hull.buffer(self.bar / 2, 12))

    def sliders(self):
        """Each block rigid with its link; a fixed guide hatched over the whole travel, a moving one
        a slotted bar over the block's travel relative to it."""
        from shapely.geometry import Polygon as SPolygon
        px, sol0 = self.px, self.sol0
        for s, r in zip(self.m.sliders, sol0.motion.sliders):
            d = _unit(float(r["direction"][0]))   # at the drawn pose: rotate back to the reference pose
            ib = self.index.get(s.block)
            th_b = float(sol0.q[3 * ib + 2]) if ib is not None else 0.0
            c, sn = math.cos(-th_b), math.sin(-th_b)
            d_ref = np.array([c * d[0] - sn * d[1], c * d[1] + sn * d[0]])
            n_ref = np.array([-d_ref[1], d_ref[0]])
            p = self.ref[s.point]
            L, H = 30 * px, 18 * px
            block = SPolygon([p - d_ref * L / 2 - n_ref * H / 2, p + d_ref * L / 2 - n_ref * H / 2,
                              p + d_ref * L / 2 + n_ref * H / 2, p - d_ref * L / 2 + n_ref * H / 2])
            if s.block in self.parts:
                self.parts[s.block].append(block)
            if s.centre is not None:
                continue
            track = self.track(s.point, s.block)   # the block's point along the guide
            if track is None:
                continue
            if self.m.link(s.guide).frame:
                self._fixed_guide(s, d, track, L, H)
            elif s.guide in self.parts:
                self._moving_guide(s, d_ref, p, track, L, H)

    def _fixed_guide(self, s, d, track, L, H):
        """A guide on the frame: hatched on the side away from the block's other links, with its
        centre line, over the block's whole travel."""
        sol0 = self.sol0
        p_now = sol0.place(s.block, s.point)
        t = (track - p_now) @ d
        lo, hi = float(t.min()) - L, float(t.max()) + L
        a, b = p_now + d * lo, p_now + d * hi
        nrm = np.array([-d[1], d[0]])
        others = [sol0.place(x, q) for x in self.m.carriers.get(s.point, ()) if x not in (s.block, s.guide)
                  for q in self.m.link(x).points if q != s.point]
        side = -1.0 if others and np.dot(sum(o - p_now for o in others), nrm) > 0 else 1.0
        off = nrm * side * H / 2
        self.hatch(a + off, b + off, nrm * side, "guide")
        self.ground.append([self.line(a, b), "centre-line"])

    def _moving_guide(self, s, d_ref, p, track, L, H):
        """A guide on a moving link: a slotted bar over the block's travel relative to it."""
        from shapely.geometry import LineString
        loc = self.local(s.guide, track)
        t = (loc - p) @ d_ref
        lo, hi = float(t.min()) - L / 2, float(t.max()) + L / 2
        seg = LineString([tuple(p + d_ref * lo), tuple(p + d_ref * hi)])
        self.parts[s.guide].append(seg.buffer(H / 2 + 3 * self.px, cap_style="flat"))
        self.holes[s.guide].append(seg.buffer(H * 0.3, cap_style="round"))

    def slots(self):
        """Each slot along its pin's travel: cut in the frame, or a slotted part of its link."""
        from shapely.geometry import LineString
        m, px, k = self.m, self.px, self.k
        for s in m.slots:
            track = self.track(s.pin, s.link)
            if track is None or s.slot not in self.parts and not m.link(s.slot).frame:
                continue
            pts = track if m.link(s.slot).frame else self.local(s.slot, track)
            seg = LineString([tuple(x) for x in pts]).simplify(px)
            if seg.length <= 0:
                continue
            if m.link(s.slot).frame:
                self.ground.append([_path(seg.buffer(9 * px), k), "slot-frame"])
                self.ground.append([_path(seg.buffer(5.5 * px), k), "slot"])
            else:
                self.parts[s.slot].append(seg.buffer(9 * px))
                self.holes[s.slot].append(seg.buffer(5.5 * px))

    def contacts(self):
        """The contacts' profiles: circles about their centres of curvature, flats along the tangent."""
        m = self.m
        for c, r in zip(m.contacts, self.sol0.motion.contacts):
            if c.centres is None:
                continue
            place_now = np.asarray(r["place"][0], float)
            for j, (lk, cn) in enumerate(zip(c.links, c.centres)):
                if m.link(lk).frame:
                    self._frame_profile(c, r, j, lk, cn, place_now)
                elif lk in self.parts:
                    self._link_profile(r, j, lk, cn, place_now)

    def _frame_profile(self, c, r, j, lk, cn, place_now):
        """A profile on the frame: a hatched flat over the contact's travel, or its circle."""
        from shapely.geometry import Point
        px = self.px
        u = _unit(float(r["normal"][0])) * (1 if j == 1 else -1)
        t = np.array([-u[1], u[0]])
        track = self.w.position.get(f"{c.point}@{lk}", self.w.position.get(c.point))
        if cn is None:
            tt = (track - place_now) @ t if track is not None else np.array([0.0])
            a, b = place_now + t * (float(tt.min()) - 20 * px), place_now + t * (float(tt.max()) + 20 * px)
            self.hatch(a, b, u, "ground")
        else:
            ctr = self.ref[cn] if cn in self.ref else self.sol0.place(lk, cn)
            rad = float(np.hypot(*(place_now - ctr)))
            self.ground.append([_path(Point(*ctr).buffer(rad, 64).exterior, self.k), "profile"])

    def _link_profile(self, r, j, lk, cn, place_now):
        """A profile on a moving link: a flat face (on a one-point link, a plate through the contact
        along the tangent), or a disc about its centre of curvature."""
        from shapely.geometry import LineString, Point
        from shapely.geometry import Polygon as SPolygon
        px, ref = self.px, self.ref
        if cn is not None:
            if cn in ref:
                rad = float(np.hypot(*(self.local(lk, place_now[None, :])[0] - ref[cn])))
                if rad < 1.5 * self.m.size:
                    self.parts[lk].append(Point(*ref[cn]).buffer(rad, 48))
            return
        link = self.m.link(lk)
        if len(link.points) >= 2:
            return
        th = float(self.sol0.q[3 * self.index[lk] + 2])
        u = _unit(float(r["normal"][0]) - math.degrees(th)) * (-1 if j == 0 else 1)
        t = np.array([-u[1], u[0]])
        own = ref[link.points[0]]
        pl = self.local(lk, place_now[None, :])[0]
        foot = pl + t * float(np.dot(own - pl, t))
        half = max(40 * px, abs(float(np.dot(pl - foot, t))) + 20 * px)
        e0, e1 = foot - t * half, foot + t * half
        geom = SPolygon([e0, e1, e1 + u * 7 * px, e0 + u * 7 * px])
        if float(np.hypot(*(own - foot))) > 8 * px:
            geom = geom.union(LineString([tuple(own), tuple(foot)]).buffer(self.bar / 2, cap_style="flat"))
        self.parts[lk].append(geom)

    def discs(self):
        """One-point links with nothing else drawn (no block either): a disc."""
        from shapely.geometry import Point
        blocks = {s.block for s in self.m.sliders}
        for lk in self.m.moving_links:
            if not self.parts[lk.name] and lk.name not in blocks:
                self.parts[lk.name].append(Point(*self.ref[lk.points[0]]).buffer(8 * self.px, 12))

    def bodies(self) -> dict:
        """Each link's parts as one outline and its holes, as SVG path data."""
        from shapely.ops import unary_union
        out = {}
        for lk, geoms in self.parts.items():
            if geoms:
                holes = self.holes[lk]
                out[lk] = {"d": _path(unary_union(geoms), self.k),
                           "holes": _path(unary_union(holes), self.k) if holes else ""}
        return out

    def pivots(self) -> dict:
        """Ground pivots: a triangle on hatched ground, the way most free of the pivot's links.
        Returns each pinned point's links."""
        m, sol0, px, k = self.m, self.sol0, self.px, self.k
        pins_at: dict = {}
        for pin in m.pins:
            pins_at.setdefault(pin.point, set()).update(pin.links)
        for point, links in pins_at.items():
            if m.frame.name not in links:
                continue
            p = np.asarray(sol0.position.get(point, self.ref.get(point)), float)
            others = [sol0.place(x, q) - p for x in links - {m.frame.name} for q in m.link(x).points if q != point]
            away = -sum((o / max(float(np.hypot(*o)), 1e-300) for o in others), np.zeros(2))
            g = max((-90.0, 0.0, 180.0, 90.0), key=lambda a: float(np.dot(_unit(a), away)) + (0.45 if a == -90 else 0))
            u = _unit(g)
            nrm = np.array([-u[1], u[0]])
            base = p + u * 19 * px
            tri = [p + nrm * 4.5 * px, base + nrm * 11 * px, base - nrm * 11 * px, p - nrm * 4.5 * px]
            self.ground.append(["M" + " ".join(f"{k * x:.2f},{-k * y:.2f}" for x, y in tri) + "Z", "pivot"])
            self.hatch(base + nrm * 19 * px, base - nrm * 19 * px, u)
        return pins_at


def _link_numbers(m, ref, px) -> dict:
    """Where each link's number goes: beside a bar's middle (away from the mechanism's centre),
    inside a plate."""
    centre = np.mean(np.array(list(ref.values())), axis=0)
    numbers = {}
    for lk in m.moving_links:
        pts = [ref[p] for p in lk.points]
        if len(pts) >= 3:
            anchor = np.mean(np.array(pts), axis=0)
        elif len(pts) == 2:
            a, b = pts
            u = (b - a) / max(float(np.hypot(*(b - a))), 1e-300)
            nrm = np.array([-u[1], u[0]])
            if np.dot(nrm, (a + b) / 2 - centre) < 0:
                nrm = -nrm
            anchor = (a + b) / 2 + nrm * 20 * px
        else:
            anchor = pts[0] + np.array([22, 22]) * px
        numbers[lk.name] = [float(anchor[0]), float(anchor[1])]
    return numbers


def _point_kinds(m, sol0, pins_at) -> dict:
    """Each point key's mark: a pin (open circle), a centre of curvature (cross), else a dot."""
    centres = {cn for c in m.contacts for cn in (c.centres or ()) if cn} | \
        {s.centre for s in (*m.sliders, *m.slots) if s.centre}
    pins = set(pins_at) | {s.pin for s in m.slots}
    kinds = {}
    for key in sol0.position:
        name = key.split("@")[0]
        kinds[key] = "pin" if name in pins else "centre" if name in centres else "dot"
    return kinds


def _driver_text(m) -> str:
    d = m.driver
    if d.is_slider:   # along its path: relative to a moving guide (V_A₃/A₄), as the sheet and captions name it
        return f"V_{driver_index(m)} = {abs(d.speed):.4g} {m.units}/s"
    text = f"omega_{d.link} = {abs(d.omega):.4g} rad/s {'ccw' if d.omega >= 0 else 'cw'}"
    if d.alpha:
        text += f", alpha_{d.link} = {abs(d.alpha):.4g} rad/s^2 {'ccw' if d.alpha >= 0 else 'cw'}"
    return text


def sheet_data(m, step: float = 1.0, cycle=None) -> tuple[dict, str]:
    """The page's data: (static part as a dict, the poses as JSON text of the templates' encoding).
    ``cycle``: what :func:`cycle_solutions` gives, if already at hand."""
    from .sweeps import solution_at
    from .reference import file_pose_angle
    from .solution import driver_reference_angle
    w, kin, limited, sols = cycle if cycle is not None else cycle_solutions(m, step)
    if not len(w.angles):
        raise InputError("no pose of the driver's cycle can be assembled", where="driver", file=m.source)
    index = kin.system.index
    enc = _Encoder()
    for sol in sols:
        enc.add(pose_values(sol, index))
    # the pose the file draws: the one nearest its driver angle (the reference pose for a slider)
    a = np.asarray(w.angles, float)
    if m.driver.is_slider:
        start = int(np.argmin(np.abs(a)))
    else:
        target = file_pose_angle(m)
        start = int(np.argmin(np.abs((a - target + 180.0) % 360.0 - 180.0)))
    sol0 = solution_at(w, kin, int(np.argmin(np.abs(a - (0 if m.driver.is_slider else driver_reference_angle(m))))))
    # views: fixed over the cycle, so that the drawing does not jump
    pos = np.vstack([v for v in w.position.values()])
    space = _View(pos, floor=m.size * 1e-3)
    space = _View(np.vstack([pos, pos.min(axis=0) - 14 / space.k, pos.max(axis=0) + 14 / space.k]),
                  floor=m.size * 1e-3)
    lo, hi = pos.min(axis=0), pos.max(axis=0)
    grow = 0.25 * (hi - lo).max()
    pole_view = _View(np.vstack([lo - grow, hi + grow]), floor=m.size * 1e-3)
    static = _static(m, sol0, w, space)
    static_poles = _static(m, sol0, w, pole_view)
    # the [reference] table at the file's pose
    ref_rows = _reference_rows(m)
    data = {
        "format": 1, "title": m.title, "units": m.units, "source": m.source or "",
        "frame": m.frame.name, "links": [lk.name for lk in m.links], "moving": [lk.name for lk in m.moving_links],
        "points": {lk.name: list(lk.points) for lk in m.links},
        "driver": {"link": m.driver.link, "slider": m.driver.slider if m.driver.is_slider else None,
                   "text": _driver_text(m), "omega": m.driver.omega if not m.driver.is_slider else None},
        "pivot": next((pin.point for pin in m.pins if not m.driver.is_slider
                       and set(pin.links) == {m.driver.link, m.frame.name}), None),
        "angles": [float(x) for x in w.angles], "start": start, "limited": limited,
        "size": float(m.size), "step": float(step),
        # the polygons' views are chosen by the page for each pose: a round scale that fits it
        "views": {"space": space.to_dict(), "poles": pole_view.to_dict(), "panel": list(PANEL), "margin": MARGIN},
        "accelerations": bool(sols[0].has_accelerations),
        "space": static, "polesSpace": static_poles,
        "reference": {"source": m.reference.source if m.reference else "", "rows": ref_rows},
    }
    return data, enc.json()


def _reference_rows(m) -> list[dict]:
    """The ``[reference]`` table at the file's pose, as the page shows it; ``z``: below it a computed value is
    rounding noise and prints 0, as in velpoly solve's table (compare.key_floor)."""
    from .compare import key_floor, kind_scales
    from .reference import compare
    from .solution import solve
    try:
        file_pose = solve(m) if m.reference is not None else None
        rows, scales = (compare(file_pose), kind_scales(file_pose)) if file_pose is not None else ([], {})
    except VelpolyError:
        return []
    return [{"key": r.key, "printed": r.printed, "value": r.computed, "dev": r.deviation, "angle": r.angle_error,
             "note": r.note, "z": key_floor(m, r.key, scales)} for r in rows]


# -- the page ----------------------------------------------------------------------------------------
def _asset(name: str) -> str:
    return resources.files("velpoly").joinpath("html_assets", name).read_text(encoding="utf-8")


def _script_safe(text: str) -> str:
    """JSON text safe inside <script>: no "</" can close the element."""
    return text.replace("</", "<\\/").replace("<!--", "<\\!--")


def page(m, step: float = 1.0) -> str:
    """The whole self-contained HTML page of mechanism ``m`` (a string)."""
    static, poses = sheet_data(m, step)
    default = lambda o: o.tolist() if isinstance(o, np.ndarray) else float(o)  # noqa: E731
    static_json = json.dumps(static, separators=(",", ":"), ensure_ascii=False, allow_nan=False,
                             default=default)
    fill = {"{{TITLE}}": _html.escape(m.title), "/*STYLE*/": _asset("sheet.css"), "/*SCRIPT*/": _asset("sheet.js"),
            "/*DATA*/": "window.VELPOLY_STATIC=" + _script_safe(static_json) + ";\nwindow.VELPOLY_POSES="
                        + _script_safe(poses) + ";"}
    # each marker of the template filled once, in one pass: nothing filled in is read again
    parts = re.split(r"(\{\{TITLE\}\}|/\*STYLE\*/|/\*SCRIPT\*/|/\*DATA\*/)", _asset("sheet.html"))
    return "".join(fill.get(p, p) for p in parts)


def write_page(m, out, step: float = 1.0) -> Path:
    """Write the page of ``m`` to ``out`` atomically; return the path."""
    from .fileio import atomic_write_text
    out = Path(out)
    atomic_write_text(out, page(m, step))
    return out


@dataclass(frozen=True)
class HtmlSheet:
    """The interactive page; shown inline by a notebook (an iframe whose ``srcdoc`` is the page)."""

    text: str

    def _repr_html_(self) -> str:
        return (f'<iframe srcdoc="{_html.escape(self.text, quote=True)}" style="width:100%;height:900px;'
                'border:1px solid #ccc" sandbox="allow-scripts"></iframe>')

    def __str__(self) -> str:
        return self.text

    def save(self, out) -> Path:
        from .fileio import atomic_write_text
        atomic_write_text(Path(out), self.text)
        return Path(out)


def html(m, step: float = 1.0) -> HtmlSheet:
    """The interactive page of a Mechanism (or of a Solution's mechanism), for a notebook or a file:
    ``velpoly.html(m)`` shows it inline; ``velpoly.html(m).save("sheet.html")`` writes it."""
    from .model import Mechanism
    mech = getattr(m, "mechanism", m)
    if not isinstance(mech, Mechanism):
        raise InputError(f"velpoly.html needs a Mechanism, got {type(m).__name__}", where="m")
    return HtmlSheet(page(mech, step))


class _CallableModule(types.ModuleType):
    """``velpoly.html(m)``: the module is also the function, whichever of the two ``velpoly.html``
    names after ``import velpoly.html`` (Python binds a package's submodule as its attribute)."""

    def __call__(self, m, step: float = 1.0) -> HtmlSheet:
        return html(m, step)


sys.modules[__name__].__class__ = _CallableModule
