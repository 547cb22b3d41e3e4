"""Hand-made construction objects for the render tests, following docs/internals.md's contract.

The figures are drawn from velpoly.polygons' objects (Polygon, Step,
ConstructionLine, Vector); these are built by hand for the six-bar of
velpoly/examples/problem_1_4_4_sixbar.toml, the way a textbook constructs them, so that the
drawing code is tested against known geometry independently of how
velpoly.polygons plans its constructions.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
from shapely.geometry import box

import velpoly
from velpoly.polygons import ConstructionLine, Polygon, Step, Vector
from velpoly.render.labels import placer

from paths import SIXBAR  # noqa: E402


def _unit(v):
    v = np.asarray(v, float)
    return v / np.hypot(*v)


def _perp(v):
    return np.array([-v[1], v[0]])


def sixbar_velocity(sol) -> Polygon:
    """The velocity polygon of the six-bar: b (driver), c (two lines), e (image), f (two lines)."""
    P, V = sol.position, sol.velocity
    o = np.zeros(2)
    steps = (
        Step(1, "driver", "V_B = omega_1 x R_BA", (), ("B",), (Vector(o, V["B"], "absolute", "V_B"),),
             {"1": sol.omega["1"]}, 1.0),
        Step(2, "intersection", "V_C = V_B + V_CB = V_D + V_CD",
             (ConstructionLine(V["B"], _unit(_perp(P["C"] - P["B"])), "b", "perpendicular to BC"),
              ConstructionLine(o, _unit(_perp(P["C"] - P["D"])), "d", "perpendicular to DC")),
             ("C",), (Vector(V["B"], V["C"], "relative", "V_CB"), Vector(o, V["C"], "absolute", "V_C")),
             {"2": sol.omega["2"], "3": sol.omega["3"]}, 0.8),
        Step(3, "image", "V_E from the image of DCE", (), ("E",), (Vector(o, V["E"], "absolute", "V_E"),), {}, 1.0),
        Step(4, "intersection", "V_F = V_E + V_FE, along the path",
             (ConstructionLine(V["E"], _unit(_perp(P["F"] - P["E"])), "e", "perpendicular to EF"),
              ConstructionLine(o, np.array([0.0, 1.0]), "O_v", "parallel to the path of F")),
             ("F",), (Vector(V["E"], V["F"], "relative", "V_FE"),), {"4": sol.omega["4"]}, 0.95),
    )
    images = {k: np.asarray(V[k], float) for k in ("A", "D", "B", "C", "E", "F")}
    return Polygon("velocity", "O_v", images, {k: k.lower() for k in images}, steps,
                   {"1": ("A", "B"), "2": ("B", "C"), "3": ("D", "C", "E"), "4": ("E", "F")},
                   {lk: sol.omega[lk] for lk in ("1", "2", "3", "4", "5")}, 0.0)


def sixbar_acceleration(sol) -> Polygon:
    """The acceleration polygon of the six-bar, normal and tangential components drawn."""
    P, A, w = sol.position, sol.acceleration, sol.omega
    o = np.zeros(2)

    def normal(lk, p, q):   # A^n of p relative to q on link lk: omega^2 |R| towards q
        return -w[lk] ** 2 * (P[p] - P[q])

    n_cb = A["B"] + normal("2", "C", "B")
    n_cd = normal("3", "C", "D")
    n_fe = A["E"] + normal("4", "F", "E")
    steps = (
        Step(1, "driver", "A_B = A^n_BA + A^t_BA", (), ("B",), (Vector(o, A["B"], "normal", "A^n_BA"),), {}, 1.0),
        Step(2, "intersection", "A_C = A_B + A^n_CB + A^t_CB = A^n_CD + A^t_CD",
             (ConstructionLine(n_cb, _unit(_perp(P["C"] - P["B"])), "n_CB", "perpendicular to BC"),
              ConstructionLine(n_cd, _unit(_perp(P["C"] - P["D"])), "n_CD", "perpendicular to DC")),
             ("C",), (Vector(A["B"], n_cb, "normal", "A^n_CB"), Vector(n_cb, A["C"], "tangential", "A^t_CB"),
                      Vector(o, n_cd, "normal", "A^n_CD"), Vector(n_cd, A["C"], "tangential", "A^t_CD")),
             {"2": sol.alpha["2"], "3": sol.alpha["3"]}, 0.8),
        Step(3, "image", "A_E from the image of DCE", (), ("E",), (), {}, 1.0),
        Step(4, "intersection", "A_F = A_E + A^n_FE + A^t_FE, along the path",
             (ConstructionLine(n_fe, _unit(_perp(P["F"] - P["E"])), "n_FE", "perpendicular to EF"),
              ConstructionLine(o, np.array([0.0, 1.0]), "O_a", "parallel to the path of F")),
             ("F",), (Vector(A["E"], n_fe, "normal", "A^n_FE"), Vector(n_fe, A["F"], "tangential", "A^t_FE")),
             {"4": sol.alpha["4"]}, 0.95),
    )
    images = {k: np.asarray(A[k], float) for k in ("A", "D", "B", "C", "E", "F")}
    return Polygon("acceleration", "O_a", images, {k: k.lower() + "'" for k in images}, steps,
                   {"1": ("A", "B"), "2": ("B", "C"), "3": ("D", "C", "E"), "4": ("E", "F")},
                   {lk: sol.alpha[lk] for lk in ("1", "2", "3", "4", "5")}, 0.0)


def load_sixbar():
    m = velpoly.load(SIXBAR)
    return m, velpoly.solve(m)


def rotate(v, deg):
    t = math.radians(deg)
    return np.array([math.cos(t) * v[0] - math.sin(t) * v[1], math.sin(t) * v[0] + math.cos(t) * v[1]])


def _page_texts(fig):
    """The page's title, panel captions and step caption with their boxes (figure pixels)."""
    r = fig.canvas.get_renderer()
    out = []
    for t in fig.texts:
        gid = t.get_gid() or ""
        if gid == "sheet-title" or gid.startswith("caption-") or gid == "step-caption":
            bb = t.get_window_extent(r)
            if gid == "step-caption":   # the box drawn round it
                p = (0.3 * t.get_fontsize()) * fig.dpi / 72
                bb = bb.expanded(1, 1).from_extents(bb.x0 - p, bb.y0 - p, bb.x1 + p, bb.y1 + p)
            out.append((gid, box(bb.x0, bb.y0, bb.x1, bb.y1)))
    return out


def assert_page_texts_clear(fig):
    """Title and captions inside the page, clear of each other and of the panels beneath them."""
    W, H = fig.get_size_inches() * fig.dpi
    page = box(0, 0, W, H)
    texts = _page_texts(fig)
    for gid, b in texts:
        assert page.contains(b), f"{gid} runs off the page"
    for i, (ga, a) in enumerate(texts):
        for gb, b in texts[i + 1:]:
            assert not a.intersects(b), f"{ga} and {gb} overlap"
    panels = {ax.get_label(): ax.get_window_extent() for ax in fig.axes}
    for gid, b in texts:
        for name, bb in panels.items():
            if name != "table" and gid != f"caption-{name}":
                assert not b.intersects(box(bb.x0, bb.y0, bb.x1, bb.y1)), f"{gid} over the {name} panel"


def legend_trouble(fig) -> list:
    """What each polygon's legend (window box) runs over: the panel's border, lines (construction lines,
    shafts), arrowheads. Empty when every legend sits clear."""
    from shapely.geometry import LineString
    r = fig.canvas.get_renderer()
    out = []
    for ax in fig.axes:
        leg = ax.get_legend()
        if leg is None:
            continue
        bb = leg.get_window_extent(r)
        lb = box(bb.x0, bb.y0, bb.x1, bb.y1)
        ab = ax.get_window_extent()
        if not box(ab.x0 - 1, ab.y0 - 1, ab.x1 + 1, ab.y1 + 1).contains(lb):
            out.append(("outside its panel", ax.get_label()))
        for ln in ax.lines:
            pts = ax.transData.transform(ln.get_xydata())
            pts = pts[np.all(np.isfinite(pts), axis=1)]
            if len(pts) >= 2 and LineString(pts).intersects(lb):
                out.append(("over a line", ln.get_gid()))
        for p in ax.patches:
            if (p.get_gid() or "").startswith(("absolute", "normal", "tangential", "coriolis", "slip", "relative")) \
                    and p.get_window_extent(r).overlaps(bb):
                out.append(("over an arrowhead", p.get_gid()))
    return out


def reasons_too_close(fig, gap: float = 3.5) -> list:
    """Construction reasons whose text comes within ``gap`` points of a label (they read as one:
    '... the path of B on 1 O_v, o_1')."""
    from shapely import affinity
    r = fig.canvas.get_renderer()
    out = []

    def outline(t):
        rot = t.get_rotation()
        t.set_rotation(0)
        bb = t.get_window_extent(r)
        t.set_rotation(rot)
        return affinity.rotate(box(bb.x0, bb.y0, bb.x1, bb.y1), rot, origin="centroid")
    for ax in fig.axes:
        reasons = [t for t in ax.texts if (t.get_gid() or "").endswith("-reason")]
        labels = [t for t in ax.texts if (t.get_gid() or "").startswith("label-")]
        for a in reasons:
            oa = outline(a)
            for b in labels:
                d = oa.distance(outline(b)) * 72 / fig.dpi
                if d < gap:
                    out.append((a.get_text(), b.get_text(), round(d, 2)))
    return out


def leaders_crossing_labels(fig) -> list:
    """Leader lines (from a label far from its anchor) that cross another label's box."""
    from shapely.geometry import LineString
    r = fig.canvas.get_renderer()
    s = 0.3 * fig.dpi / 72
    out = []
    for ax in fig.axes:
        texts = [t for t in ax.texts if (t.get_gid() or "").startswith(("label-", "link-number-", "driver-label",
                                                                         "scale-bar", "kennedy-label-"))]
        boxes = []
        for t in texts:
            bb = t.get_window_extent(r)
            boxes.append((t, box(bb.x0 + s, bb.y0 + s, bb.x1 - s, bb.y1 - s)))
        for t in texts:
            ld = getattr(placer(ax).of(t), "leader", None)
            if ld is None or ld.axes is None:
                continue
            line = LineString(ax.transData.transform(ld.get_xydata()))
            out += [(t.get_text(), o.get_text()) for o, b in boxes if o is not t and line.intersects(b)]
    return out
